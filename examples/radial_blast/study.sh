#!/usr/bin/env bash
# The scaled radial blast (SCENES.md, scene C): rough against smooth walls. Trials RRHH (wall
# friction 0.3, wall rolling friction 0.3) and RSHH (0.1, 0.01), same particles, three packings
# each (insertion seeds); then `regolith analyze ring` measures each run (surface radii,
# corrugation, compaction front, force spectrum) and compares the trials (mean and spread over
# the seeds).
#
#   examples/radial_blast/study.sh                      regolith runs the decks
#   PROGRAM=liggghts examples/radial_blast/study.sh     Debian's LIGGGHTS runs them
# Environment: PROGRAM (default the release build of regolith), WORK (default
# examples/radial_blast/study), TRIALS ("RRHH RSHH"), SEEDS (three primes), BLAST (blast
# steps, 120000 = 180 us), KEEP=1 keeps the dumps, RESUME=1 keeps finished runs. Writes
# WORK/analysis/ and, for regolith's runs, docs/figures/radial_blast_*.png. About 6 minutes per
# run on an idle core here (2500 spheres, 1.4e5 steps).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
regolith="$root/target/release/regolith"
[ -x "$regolith" ] || (cd "$root" && cargo build --release)
program="${PROGRAM:-$regolith}"
work="${WORK:-$here/study}"
trials="${TRIALS:-RRHH RSHH}"
seeds="${SEEDS:-49979687 49979693 49979737}"
blast="${BLAST:-120000}"
start=$SECONDS
sets=()
# seeds outer, so that an interrupted study has both trials for the seeds it finished; a run
# whose folder holds a `done` mark is not run again (RESUME=1 keeps finished runs)
for seed in $seeds; do
    for trial in $trials; do
        dir="$work/${trial}_$seed"
        if [ "${RESUME:-0}" = 1 ] && [ -e "$dir/done" ]; then
            sets+=(--set "$trial" "$dir/post/ring_*.dump")
            continue
        fi
        rm -rf "$dir"
        mkdir -p "$dir"
        cp "$here/in.radial_blast" "$dir/"
        echo "$trial, seed $seed"
        if (cd "$dir" && nice -n 19 "$program" -in in.radial_blast -var trial "$trial" -var seed "$seed" \
            -var blast "$blast" -log log.liggghts > screen.txt); then
            touch "$dir/done"
            sets+=(--set "$trial" "$dir/post/ring_*.dump")
        else
            echo "  failed: see $dir/log.liggghts"
        fi
    done
done
"$regolith" analyze ring --dt 1.5e-9 --out "$work/analysis" "${sets[@]}" | tee "$work/summary.txt"
if [ "$program" = "$regolith" ]; then
    cp "$work/analysis/ring_trials.png" "$root/docs/figures/radial_blast_trials.png"
    first="$(echo $trials | cut -d' ' -f1)"
    cp "$work/analysis/${first}_run1_ring_radii.png" "$root/docs/figures/radial_blast_radii.png"
    cp "$work/analysis/${first}_run1_ring_spectrum.png" "$root/docs/figures/radial_blast_spectrum.png"
fi
[ "${KEEP:-0}" = 1 ] || find "$work" -name 'ring_*.dump' -delete
echo "study time: $((SECONDS - start)) s"
