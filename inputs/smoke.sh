#!/usr/bin/env bash
# Runs every deck of inputs/smoke.txt for a few steps in Debian's LIGGGHTS (or PROGRAM), each
# folder copied to a scratch directory; exits non-zero at the first run that fails. Skipped,
# with a note, when the program is not installed.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
program="${PROGRAM:-liggghts}"
if ! command -v "$program" >/dev/null; then
    echo "inputs/smoke.sh: $program not found, skipped"
    exit 0
fi
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
n=0
while read -r folder deck vars; do
    case "$folder" in '' | '#'*) continue ;; esac
    [ -d "$scratch/$folder" ] || cp -r "$here/$folder" "$scratch/$folder"
    args=()
    set -- $vars
    while [ $# -ge 2 ]; do args+=(-var "$1" "$2"); shift 2; done
    if ! (cd "$scratch/$folder" && "$program" -in "$deck" "${args[@]}" -log log.smoke \
        > /dev/null 2>&1); then
        echo "inputs/smoke.sh: $folder/$deck $vars failed in $program:" >&2
        tail -5 "$scratch/$folder/log.smoke" >&2 || true
        exit 1
    fi
    n=$((n + 1))
done < "$here/smoke.txt"
echo "inputs/smoke.sh: $n runs of the inputs/ decks passed in $program"
