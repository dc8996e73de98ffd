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
#   bed           in.bed: packing fraction phi and height H of a poured and settled cohesive
#                 bed of lunar material (300 spheres); statistical (the pour is chaotic): a
#                 seed sweep at the reference (spread_bed) measures the run-to-run spread
#   channel       in.channel: front speed c_w (`analyze:channel:c_w`, the first 30 % of the
#                 channel) and surface rise behind the front (`analyze:channel:rise`) of a P
#                 shock (piston 3 m/s) in a scaled lunar channel (1 cm x 10 cm, about 1 100
#                 spheres); every run shocks the same bed, which in.channel_bed pours and
#                 settles once; arrival times are read from dumps, so a sweep of four dump
#                 intervals at 5 % of the Rayleigh time (spread_channel) measures the
#                 sampling's spread (round-off hardly matters here: piston speeds a millionth
#                 apart gave the same c_w and a rise within 0.05 %)
#                 The bed and the channel cost 300 and 1 100 spheres a step: their time-step
#                 axes start at 1 % against a reference at 0.5 % of the Rayleigh time
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
all_scenes="collision elastic slide chain_weak chain_strong bed channel"
seeds="32452867,49979693,67867967"
start=$SECONDS

# the deck and observables of a scene
scene() {
    case "$1" in
    collision) echo "$here/in.collision --observe e=v_e_meas --observe tc=v_tc" ;;
    elastic) echo "$here/in.collision --set e 1 --observe drift=v_drift --expect drift=0" ;;
    slide) echo "$here/in.slide --observe v_roll=v_v_roll --observe t_roll=v_t_roll" ;;
    chain_weak) echo "$here/in.chain --set vim 1e-4 --observe c_w=analyze:chain:c_w" ;;
    chain_strong) echo "$here/in.chain --set vim 1 --observe c_w=analyze:chain:c_w" ;;
    bed) echo "$here/in.bed --observe phi=v_phi --observe H=v_H" ;;
    channel) echo "$here/in.channel --set bed $work/channel_bed/post/channel_bed.restart \
        --observe c_w=analyze:channel:c_w --observe rise=analyze:channel:rise" ;;
    esac
}

