#!/usr/bin/env bash
# Times the study scenes end to end in Debian's LIGGGHTS, regolith's exact path (one thread)
# and its fast path (one and two threads), interleaved, and writes docs/scenes.md:
#   struck chain (1 001 soft beads, 300 000 steps), lunar channel bed (pour, trim, settle),
#   P-wave shock on that bed, radial blast in a granular ring.
#   apt-get install -y liggghts          (for the LIGGGHTS column)
#   benches/scenes.sh                    (REPEAT=3 for medians of three runs)
# The decks run in a scratch copy of examples/. Run it on an otherwise idle machine.
set -euo pipefail
cd "$(dirname "$0")/.."
REPEAT=${REPEAT:-1}
cargo build --release --quiet
bin=$PWD/target/release/regolith
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp -r examples/struck_chain examples/lunar_channel examples/radial_blast "$work"/
ligg=()
if command -v liggghts >/dev/null; then ligg=(--liggghts); fi
out=docs/scenes.md
mkdir -p docs
{
    echo "# Study scenes: regolith against Debian's LIGGGHTS"
    echo
    echo "Made by \`benches/scenes.sh\` (REPEAT=$REPEAT); loop time summed over each deck's runs."
    for deck in struck_chain/in.struck_chain lunar_channel/in.lunar_channel \
        lunar_channel/in.shock radial_blast/in.radial_blast; do
        echo
        echo "## $deck"
        echo
        report=$("$bin" bench "$work/$deck" --exact --fast --threads 1,2 "${ligg[@]}" --repeat "$REPEAT")
        echo '```'
        sed '/^$/,$d' <<<"$report"
        echo '```'
        echo
        sed '1,/^$/d' <<<"$report"
    done
} > "$out.tmp"
mv "$out.tmp" "$out"
cat "$out"
