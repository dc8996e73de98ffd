#!/usr/bin/env bash
# Rebuilds every committed reference output under compat/ with Debian's LIGGGHTS 3.8.0.
#   apt-get install -y liggghts liggghts-doc
# Each section is a function; later sections (engine dumps, restarts) add their own.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"

if ! command -v liggghts >/dev/null; then
    echo "liggghts not found: apt-get install -y liggghts liggghts-doc" >&2
    exit 1
fi

# Script-language decks: compat/script/in.NAME, side files in compat/script/NAME.inputs/.
# References: NAME.out (stdout without the banner line), NAME.status (exit status),
# NAME.log (log file without the banner line) and NAME.files/ (every file the deck wrote).
script_references() {
    local dir="$here/script"
    for deck in "$dir"/in.*; do
        local name="${deck##*/in.}"
        local work
        work="$(mktemp -d)"
        cp "$deck" "$work/"
        if [ -d "$dir/$name.inputs" ]; then cp -r "$dir/$name.inputs/." "$work/"; fi
        local status=0
        (cd "$work" && env -u REGOLITH_COMPAT_SET liggghts -in "in.$name" -log log.txt \
            > stdout.txt 2> /dev/null) || status=$?
        tail -n +2 "$work/stdout.txt" | tr -d '\000' > "$dir/$name.out"
        echo "$status" > "$dir/$name.status"
        if [ -f "$work/log.txt" ]; then tail -n +2 "$work/log.txt" | tr -d '\000' > "$dir/$name.log"; else rm -f "$dir/$name.log"; fi
        rm -rf "$dir/$name.files"
        (
            cd "$work"
            rm -f stdout.txt log.txt "in.$name"
            if [ -d "$dir/$name.inputs" ]; then
                (cd "$dir/$name.inputs" && find . -type f) | while read -r f; do rm -f "$f"; done
            fi
            find . -type d -empty -delete
            if [ -n "$(find . -mindepth 1 -print -quit)" ]; then
                mkdir -p "$dir/$name.files"
                cp -r . "$dir/$name.files/"
            fi
        )
        rm -rf "$work"
        echo "script/$name: status $status"
    done
}

# Engine decks: compat/engine/in.NAME (side files in NAME.inputs/). References in NAME.ref/:
# every file the deck writes (dumps) and thermo.txt, the thermo lines of its runs.
engine_references() {
    local dir="$here/engine"
    for deck in "$dir"/in.*; do
        local name="${deck##*/in.}"
        local work
        work="$(mktemp -d)"
        cp "$deck" "$work/"
        if [ -d "$dir/$name.inputs" ]; then cp -r "$dir/$name.inputs/." "$work/"; fi
        local status=0
        (cd "$work" && liggghts -in "in.$name" -log none > stdout.txt 2> /dev/null) || status=$?
        rm -rf "$dir/$name.ref"
        mkdir -p "$dir/$name.ref"
        tr -d '\000' < "$work/stdout.txt" | awk '
            /^Loop time/ { inrun = 0 }
            inrun { print }
            /^ *Step / { inrun = 1; print }' > "$dir/$name.ref/thermo.txt"
        (
            cd "$work"
            rm -f stdout.txt "in.$name"
            if [ -d "$dir/$name.inputs" ]; then
                (cd "$dir/$name.inputs" && find . -type f) | while read -r f; do rm -f "$f"; done
            fi
            cp -r . "$dir/$name.ref/"
        )
        rm -rf "$work"
        echo "engine/$name: status $status"
    done
}

[ "${1:-all}" = engine ] || script_references
[ "${1:-all}" = script ] || engine_references
