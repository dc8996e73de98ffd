#!/usr/bin/env bash
# Reproduces README's speed table and thread plot: the standard beds (10k and 50k lunar-
# material spheres; add 200k with SIZES=10k,50k,200k) at rest and under a 10 m/s piston, three
# contact models, timed in Debian's LIGGGHTS, regolith's exact path (one thread) and its fast
# path (1 and 2 threads), interleaved, medians of REPEAT runs each.
#   apt-get install -y liggghts        (for the LIGGGHTS column)
#   benches/speed_table.sh             (writes docs/speed.md, docs/speed.csv, docs/figures/speed_threads.png)
# The beds are built once (regolith -sf fast -in benches/beds/in.make_bed) into $REGOLITH_BEDS
# or ~/.cache/regolith/beds. Run it on an otherwise idle machine: only ratios measured in one
# run mean anything.
set -euo pipefail
cd "$(dirname "$0")/.."
SIZES=${SIZES:-10k,50k}
REPEAT=${REPEAT:-3}
THREADS=${THREADS:-1,2}
cargo build --release --quiet
mkdir -p docs/figures
ligg=()
if command -v liggghts >/dev/null; then ligg=(--liggghts); fi
./target/release/regolith bench beds --sizes "$SIZES" --models hh,sjkr,epsd --states rest,shock \
    --exact --fast --threads "$THREADS" "${ligg[@]}" --repeat "$REPEAT" \
    --csv docs/speed.csv --plot docs/figures/speed_threads.png > docs/speed.md
cat docs/speed.md
