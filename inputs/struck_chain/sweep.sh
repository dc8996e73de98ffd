#!/usr/bin/env bash
# The study's struck-chain sweep at full scale: soft and steel beads, 40 layers, v_im from 1e-6
# to 10 m/s. Each run lasts about 1.5 crossings of the column at the expected speed (soft
# 3.5, steel 140 m/s at v_im 1e-3, times (v_im / 1e-3)^0.2) with 200 dumps; then
# `regolith analyze chain` gives c_w per run and, per material, c_w against v_im (exponent,
# weak-impact speed, impacts above the Hertz elastic limit flagged). Steel runs take hours to
# days; MATERIALS="soft" runs the soft sweep alone (under an hour).
# Environment: PROGRAM (regolith or liggghts; default regolith on PATH), WORK (default
# ./sweep), MATERIALS ("soft steel"), SPEEDS.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
program="${PROGRAM:-regolith}"
analyzer="${ANALYZER:-regolith}"
work="${WORK:-$PWD/sweep}"
speeds="${SPEEDS:-1e-6 1e-5 1e-4 1e-3 1e-2 0.1 1 10}"
for material in ${MATERIALS:-soft steel}; do
    case $material in soft) c3=3.5 dt=1e-6 ;; steel) c3=140 dt=1e-10 ;; esac
    sets=()
    for v in $speeds; do
        dir="$work/$material/vim_$v"
        mkdir -p "$dir"
        cp "$here/in.struck_chain" "$dir/"
        read -r nsteps dn < <(awk -v v="$v" -v c3="$c3" -v dt="$dt" 'BEGIN {
            c = c3 * (v / 1e-3) ^ 0.2; s = int(1.5 * 40 * 0.02064 / c / dt); print s, int(s / 200) }')
        echo "$material, v_im $v m/s: $nsteps steps"
        (cd "$dir" && "$program" -in in.struck_chain -var material "$material" -var vim "$v" \
            -var nsteps "$nsteps" -var dN "$dn" -log log.liggghts > screen.txt)
        sets+=(--set "$v" "$dir/post/chain_*.dump")
    done
    "$analyzer" analyze chain --material "$material" --dt "$dt" --out "$work/$material/analysis" "${sets[@]}"
done
