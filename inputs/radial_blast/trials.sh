#!/usr/bin/env bash
# The study's six ring trials at full size (RRHH RSHH SRHH SSHH SSHL SSSL), one packing each
# (SEEDS="p1 p2 p3" for more), then `regolith analyze ring` compares them. Each trial is a
# long run (2.8e5 spheres, 3.3e6 steps: days of CPU time).
# Environment: PROGRAM (regolith or liggghts; default regolith on PATH), WORK (default
# ./trials), TRIALS, SEEDS, and VARS (extra -var pairs, e.g. VARS="-var blast 1000").
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
program="${PROGRAM:-regolith}"
analyzer="${ANALYZER:-regolith}"
work="${WORK:-$PWD/trials}"
sets=()
for trial in ${TRIALS:-RRHH RSHH SRHH SSHH SSHL SSSL}; do
    for seed in ${SEEDS:-49979687}; do
        dir="$work/${trial}_$seed"
        mkdir -p "$dir"
        cp "$here/in.radial_blast" "$dir/"
        echo "$trial, seed $seed"
        # shellcheck disable=SC2086
        (cd "$dir" && "$program" -in in.radial_blast -var trial "$trial" -var seed "$seed" ${VARS:-} \
            -log log.liggghts > screen.txt)
        sets+=(--set "$trial" "$dir/post/ring_*.dump")
    done
done
"$analyzer" analyze ring --log "$dir/log.liggghts" --out "$work/analysis" "${sets[@]}"
