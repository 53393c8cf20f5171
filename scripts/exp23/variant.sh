#!/usr/bin/env bash
# Issue 23 experiment (docs/performance.md "Sub-windows, zones and more
# sweeps"): builds the library with one of the throw-away patches of this
# folder applied (in a temporary worktree of HEAD), then runs the sweep
# engine of flow.c (W = 1/mu, one sweep) over SEEDS seeds with the
# patch's environment variables and prints mean +- standard error.
#   subwindow.patch  GF_ZSUB=z GF_KSUB=k: the moves whose centre is below z
#                    gathered and relaxed in k sub-windows of the window, in
#                    time order (z = 1000: every move)
#   ksweep.patch     GF_KSWEEP=k: k sweeps a window, sweep s relaxing only the
#                    particles reached by more than s moves of the window
#   permove.patch    GF_PERMOVE=2 GF_NOSWEEP=1: each move's relax() computed
#                    alone from the window start displaced by that move only,
#                    its increment over the undisplaced packing summed over
#                    the moves, plus one pass at the window start (=1: the
#                    raw sums); GF_NOSWEEP=1 skips the window's sweeps
#   serialzone.patch GF_ZSUB=z [GF_ZNORELAX=1]: the moves below z made one by
#                    one after the window, as the event engine makes them
# usage: bash scripts/exp23/variant.sh PATCH "ENV=VALUE ..." [SEEDS] [OUT_DIR]
set -euo pipefail
SRC=$(cd "$(dirname "$0")/../.." && pwd)
PATCH=$1 ENVS=$2 SEEDS=${3:-8}
OUT=${4:-$SRC/runs/exp23/$(basename "$PATCH" .patch)}
WT=$OUT/src
mkdir -p "$OUT"
if [ ! -x "$OUT/flow" ]; then
    rm -rf "$WT"
    git -C "$SRC" worktree add --detach "$WT" HEAD >/dev/null
    git -C "$WT" apply "$SRC/scripts/exp23/$(basename "$PATCH")"
    cmake -S "$WT" -B "$OUT/build" -DCMAKE_BUILD_TYPE=Release -DGF_LTO=OFF >"$OUT/configure.log"
    cmake --build "$OUT/build" -j2 --target granflow >"$OUT/build.log"
    cc -O2 -std=c17 -I"$WT/include" -I"$OUT/build/include" "$SRC/scripts/exp23/flow.c" -L"$OUT/build" -lgranflow \
        -Wl,-rpath,"$OUT/build" -lm -o "$OUT/flow"
fi
label=$(echo "$ENVS" | tr ' =' '_-')
for s in $(seq 1 "$SEEDS"); do env $ENVS "$OUT/flow" sweep1 "$s" 0.0357142857; done >"$OUT/$label.txt"
awk -v l="$ENVS" '{ v[NR] = $NF; m += $NF; r += $9 } END { m /= NR; for (i = 1; i <= NR; i++) s += (v[i] - m)^2
    printf "| %s | %d | %.2f +- %.2f | %.6f |\n", l, NR, m, sqrt(s / (NR - 1) / NR), r / NR }' "$OUT/$label.txt"
