#!/usr/bin/env bash
# Issue 23 experiment (docs/performance.md "The sweep engine", "Where the
# flow bias lives"): builds flow.c against build/libgranflow.so and prints
# the outflow of each engine, mean +- standard error over the seeds, with
# and without relaxation, and of the sweep engine for windows from 1/mu
# down to 1/(256 mu). Minutes on one core (the smallest window, ~2 min a seed).
# usage: bash scripts/exp23/run.sh [BUILD_DIR] [OUT_DIR]
set -euo pipefail
SRC=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-$SRC/build}
OUT=${2:-$SRC/runs/exp23}
mkdir -p "$OUT"
cc -O2 -std=c17 -I"$SRC/include" -I"$BUILD/include" "$SRC/scripts/exp23/flow.c" -L"$BUILD" -lgranflow \
    -Wl,-rpath,"$BUILD" -lm -o "$OUT/flow"
MU=28
row() { # row LABEL ENV ENGINE [WINDOW]: 12 seeds (6 for the smallest window)
    local label=$1 env=$2 engine=$3 w=${4:-} seeds=12
    [ "$w" = "$(awk -v m=$MU 'BEGIN { printf "%.9g", 1 / (256 * m) }')" ] && seeds=6
    for s in $(seq 1 $seeds); do env $env "$OUT/flow" "$engine" "$s" $w; done >"$OUT/$label.txt"
    awk -v l="$label" '{ v[NR] = $NF; m += $NF } END { m /= NR; for (i = 1; i <= NR; i++) s += (v[i] - m)^2
        printf "| %s | %d | %.2f +- %.2f |\n", l, NR, m, sqrt(s / (NR - 1) / NR) }' "$OUT/$label.txt"
}
echo "| engine | seeds | out per tau |"
echo "|---|---|---|"
for relax in on off; do
    env=X=1
    [ $relax = off ] && env=NORELAX=1
    row "event-relax-$relax" $env event
    row "fixed-relax-$relax" $env fixed
    row "domains-relax-$relax" $env domains
    for k in 1 64 256; do
        w=$(awk -v m=$MU -v k=$k 'BEGIN { printf "%.9g", 1 / (k * m) }')
        row "sweep1-W1over${k}mu-relax-$relax" $env sweep1 "$w"
    done
done
