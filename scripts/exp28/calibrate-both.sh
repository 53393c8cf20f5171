#!/bin/sh
# Issue 28 item 3: calibrate a DEM reference with each flow rule (diffusive,
# sfr, sfr with spot.sfr_rise = steady) and keep the refined comparisons
# (docs/stress.md, "Against DEM").
#   scripts/exp28/calibrate-both.sh DEM_DIR OUT_PREFIX [--set KEY=VALUE]...
set -u
gf=${GRANFLOW:-$(dirname "$0")/../../build/granflow}
dem=$1 out=$2; shift 2
for v in diffusive sfr sfr-steady; do
    case $v in
        diffusive) set_rule="--set spot.flow_rule=diffusive" ;;
        sfr) set_rule="--set spot.flow_rule=sfr --set spot.sfr_rise=slip" ;;
        sfr-steady) set_rule="--set spot.flow_rule=sfr --set spot.sfr_rise=steady" ;;
    esac
    # shellcheck disable=SC2086
    "$gf" calibrate "$dem" $set_rule "$@" -o "$out-$v.ini" > "$out-$v.txt" 2> "$out-$v.err"
    echo "$v rc=$?"
done
