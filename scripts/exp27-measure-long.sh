#!/bin/sh
# Issue 27 item 4 (docs/dem.md, "Long references"): measure a recirculating
# DEM reference that is still running, then let it go on. SIGTERM to its
# `granflow dem` makes it write exits.csv and stop at a restart point; the
# run directory so far is copied (a continuation removes the snapshots after
# its restart point), the copy is measured with `granflow compare COPY COPY`
# over 16 sub-windows (the DEM column's errors are the Var standard errors
# at each height), and the drain is continued at the lowest priority.
#   scripts/exp27-measure-long.sh RUN_DIR COPY_DIR HEIGHTS [GRANFLOW]
#   e.g. scripts/exp27-measure-long.sh runs/C-long /tmp/C 5,7.5,10,12.5,15,17.5,20
set -eu
run=$1 copy=$2 heights=$3
gf=${4:-$(dirname "$0")/../build/granflow}
pid=$(pgrep -f "granflow dem -o $run --continue" | head -1 || true)
[ -n "$pid" ] || pid=$(pgrep -f "granflow dem .*-o $run" | head -1 || true)
if [ -n "$pid" ]; then
    kill -TERM "$pid"
    # Wait on the process itself (a pgrep loop would match this script's own line).
    while kill -0 "$pid" 2>/dev/null; do sleep 2; done
fi
[ -s "$run/exits.csv" ] || { echo "$run: no exits.csv (was the drain running?)" >&2; exit 1; }
rm -rf "$copy"
mkdir -p "$copy/snapshots"
cp "$run/config.ini" "$run/exits.csv" "$copy/"
[ -f "$run/reinserted.txt" ] && cp "$run/reinserted.txt" "$copy/"
cp "$run"/snapshots/*.dump "$copy/snapshots/"
nohup nice -n 19 "$gf" dem -o "$run" --continue >> "$run.log" 2>&1 &
"$gf" compare "$copy" "$copy" --no-plots --set velocity.heights="$heights" --set window.parts=16 \
    -o "$copy-cmp" 2>/dev/null | grep -E "over|Var of|flow rate"