# the time-step axis of a scene: its steps and its reference
dt_axis() {
    case "$1" in
    bed | channel) echo "--var frac ${fracs#0.005,} --var sf off,fast --reference frac=0.005,sf=off" ;;
    *) echo "--var frac $fracs --var sf off,fast --reference frac=0.001,sf=off" ;;
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
        if [ "$s" = channel ]; then
            # the channel's bed, poured and settled once (at 5 % of the Rayleigh time)
            mkdir -p "$work/channel_bed"
            (cd "$work/channel_bed" && nice -n 10 "$regolith" -in "$here/in.channel_bed" \
                -log log.liggghts > /dev/null 2> stderr.txt)
        fi
        # shellcheck disable=SC2046
        sweep "dt_$s" $(scene "$s") $(dt_axis "$s")
        # shellcheck disable=SC2046
        sweep "neigh_$s" $(scene "$s") --set frac 0.2 --var skin 0.01,0.05,0.1,0.5 \
            --var every 1,10 --var check yes,no --reference skin=0.1,every=1,check=yes
        # shellcheck disable=SC2046
        sweep "soften_$s" $(scene "$s") --set frac 0.2 --var soften 1,10,100
        if [ "$s" = bed ]; then
            # the run-to-run spread: other seeds at the reference setting
            # shellcheck disable=SC2046
            sweep "spread_bed" $(scene bed) --set frac 0.005 --var seed "$seeds"
        fi
        if [ "$s" = channel ]; then
            # the sampling's spread: dumps every 28, 27, 26 and 25 steps at 5 % of the
            # Rayleigh time
            # shellcheck disable=SC2046
            sweep "spread_channel" $(scene channel) --set frac 0.05 --var ndumps 70,74,77,80
        fi
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
                label["bed,phi"] = "settled cohesive bed: packing fraction (statistical)"
                label["bed,H"] = "settled cohesive bed: height (statistical)"
                label["channel,c_w"] = "lunar channel, piston 3 m/s: front speed"
                label["channel,rise"] = "lunar channel, piston 3 m/s: surface rise"
            }
            NR == 1 || $3 != "exact" { next }
            {
                key = $1 "," $2
                if (!(key in seen)) { seen[key] = 1; order[++n] = key }
                p = 100 * $5
                if ($6 == 1) cell = sprintf("%.2g", $5)
                else if ($5 == 0) cell = "ref"
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
    # the run-to-run spreads: the bed's seeds (spread_bed and dt_bed's reference run, all at
    # 0.5 % of the Rayleigh time on the exact path) and the channel's dump intervals
    # (spread_channel); `spread_stats SCENE NAMES FILES...` prints per observable its runs,
    # mean, standard deviation, the deviation relative to the mean and the largest deviation
    spread_stats() {
        local scene="$1" names="$2"
        shift 2
        for f in "$@"; do
            awk -F, -v names="$names" -v ref="$([ "$f" = "$work/dt_bed/sweep.csv" ] && echo 1)" '
                NR == 1 { for (c = 1; c <= NF; c++) h[$c] = c; nn = split(names, nm, " "); next }
                $(h["status"]) == "ok" && (ref != 1 || $(h["reference"]) == 1) {
                    line = ""
                    for (k = 1; k <= nn; k++) line = line (k > 1 ? " " : "") $(h[nm[k]])
                    print line
                }' "$f"
        done | awk -v scene="$scene" -v names="$names" '
            { n++; for (k = 1; k <= NF; k++) { x[n, k] = $k; s[k] += $k }; nf = NF }
            END {
                split(names, nm, " ")
                for (k = 1; k <= nf; k++) {
                    m = s[k] / n; v = 0; big = 0
                    for (i = 1; i <= n; i++) {
                        dv = x[i, k] - m; v += dv * dv
                        if (dv < 0) dv = -dv
                        if (dv > big) big = dv
                    }
                    sd = sqrt(v / (n - 1)); rel = sd / (m < 0 ? -m : m)
                    printf "%s %s %d %.6g %.3g %.6g %.6g\n", scene, nm[k], n, m, sd, rel, big / (m < 0 ? -m : m)
                }
            }'
    }
    spreads="$(
        spread_stats bed "phi H" "$work/spread_bed/sweep.csv" "$work/dt_bed/sweep.csv"
        spread_stats channel "c_w rise" "$work/spread_channel/sweep.csv"
    )"
    # into the margin table: a seventh column, the observable's relative spread (0: none)
    awk -v spreads="$spreads" '
        BEGIN { n = split(spreads, l, "\n"); for (i = 1; i <= n; i++) { split(l[i], w, " "); sp[w[1] "," w[2]] = w[6] } }
        NR == 1 { print $0 ",spread"; next }
        { split($0, w, ","); k = w[1] "," w[2]; printf "%s,%s\n", $0, (k in sp) ? sp[k] : 0 }
    ' "$root/docs/trade_margin.csv" > "$root/docs/trade_margin.csv.new"
    mv "$root/docs/trade_margin.csv.new" "$root/docs/trade_margin.csv"
    spread="$(
        echo "| scene | observable | runs | mean | standard deviation | relative | largest deviation from the mean |"
        echo "|---|---|---|---|---|---|---|"
        echo "$spreads" | awk '{ printf "| %s | %s | %d | %.5g | %.2g | %.2g %% | %.2g %% |\n", $1, $2, $3, $4, $5, 100 * $6, 100 * $7 }'
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
        echo "Errors against the exact path at 0.1 % of the Rayleigh time (the bed's and the"
        echo "channel's against 0.5 %: \`ref\`); the fast path's are in the full tables below."
        echo
        echo "$summary"
        echo
        echo "## Run-to-run spread of the bed and the channel"
        echo
        echo "A poured bed is one draw of a chaotic process: another seed (or another time step, or"
        echo "round-off) gives another bed. Four seeds of \`in.bed\` at its reference setting (0.5 %"
        echo "of the Rayleigh time, exact path); the channel's arrival times are read from dumps,"
        echo "and four dump intervals (every 25 to 28 steps at 5 % of the Rayleigh time) give its"
        echo "sampling's spread. Errors along the axes below within a few of these spreads are"
        echo "differences between draws or samplings, not time-step errors."
        echo "\`docs/trade_margin.csv\` carries the relative spread; \`regolith check\` counts an error"
        echo "within three spreads as within the tolerance, and quotes these observables without"
        echo "letting them set its fastest setting."
        echo
        echo "$spread"
        echo
        echo "## Time step (dt as a fraction of the Rayleigh time), exact and fast path"
        echo
        echo "Reference: the exact path at 0.1 % of the Rayleigh time (the bed and the channel: 0.5 %)."
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
