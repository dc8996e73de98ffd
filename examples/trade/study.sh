#!/usr/bin/env bash
# The speed/accuracy trade study: small scenes with known answers, each run by `regolith sweep`
# along three axes, and the results as tables and figures.
#
# Scenes (decks in this folder; each also runs in Debian's LIGGGHTS):
#   collision     in.collision (e 0.5): restitution e and contact time tc
#   elastic       in.collision -var e 1: energy drift, kinetic energy after over before minus 1
#                 (measured absolutely: its exact value is 0)
#   slide         in.slide: rolling speed v_roll (5/7 v0) and sliding time t_roll
#   chain_weak    in.chain -var vim 1e-4: wave speed c_w of a struck chain of soft beads
#   chain_strong  in.chain -var vim 1: the same at a strong impact
# Axes:
#   dt      dt from 0.5 % to 40 % of the Rayleigh time (-var frac), on the exact and the fast
#           path (-sf fast); errors against the exact path at 0.1 %
#   neigh   neighbour skin 0.01 .. 0.5 diameters, neigh_modify every 1 or 10, check yes or
#           no, at dt = 20 % of the Rayleigh time; errors against skin 0.1, every 1, check yes
#   soften  Young's modulus divided by 10 and 100 (-var soften), at dt = 20 % of the softened
#           material's Rayleigh time; errors against the material's own modulus
# Every sweep runs one deck at a time (--jobs 1): wall times are those of a quiet core only if
# the machine is quiet, so the tables and figures rank cost by steps (deterministic: a run's
# steps, as 1 / dt for a fixed simulated time); the wall times are in each sweep's CSV.
#
#   examples/trade/study.sh            run the sweeps, then write the report
#   examples/trade/study.sh runs       only the sweeps
#   examples/trade/study.sh report     only the report, from the sweeps' CSV files
# Environment: REGOLITH (default the release build), WORK (default examples/trade/study),
# SCENES (the scenes to run; default all: the report always reads all of them).
# Writes WORK/<axis>_<scene>/ (sweep.csv, sweep.png, summary.txt; the runs' folders are
# removed), WORK/report/<axis>/ (trade.md, trade.png) and, in the repository, docs/trade.md,
# docs/figures/trade_{dt,neigh,soften}.png (the dt figure shows the exact path only) and
# docs/trade_margin.csv (the errors along the dt axis, which `regolith check` and the run
# header quote: the file is compiled into regolith).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
regolith="${REGOLITH:-$root/target/release/regolith}"
[ -x "$regolith" ] || (cd "$root" && cargo build --release)
work="${WORK:-$here/study}"
phase="${1:-all}"
fracs="0.005,0.01,0.02,0.05,0.1,0.2,0.3,0.4"
all_scenes="collision elastic slide chain_weak chain_strong"
start=$SECONDS

# the deck and observables of a scene
scene() {
    case "$1" in
    collision) echo "$here/in.collision --observe e=v_e_meas --observe tc=v_tc" ;;
    elastic) echo "$here/in.collision --set e 1 --observe drift=v_drift --expect drift=0" ;;
    slide) echo "$here/in.slide --observe v_roll=v_v_roll --observe t_roll=v_t_roll" ;;
    chain_weak) echo "$here/in.chain --set vim 1e-4 --observe c_w=analyze:chain:c_w" ;;
    chain_strong) echo "$here/in.chain --set vim 1 --observe c_w=analyze:chain:c_w" ;;
    esac
}

sweep() {
    local name="$1"
    shift
    echo "== $name"
    nice -n 10 "$regolith" sweep "$@" --jobs 1 --out "$work/$name" > "$work/$name.txt"
    cat "$work/$name.txt"
    rm -rf "$work/$name/runs"
}

if [ "$phase" = all ] || [ "$phase" = runs ]; then
    mkdir -p "$work"
    for s in ${SCENES:-$all_scenes}; do
        # shellcheck disable=SC2046
        sweep "dt_$s" $(scene "$s") --var frac "$fracs" --var sf off,fast \
            --reference frac=0.001,sf=off
        # shellcheck disable=SC2046
        sweep "neigh_$s" $(scene "$s") --set frac 0.2 --var skin 0.01,0.05,0.1,0.5 \
            --var every 1,10 --var check yes,no --reference skin=0.1,every=1,check=yes
        # shellcheck disable=SC2046
        sweep "soften_$s" $(scene "$s") --set frac 0.2 --var soften 1,10,100
    done
fi

