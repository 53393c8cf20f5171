#!/usr/bin/env bash
# CLI test: examples/wedge-hopper.ini (a quasi-2D wedge hopper,
# container.shape = wedge) end to end, scaled down to seconds on the command
# line: granflow run (exits only through the slit, container.vtk), analyze
# (the profiles in x), render (the hopper's outline), and the errors of its
# keys naming the file, the line and the key.
# usage: bash tests/cli/wedge.sh GRANFLOW_BINARY TESTS_DATA_DIR
NAME=wedge
source "$(dirname "$0")/lib.bash" "$@"
EX=$DATA/../../examples/wedge-hopper.ini

gf config "$EX"
expect_rc 0 "config examples/wedge-hopper.ini"
grep -q '^shape = wedge' out || fail "config: container.shape is not wedge"
grep -q '^orifice_shape = slit' out || fail "config: a wedge's outlet is not made a slit"
ok "examples/wedge-hopper.ini is valid; its outlet is a slit"

# 20 x 6, walls at 60 degrees, a 4 d slit with a 1 d chute, filled to 20: a few seconds.
gf run -q "$EX" --set container.width=20 --set container.orifice_diameter=4 --set container.outlet_length=1 \
    --set packing.fill_height=20 --set run.duration=4 --set output.snapshot_interval=1 \
    --set output.format=both -o w
expect_rc 0 "run the scaled-down wedge"
n=$(awk -F, 'NR > 1 { n++ } END { print n + 0 }' w/exits.csv)
[ "$n" -gt 20 ] || fail "the wedge did not drain: $n exits"
awk -F, 'NR > 1 && ($3 <= -2 || $3 >= 2) { bad++ } END { exit bad > 0 }' w/exits.csv ||
    fail "an exit outside the slit |x| < 2: $(awk -F, 'NR > 1 && ($3 <= -2 || $3 >= 2)' w/exits.csv | head -n 3)"
head -n 4 w/container.vtk | grep -q '^DATASET POLYDATA$' || fail "container.vtk is not VTK polydata"
ok "the wedge drains ($n exits in 4 tau), every exit through the slit; container.vtk written"

gf analyze w --no-plots
expect_rc 0 "analyze the wedge"
expect_err "wedge hopper 20 x 6 d" "analyze: the container described"
ls w/analysis/*velocity* >/dev/null 2>&1 || fail "analyze: no velocity profiles"
grep -rqs 'v_z(r)' w/analysis && fail "analyze: a wedge's profiles are radial"
ok "analyze: the wedge described, its velocity profiles in x"

gf render w --times 4 --scale 4 -o pic
expect_rc 0 "render the wedge"
png=$(ls pic/*.png | head -n 1)
[ -s "$png" ] || fail "render wrote no picture"
ok "render: $(basename "$png")"

printf '[container]\nshape = wedge\nwidth = 20\nhopper_angle = 0\n' > bad.ini
gf config bad.ini
expect_rc 2 "a wedge with flat walls"
expect_err "bad.ini:4: container.hopper_angle = 0 must be more than 0 with container.shape = wedge (bad.ini:2)" \
    "the angle's error names the file, line and keys"
printf '[container]\nshape = wedge\nwidth = 20\nhopper_angle = 45\norifice_diameter = 24\n' > bad.ini
gf config bad.ini
expect_rc 2 "a slit wider than the wedge"
expect_err "bad.ini:5: container.orifice_diameter = 24 must be less than container.width = 20 (bad.ini:3)" \
    "the slit's error names the file, line and keys"
ok "bad wedge keys: errors naming file, line and key"
echo "cli $NAME: $PASS passed, 0 failed"
