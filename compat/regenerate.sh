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

# The thermo lines of a run's screen output: each block from its `Step` header up to (not
# including) `Loop time`, with the lines fixes print during the run.
thermo_lines() {
    tr -d '\000' | awk '
        /^Loop time/ { inrun = 0 }
        inrun { print }
        /^ *Step / { inrun = 1; print }'
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
        thermo_lines < "$work/stdout.txt" > "$dir/$name.ref/thermo.txt"
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
    # the wet bed LIGGGHTS writes for engine deck easo_reads (compat/engine/easo_reads.inputs/in.make_wet)
    work="$(mktemp -d)"
    cp "$here/engine/easo_reads.inputs/in.make_wet" "$work/"
    (cd "$work" && liggghts -in in.make_wet -log none > /dev/null 2>&1)
    cp "$work/wet.restart" "$here/engine/easo_reads.inputs/wet.restart"
    rm -rf "$work"
    # the worn stress mesh LIGGGHTS writes for engine deck stress_reads
    # (compat/engine/stress_reads.inputs/in.make_stress)
    work="$(mktemp -d)"
    cp "$here/engine/stress_reads.inputs/in.make_stress" "$here/engine/stress_reads.inputs/square.stl" "$work/"
    (cd "$work" && liggghts -in in.make_stress -log none > /dev/null 2>&1)
    cp "$work/stress.restart" "$here/engine/stress_reads.inputs/stress.restart"
    rm -rf "$work"
    echo "convert: bed.restart, bed.data"
}

# Official tutorials (`regenerate.sh tutorials [NAME]`, tests/tutorials.rs), listed with their
# probe boxes in compat/tutorials/probes.txt: each deck runs unchanged in a copy of its tutorial
# folder (a deck that reads another's restart file right after that one, in its directory).
# References in compat/tutorials/NAME.ref/: thermo.txt, the thermo lines of its runs, and
# final.txt: the last thermo line's step, atoms and KinEng; and of its last particle dump (the
# largest step among the files of its `dump custom/vtk`, so no `_boundingBox` or mesh files) the
# step, particle count, mean z and the count inside the probe box.
tutorial_references() {
    local dir="$here/tutorials"
    local tutorials="${REGOLITH_TUTORIALS:-/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public}"
    if [ ! -d "$tutorials" ]; then
        echo "no tutorials at $tutorials: apt-get install -y liggghts-doc" >&2
        exit 1
    fi
    local name folder decks box work="" chain="" prev_folder=""
    while read -r name folder decks box; do
        case "$name" in "#"* | "") continue ;; esac
        [ -z "${2:-}" ] || [ "$name" = "$2" ] || continue
        local todo
        if [ -n "$chain" ] && [ "$folder" = "$prev_folder" ] && [ "${decks#"$chain",}" != "$decks" ]; then
            todo="${decks#"$chain",}" # continue in the previous line's directory
        else
            [ -z "$work" ] || rm -rf "$work"
            work="$(mktemp -d)"
            cp -r "$tutorials/$folder/." "$work/"
            todo="$decks"
        fi
        chain="$decks" prev_folder="$folder"
        local deck pattern
        for deck in ${todo//,/ }; do
            pattern="$(awk '$1 == "dump" && $4 == "custom/vtk" { print $6; exit }' "$work/$deck")"
            (cd "$work" && rm -f $pattern && liggghts -in "$deck" -log none > stdout.txt 2> /dev/null) ||
                { echo "tutorials/$name: $deck failed" >&2; exit 1; }
        done
        rm -rf "$dir/$name.ref"
        mkdir -p "$dir/$name.ref"
        thermo_lines < "$work/stdout.txt" > "$dir/$name.ref/thermo.txt"
        (cd "$work" && python3 - "$dir/$name.ref/thermo.txt" "$pattern" ${box%%#*}) <<'EOF' > "$dir/$name.ref/final.txt"
import glob, re, sys
thermo, pattern, box = sys.argv[1], sys.argv[2], [float(v) for v in sys.argv[3:9]]
header, last = None, None
for words in map(str.split, open(thermo)):
    if words[:1] == ["Step"]:
        header = words
    elif header and len(words) == len(header) and all(re.fullmatch(r"[-+.0-9eE]+", w) for w in words):
        last = dict(zip(header, words))
print(f"step {last['Step']}\natoms {last['Atoms']}\nke {last['KinEng']}")
name = re.compile(re.escape(pattern).replace(r"\*", "([0-9]+)"))
step, path = max((int(m[1]), f) for f in glob.glob(pattern) if (m := name.fullmatch(f)))
words = open(path).read().split()
k = words.index("POINTS")
n = int(words[k + 1])
xyz = [tuple(map(float, words[k + 3 + 3 * i : k + 6 + 3 * i])) for i in range(n)]
inside = sum(all(box[2 * a] <= p[a] <= box[2 * a + 1] for a in range(3)) for p in xyz)
print(f"dump_step {step}\ndump_atoms {n}\nmean_z {sum(p[2] for p in xyz) / n:.9g}\nprobe {inside}")
EOF
        echo "tutorials/$name: $(tr '\n' ' ' < "$dir/$name.ref/final.txt")"
    done < "$dir/probes.txt"
    [ -z "$work" ] || rm -rf "$work"
}

# Analysis references (tests/analyze.rs): LIGGGHTS's dumps of a short struck chain
# (examples/struck_chain/in.struck_chain, 10 layers, v_im 0.1 m/s, 30 000 steps, a dump every
# 1 000), concatenated in step order into one gzip file; regolith's run of the same deck must
# give the same wave speed.
analyze_references() {
    local dir="$here/analyze"
    local work
    work="$(mktemp -d)"
    mkdir -p "$dir"
    cp "$here/../examples/struck_chain/in.struck_chain" "$work/"
    (cd "$work" && liggghts -in in.struck_chain -var nlayers 10 -var vim 0.1 -var nsteps 30000 \
        -var dN 1000 -log none -screen none)
    (cd "$work/post" && ls chain_*.dump | sort -t_ -k2 -n | xargs cat) | gzip -9n > "$dir/chain_liggghts.dump.gz"
    rm -rf "$work"
    echo "analyze/chain_liggghts.dump.gz"
}

section="${1:-all}"
case "$section" in all | script | convert | engine | tutorials | analyze) ;; *)
    echo "usage: $0 [script|convert|engine|tutorials|analyze] [NAME]" >&2
    exit 2
    ;;
esac
case "$section" in all | script) script_references ;; esac
case "$section" in all | convert) convert_references ;; esac
case "$section" in all | engine) engine_references "$@" ;; esac
case "$section" in all | tutorials) tutorial_references "$@" ;; esac
case "$section" in all | analyze) analyze_references ;; esac
