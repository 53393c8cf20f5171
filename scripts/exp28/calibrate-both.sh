#!/bin/sh
# Issue 28 item 3: calibrate a DEM reference with both flow rules and keep
# the refined comparison (docs/stress.md, "Both rules against DEM").
#   scripts/exp28/calibrate-both.sh DEM_DIR OUT_PREFIX [--set KEY=VALUE]...
set -u
gf=${GRANFLOW:-$(dirname "$0")/../../build/granflow}
dem=$1 out=$2; shift 2
for rule in diffusive sfr; do
    "$gf" calibrate "$dem" --set spot.flow_rule=$rule "$@" -o "$out-$rule.ini" \
        > "$out-$rule.txt" 2> "$out-$rule.err"
    echo "$rule rc=$?"
done
