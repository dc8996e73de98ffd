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

# Script-language decks (tests/compat_script.rs compares regolith against these).
#   compat/script/in.NAME          the deck; run as `liggghts -in <absolute path> -log none -echo none`
#                                  in a fresh empty directory, environment without REGOLITH_COMPAT_*
#   compat/script/NAME.inputs/     optional side files, copied into that directory first
# References written here:
#   NAME.out     stdout minus the banner line; cut after the first line starting with ERROR
#                (LIGGGHTS follows it with a random "tip of the day" from a dangling pointer)
#   NAME.status  exit status (error->all, error->one and quit all give 1)
#   NAME.files/  every file the deck created or changed in its directory (log, print, shell)
# Decks named err_* end in a LIGGGHTS error. stdout is line-buffered (stdbuf -oL), as on a
# terminal: otherwise MPI_Abort (error->one) loses buffered output and output of `shell`
# subprocesses lands before earlier prints.
script_references() {
    local dir="$here/script"
    command -v stdbuf >/dev/null || { echo "stdbuf (coreutils) not found" >&2; exit 1; }
    local compat_vars=()
    mapfile -t compat_vars < <(env | sed -n 's/^\(REGOLITH_COMPAT_[A-Za-z0-9_]*\)=.*/-u\n\1/p')
    # start from scratch (deck names must not end in .out, .status, .files or .inputs)
    find "$dir" -maxdepth 1 -type f \( -name '*.out' -o -name '*.status' \) ! -name 'in.*' -delete
    find "$dir" -maxdepth 1 -type d -name '*.files' ! -name 'in.*' -exec rm -rf {} +
    local deck
    for deck in "$dir"/in.*; do
        local name="${deck##*/in.}"
        local work
        work="$(mktemp -d)"
        if [ -d "$dir/$name.inputs" ]; then cp -r "$dir/$name.inputs/." "$work/"; fi
        local status=0
        (cd "$work" && env "${compat_vars[@]}" stdbuf -oL liggghts -in "$deck" -log none -echo none \
            > "$work.stdout" 2> /dev/null) || status=$?
        tail -n +2 "$work.stdout" | tr -d '\000' | awk 'cut { next } { print } /^ERROR/ { cut = 1 }' > "$dir/$name.out"
        rm -f "$work.stdout"
        echo "$status" > "$dir/$name.status"
        (
            cd "$work"
            # keep what the deck created or changed; drop untouched side files and empty dirs
            if [ -d "$dir/$name.inputs" ]; then
                (cd "$dir/$name.inputs" && find . -type f) | while read -r f; do
                    if cmp -s "$f" "$dir/$name.inputs/$f"; then rm -f "$f"; fi
                done
            fi
            find . -mindepth 1 -type d -empty -delete
            if [ -n "$(find . -mindepth 1 -print -quit)" ]; then
                mkdir -p "$dir/$name.files"
                cp -r . "$dir/$name.files/"
            fi
        )
        rm -rf "$work"
        echo "script/$name: status $status"
    done
}

# Engine decks (`regenerate.sh engine [NAME]` rebuilds one): compat/engine/in.NAME (side files in NAME.inputs/). References in NAME.ref/:
# every file the deck writes (dumps) and thermo.txt, the thermo lines of its runs.
engine_references() {
    local dir="$here/engine"
    for deck in "$dir"/in.${2:-*}; do
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
                find . -mindepth 1 -type d -empty -delete
            fi
            cp -r . "$dir/$name.ref/"
        )
        # large references are kept gzipped (the test compares them decompressed)
        find "$dir/$name.ref" -type f -size +1M ! -name '*.gz' -exec gzip -n -9 {} \;
        rm -rf "$work"
        echo "engine/$name: status $status"
    done
}

# Restart and data files of one settled bed (tests/convert.rs, engine deck restart_continue):
#   compat/convert/in.make_bed  pours and settles it, then write_restart bed.restart and
#                               write_data bed.data (the same state in both files)
# compat/engine/liggghts_reads.inputs/regolith.restart is regolith's own bed.restart of
# in.make_bed (`regolith -in in.make_bed`); tests/convert.rs keeps it current.
convert_references() {
    local work
    work="$(mktemp -d)"
    cp "$here/convert/in.make_bed" "$work/"
    (cd "$work" && liggghts -in in.make_bed -log none > /dev/null 2>&1)
    cp "$work/bed.restart" "$work/bed.data" "$here/convert/"
    cp "$work/bed.restart" "$here/engine/restart_continue.inputs/bed.restart"
    rm -rf "$work"
    # the shock deck's settled bed (compat/engine/shock.inputs/in.make_bed)
    work="$(mktemp -d)"
    cp "$here/engine/shock.inputs/in.make_bed" "$work/"
    (cd "$work" && liggghts -in in.make_bed -log none > /dev/null 2>&1)
    cp "$work/bed.restart" "$here/engine/shock.inputs/bed.restart"
    rm -rf "$work"
    echo "convert: bed.restart, bed.data"
}

[ "${1:-all}" = engine ] || [ "${1:-all}" = convert ] || script_references
[ "${1:-all}" = engine ] || [ "${1:-all}" = script ] || convert_references
[ "${1:-all}" = script ] || [ "${1:-all}" = convert ] || engine_references "$@"
