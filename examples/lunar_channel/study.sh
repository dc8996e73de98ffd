#!/usr/bin/env bash
# The scaled lunar channel (SCENES.md, scene B): three beds (insertion seeds), each shocked by
# P-wave pistons at several speeds, an S wave (the sheet moving on after its period, and
# stopped) and a P wave without the frozen floor; then
# `regolith analyze channel` measures each run (c_w, c_p, dilation) and the sweep (mean and
# spread over the seeds).
#
#   examples/lunar_channel/study.sh                      regolith runs the decks
#   PROGRAM=liggghts examples/lunar_channel/study.sh     Debian's LIGGGHTS runs them
# Environment: PROGRAM (default the release build of regolith), WORK (default
# examples/lunar_channel/study), SEEDS (three primes), SPEEDS (P-wave piston speeds, m/s),
# VREF (the speed of the S-wave and free-floor runs, 1 m/s), EARLY/D1 (steps and dump interval
# of the first 25 ms), LATE/D2 (then, until 0.3 s), KEEP=1 keeps the dumps. Writes
# WORK/analysis/ and, for regolith's runs, docs/figures/lunar_channel_*.png.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
regolith="$root/target/release/regolith"
[ -x "$regolith" ] || (cd "$root" && cargo build --release)
program="${PROGRAM:-$regolith}"
work="${WORK:-$here/study}"
seeds="${SEEDS:-49979687 49979693 49979737}"
speeds="${SPEEDS:-0.03 0.1 0.3 1 3}"
vref="${VREF:-1}"
early="${EARLY:-2500}" d1="${D1:-25}" late="${LATE:-27500}" d2="${D2:-1000}"
start=$SECONDS
p_sets=() s_sets=() srest_sets=() free_sets=()

shock() { # folder bed vars...
    local dir="$1" bed="$2"
    shift 2
    rm -rf "$dir"
    mkdir -p "$dir"
    cp "$here/in.shock" "$dir/"
    (cd "$dir" && nice -n 19 "$program" -in in.shock -var bed "$bed" -var early "$early" \
        -var d1 "$d1" -var late "$late" -var d2 "$d2" -var dc 100000000 "$@" \
        -log log.liggghts > screen.txt) || { echo "  failed: see $dir/log.liggghts"; return 1; }
}

for seed in $seeds; do
    bed="$work/bed_$seed"
    rm -rf "$bed"
    mkdir -p "$bed"
    cp -r "$here/in.lunar_channel" "$here/meshes" "$bed/"
    echo "bed $seed"
    (cd "$bed" && nice -n 19 "$program" -in in.lunar_channel -var seed "$seed" -log log.liggghts > screen.txt)
    for v in $speeds; do
        echo "  P wave, v_p $v m/s"
        shock "$bed/P_$v" "$bed/post/bed.restart" -var vp "$v" || continue
        p_sets+=(--set "$v" "$bed/P_$v/post/shock_*.dump")
    done
    echo "  S wave, v_p $vref m/s"
    shock "$bed/S_$vref" "$bed/post/bed.restart" -var vp "$vref" -var wave S &&
        s_sets+=(--set "$vref" "$bed/S_$vref/post/shock_*.dump")
    echo "  S wave stopped after its period, v_p $vref m/s"
    shock "$bed/Srest_$vref" "$bed/post/bed.restart" -var vp "$vref" -var wave S -var send rest &&
        srest_sets+=(--set "$vref" "$bed/Srest_$vref/post/shock_*.dump")
    echo "  P wave, free floor, v_p $vref m/s"
    shock "$bed/free_$vref" "$bed/post/bed.restart" -var vp "$vref" -var floor free &&
        free_sets+=(--set "$vref" "$bed/free_$vref/post/shock_*.dump")
done

analysis="$work/analysis"
for kind in P S Srest free; do
    case $kind in
        P) sets=("${p_sets[@]}") ;;
        S) sets=("${s_sets[@]}") ;;
        Srest) sets=("${srest_sets[@]}") ;;
        free) sets=("${free_sets[@]}") ;;
    esac
    echo "== $kind"
    "$regolith" analyze channel --dt 1e-5 --out "$analysis/$kind" "${sets[@]}"
done | tee "$work/summary.txt"
if [ "$program" = "$regolith" ]; then
    cp "$analysis/P/channel_sweep.png" "$root/docs/figures/lunar_channel_sweep.png"
    for f in arrival dilation panels overlap; do
        # the first bed's run at v_p = 1 m/s (the fourth P run)
        cp "$analysis/P/run4_channel_$f.png" "$root/docs/figures/lunar_channel_$f.png" 2>/dev/null || true
    done
fi
[ "${KEEP:-0}" = 1 ] || find "$work" -name 'shock_*.dump' -delete
echo "study time: $((SECONDS - start)) s"
