#!/usr/bin/env bash
# The struck-chain sweep (SCENES.md, scene A), scaled: soft beads, a 5 x 5 x 20 column, impact
# speeds v_im from 1e-6 to 1 m/s (faster impacts on these soft beads overlap by more than half
# a radius). Each run lasts about 1.5 crossings of the column at the expected speed
# (3.2 (v_im / 1e-3 m/s)^0.2 m/s) with 150 dumps; then `regolith analyze chain` fits c_w per run
# and c_w against v_im over the sweep.
#
#   examples/struck_chain/study.sh                      regolith runs the decks
#   PROGRAM=liggghts examples/struck_chain/study.sh     Debian's LIGGGHTS runs them
# Environment: PROGRAM (default the release build of regolith), WORK (default
# examples/struck_chain/study), SPEEDS, NLAYERS (20). Writes WORK/analysis/ (tables, figures)
# and, for regolith's runs, docs/figures/struck_chain_sweep.png.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
regolith="$root/target/release/regolith"
[ -x "$regolith" ] || (cd "$root" && cargo build --release)
program="${PROGRAM:-$regolith}"
work="${WORK:-$here/study}"
nlayers="${NLAYERS:-20}"
speeds="${SPEEDS:-1e-6 1e-5 1e-4 1e-3 1e-2 0.1 1}"
start=$SECONDS
sets=()
for v in $speeds; do
    dir="$work/vim_$v"
    rm -rf "$dir"
    mkdir -p "$dir"
    cp "$here/in.struck_chain" "$dir/"
    read -r nsteps dn < <(awk -v v="$v" -v n="$nlayers" 'BEGIN {
        c = 3.2 * (v / 1e-3) ^ 0.2; s = int(1.5 * n * 0.02064 / c / 1e-6); print s, int(s / 150) }')
    echo "v_im $v m/s: $nsteps steps"
    (cd "$dir" && nice -n 19 "$program" -in in.struck_chain -var vim "$v" -var nlayers "$nlayers" \
        -var nsteps "$nsteps" -var dN "$dn" -log log.liggghts > screen.txt)
    sets+=(--set "$v" "$dir/post/chain_*.dump")
done
"$regolith" analyze chain --dt 1e-6 --out "$work/analysis" "${sets[@]}" | tee "$work/summary.txt"
if [ "$program" = "$regolith" ]; then
    cp "$work/analysis/chain_sweep.png" "$root/docs/figures/struck_chain_sweep.png"
fi
echo "study time: $((SECONDS - start)) s"
