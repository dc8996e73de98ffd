#!/usr/bin/env bash
# Every stage of the lunar channel study at full size: the bed (pour, trim, settle, optional
# tapping: TAP steps), then from its restart file the shock runs: P waves at the piston speeds
# SPEEDS, an S wave, the piston variants (thin strip, top half, bottom half, two colliding
# waves) and a P wave without the frozen floor, all at VREF; then `regolith analyze channel`.
# Days of CPU time per run (0.54 million particles, 1.5 million steps).
# Environment: PROGRAM (regolith or liggghts; default regolith on PATH), WORK (default
# ./study), SEED, TAP (0), SPEEDS ("0.01 0.03 0.1 0.3 1 3 10"), VREF (1), VARS (extra -var
# pairs for the shock runs, e.g. VARS="-var early 200 -var late 200").
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
program="${PROGRAM:-regolith}"
analyzer="${ANALYZER:-regolith}"
work="${WORK:-$PWD/study}"
vref="${VREF:-1}"
mkdir -p "$work/bed"
cp -r "$here/in.lunar_channel" "$here/meshes" "$work/bed/"
(cd "$work/bed" && "$program" -in in.lunar_channel -var seed "${SEED:-49979687}" -var tap "${TAP:-0}" \
    -log log.liggghts > screen.txt)
bed="$work/bed/post/bed.restart"
run() { # name vars...
    local name="$1"
    shift
    mkdir -p "$work/$name"
    cp "$here/in.shock" "$work/$name/"
    echo "$name"
    # shellcheck disable=SC2086
    (cd "$work/$name" && "$program" -in in.shock -var bed "$bed" "$@" ${VARS:-} -log log.liggghts > screen.txt)
}
p_sets=()
for v in ${SPEEDS:-0.01 0.03 0.1 0.3 1 3 10}; do
    run "P_$v" -var vp "$v"
    p_sets+=(--set "$v" "$work/P_$v/post/shock_*.dump")
done
run "S_$vref" -var vp "$vref" -var wave S
for piston in strip top bottom both; do
    run "${piston}_$vref" -var vp "$vref" -var piston "$piston"
done
run "free_$vref" -var vp "$vref" -var floor free
"$analyzer" analyze channel --log "$work/P_$vref/log.liggghts" --out "$work/analysis/P" "${p_sets[@]}"
for name in "S_$vref" "strip_$vref" "top_$vref" "bottom_$vref" "both_$vref" "free_$vref"; do
    "$analyzer" analyze channel --log "$work/$name/log.liggghts" --out "$work/analysis/$name" \
        "$work/$name/post/shock_*.dump"
done
