#!/bin/sh
# Issue 27 experiment 4 (docs/dem.md): does the spot model's free surface
# narrow the upper profiles? B's calibrated parameters (PARAMS, made by
# `granflow calibrate runs/dem-validation/slit --set correlation.size=3`),
# three seeds each: (a) as calibrated, (b) the papers' free surface (bias
# exponent 3, influence weighting), (c) a fill twice as tall. Var of v_z(x)
# at B's heights: OUT/VARIANT-sS/an/velocity_variance.csv.
# Usage: scripts/exp27-free-surface.sh [GRANFLOW] [PARAMS] [OUT]
set -eu
GF=${1:-build/granflow}
P=${2:-runs/dem-validation/slit-free-params.ini}
OUT=${3:-runs/fs27}
H=5,6.67,8.33,10,11.67,13.33,15,16.67
for v in base bias3 tall; do
    case $v in
        base) extra="" ;;
        bias3) extra="--set spot.bias_exponent=3 --set spot.weighting=on --set spot.weighting_zmin=0" ;;
        tall) extra="--set packing.file= --set packing.particles=10000" ;;
    esac
    for s in 1 2 3; do
        d=$OUT/$v-s$s
        # shellcheck disable=SC2086
        nice "$GF" run -q "$P" $extra --set run.seed=$s -o "$d" --force
        nice "$GF" analyze velocity "$d" --set velocity.heights=$H -o "$d/an" --no-plots -q > /dev/null
    done
done
