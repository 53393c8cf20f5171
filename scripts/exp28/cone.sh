#!/bin/sh
# Issue 28 item 4: one cone of the mass/funnel series (docs/stress.md,
# "Mass flow or funnel flow"). A cylinder of radius 8 d over a cone at
# ANGLE degrees to the horizontal down to a 6 d outlet (a 4 d outlet clogs
# in DEM at 45 and 65 degrees), filled 12 d above
# the cone's top; drained for 12 tau with snapshots every 0.5 tau.
#   scripts/exp28/cone.sh ANGLE dem OUT          (LAMMPS, one rank)
#   scripts/exp28/cone.sh ANGLE diffusive|sfr OUT [SEED]
set -eu
angle=$1 what=$2 out=$3 seed=${4:-1}
gf=${GRANFLOW:-$(dirname "$0")/../../build/granflow}
# The cone's height from r = 8 to r = 3, plus 12 d of column.
fill=$(awk -v a="$angle" 'BEGIN { printf "%.1f", 5 * sin(a * 3.14159265358979 / 180) / cos(a * 3.14159265358979 / 180) + 12 }')
set -- --set container.shape=cylinder --set container.radius=8 \
    --set container.hopper_angle="$angle" --set container.outlet_diameter=6 \
    --set container.outlet_length=1 --set packing.fill_height="$fill" \
    --set run.duration=12 --set output.snapshot_interval=0.5 --set run.seed="$seed"
if [ "$what" = dem ]; then
    "$gf" dem "$@" --set dem.fill_method=generate --set dem.settle_time=10 \
        --set dem.settle_ke=1e-5 --set dem.mpi_ranks=1 -o "$out" --run
else
    # The 2009 silo's parameters with lambda scaled by the outlet's area, (6/8)^2 375.
    "$gf" run "$@" ${EXTRA:-} --set spot.flow_rule="$what" --set spot.insertion_rate=211 -o "$out" -q --force
fi
