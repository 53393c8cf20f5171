#!/usr/bin/env bash
# CLI test: examples/pebble-bed-box.ini (the recirculating pebble bed in a box)
# is a valid configuration; scaled down to a few seconds it runs end to end:
# exits.csv with passes, snapshots as dumps (with a pass column) and .vtu,
# container.vtk, and `granflow analyze zones` with the zone tables.
# usage: bash tests/cli/pebble_bed.sh GRANFLOW_BINARY TESTS_DATA_DIR
NAME=pebble_bed
source "$(dirname "$0")/lib.bash" "$@"
EX=$DATA/../../examples/pebble-bed-box.ini

gf config "$EX"
expect_rc 0 "config examples/pebble-bed-box.ini"
grep -q '^recirculate = on' out || fail "config: run.recirculate is not on"
ok "examples/pebble-bed-box.ini is valid and recirculates"

# 300 pebbles in an 8 x 6 box, 5 tau: several passes.
gf run -q "$EX" --set packing.particles=300 --set container.width=8 --set container.depth=6 \
    --set container.orifice_diameter=5 --set run.duration=5 --set output.snapshot_interval=2.5 \
    --set run.checkpoint_interval=0 --set run.threads=2 -o bed
expect_rc 0 "run the scaled-down pebble bed"
[ "$(head -n 1 bed/exits.csv | tr -d '\r')" = "id,time,x,y,pass,entry_time,entry_r" ] || fail "exits.csv header"
awk -F, 'NR > 1 && $5 >= 2 { n++ } END { exit !(n > 0) }' bed/exits.csv || fail "exits.csv: no second pass"
grep -q '"particles_reinserted"' bed/summary.json || fail "summary.json: no particles_reinserted"
grep -q '^ITEM: ATOMS id type x y z pass$' bed/snapshots/snap_000002.dump || fail "snapshot without a pass column"
grep -q 'NumberOfPoints="300"' bed/snapshots/snap_000002.vtu || fail "snap_000002.vtu: not 300 points"
head -n 4 bed/container.vtk | grep -q '^DATASET POLYDATA$' || fail "container.vtk is not VTK polydata"
ok "the run writes passes, .vtu snapshots and container.vtk"

gf analyze zones bed --set zones.radii=1.5,3 --no-plots
expect_rc 0 "analyze zones"
for f in zones zones_matrix rtd_pass rtd_zone_hist streamlines vz_r; do
    [ "$(wc -l < "bed/analysis/$f.csv")" -ge 2 ] || fail "analyze zones: $f.csv has no data rows"
done
[ "$(wc -l < bed/analysis/zones.csv)" -eq 4 ] || fail "zones.csv: expected 3 zones"
ok "analyze zones writes the zone tables"

# The full-scale core (a cylinder over a 60 degree funnel and a pipe) is a
# valid configuration; scaled down (radius 5, a 30 degree funnel, 250
# pebbles) it recirculates.
gf config "$DATA/../../examples/pebble-bed.ini"
expect_rc 0 "config examples/pebble-bed.ini"
grep -q '^shape = cylinder' out || fail "config: container.shape is not cylinder"
gf run -q "$DATA/../../examples/pebble-bed.ini" --set packing.particles=250 --set container.radius=5 \
    --set container.hopper_angle=30 --set container.outlet_diameter=4 --set container.outlet_length=1 --set run.duration=6 \
    --set output.snapshot_interval=2 --set run.checkpoint_interval=0 --set run.threads=2 -o core
expect_rc 0 "run the scaled-down cylindrical core"
awk -F, 'NR > 1 && $5 >= 2 { n++ } END { exit !(n > 0) }' core/exits.csv || fail "core: no second pass"
awk -F, 'NR > 1 && ($7 > 5 || $1 !~ /^[0-9]+$/) { bad++ } END { exit bad > 0 }' core/exits.csv ||
    fail "core: an entry radius beyond the wall"
grep -q 'NumberOfPoints="250"' core/snapshots/snap_000003.vtu || fail "core: snap_000003.vtu: not 250 points"
head -n 4 core/container.vtk | grep -q '^DATASET POLYDATA$' || fail "core: container.vtk is not VTK polydata"
ok "examples/pebble-bed.ini: a scaled-down cylindrical core recirculates and writes VTK"
echo "cli $NAME: $PASS passed, 0 failed"