if [ "$phase" = all ] || [ "$phase" = report ]; then
    report="$work/report"
    for axis in dt neigh soften; do
        title="trade study, $axis axis"
        dirs=()
        for s in $all_scenes; do dirs+=("$work/${axis}_$s"); done
        "$regolith" sweep --merge "${dirs[@]}" --cost steps --title "$title" \
            --out "$report/$axis" > /dev/null
        cp "$report/$axis/trade.png" "$root/docs/figures/trade_$axis.png"
    done
    # the time step's figure: the exact path only (the fast path's errors were the same)
    dirs=()
    for s in $all_scenes; do
        mkdir -p "$report/exact/$s"
        awk -F, 'NR == 1 { for (c = 1; c <= NF; c++) if ($c == "sf") k = c }
                 NR == 1 || $k != "fast"' "$work/dt_$s/sweep.csv" > "$report/exact/$s/sweep.csv"
        dirs+=("$report/exact/$s")
    done
    "$regolith" sweep --merge "${dirs[@]}" --cost steps --title "trade study, exact path" \
        --out "$report/dt_exact" > /dev/null
    cp "$report/dt_exact/trade.png" "$root/docs/figures/trade_dt.png"
    # the dt axis's errors, for `regolith check` and the run header
    {
        echo "scene,observable,path,frac,error,absolute"
        for s in $all_scenes; do
            awk -F, -v scene="$s" '
                NR == 1 {
                    for (c = 1; c <= NF; c++) {
                        h[$c] = c
                        if ($c ~ /_relerr$/) { name[c] = substr($c, 1, length($c) - 7); abs[c] = 0 }
                        if ($c ~ /_abserr$/) { name[c] = substr($c, 1, length($c) - 7); abs[c] = 1 }
                    }
                    next
                }
                $(h["status"]) == "ok" {
                    path = $(h["sf"]) == "fast" ? "fast" : "exact"
                    for (c in name) printf "%s,%s,%s,%s,%s,%s\n", scene, name[c], path, $(h["frac"]), $c, abs[c]
                }' "$work/dt_$s/sweep.csv" | sort -t, -k2,2 -k3,3 -k4,4g
        done
    } > "$root/docs/trade_margin.csv"
    # the summary: the exact path's errors along the dt axis (the fast path's are in the
    # full tables below), one row per observable
    summary="$(
        awk -F, -v fracs="$fracs" '
            BEGIN {
                nf = split(fracs, f, ",")
                label["collision,e"] = "collision: restitution e"
                label["collision,tc"] = "collision: contact time"
                label["elastic,drift"] = "elastic collision (e = 1): energy drift (absolute)"
                label["slide,v_roll"] = "sliding sphere: rolling speed (5/7 v0)"
                label["slide,t_roll"] = "sliding sphere: sliding time"
                label["chain_weak,c_w"] = "struck chain, v_im 1e-4 m/s: wave speed"
                label["chain_strong,c_w"] = "struck chain, v_im 1 m/s: wave speed"
            }
            NR == 1 || $3 != "exact" { next }
            {
                key = $1 "," $2
                if (!(key in seen)) { seen[key] = 1; order[++n] = key }
                p = 100 * $5
                if ($6 == 1) cell = sprintf("%.2g", $5)
                else if (p < 0.001) cell = "< 0.001 %"
                else if (p >= 10) cell = sprintf("%.0f %%", p)
                else cell = sprintf("%.2g %%", p)
                err[key, $4] = cell
            }
            END {
                printf "| observable (error) |"
                for (i = 1; i <= nf; i++) printf " %g %% |", 100 * f[i]
                printf "\n|---|"
                for (i = 1; i <= nf; i++) printf "---|"
                printf "\n"
                for (k = 1; k <= n; k++) {
                    key = order[k]
                    printf "| %s |", (key in label) ? label[key] : key
                    for (i = 1; i <= nf; i++) printf " %s |", err[key, f[i]]
                    printf "\n"
                }
                printf "| cost: steps per simulated time, relative to 0.5 %% |"
                for (i = 1; i <= nf; i++) printf " %s |", (i == 1) ? "1" : sprintf("1/%g", f[i] / f[1])
                printf "\n"
            }' "$root/docs/trade_margin.csv"
    )"
    {
        echo "# Speed/accuracy trade study"
        echo
        echo "Written by \`examples/trade/study.sh\` (see its header for the scenes and axes)."
        echo "Each cell is an observable's error against its sweep's reference run (relative, in"
        echo "percent; absolute where marked): \`ref\` is the reference itself, \`blow-up\` a run"
        echo "that stopped. The \`steps\` rows are the cost (a run's steps; deterministic), the"
        echo "\`wall (s)\` rows the wall time of each run on the machine that ran the study."
        echo
        echo "## Summary: error against dt (as % of the Rayleigh time), exact path"
        echo
        echo "Errors against the exact path at 0.1 % of the Rayleigh time; the fast path's are"
        echo "the same (below)."
        echo
        echo "$summary"
        echo
        echo "## Time step (dt as a fraction of the Rayleigh time), exact and fast path"
        echo
        echo "Reference: the exact path at 0.1 % of the Rayleigh time."
        echo
        cat "$report/dt/trade.md"
        echo
        echo "## Neighbour skin (diameters) and neigh_modify every/check, at dt = 20 % of the Rayleigh time"
        echo
        echo "Reference: skin 0.1, every 1, check yes."
        echo
        cat "$report/neigh/trade.md"
        echo
        echo "## Young's modulus divided by 10 and 100, at dt = 20 % of the softened Rayleigh time"
        echo
        echo "Reference: the material's own modulus (soften 1)."
        echo
        cat "$report/soften/trade.md"
    } > "$root/docs/trade.md"
fi
echo "study time: $((SECONDS - start)) s"
