#!/usr/bin/env bash
# CLI test: `spot.flow_rule = sfr` (docs/stress.md): a run writes the stress
# field it follows to stress.csv (its header names the surface height), drains,
# and resumes bit for bit like a run done in one go (the field is solved
# again from the same surface); `granflow render` draws stress.png; a
# diffusive run writes neither; with the free-surface bias it recirculates;
# combinations the rule refuses exit 2 naming the key.
# usage: bash tests/cli/sfr.sh GRANFLOW_BINARY TESTS_DATA_DIR
NAME=sfr
source "$(dirname "$0")/lib.bash" "$@"

SMALL=(--set packing.particles=1500 --set container.width=12 --set container.depth=6
       --set container.orifice_diameter=5 --set output.snapshot_interval=1 --set spot.flow_rule=sfr)

gf run -q "${SMALL[@]}" --set run.duration=4 -o one
expect_rc 0 "sfr run (1500 particles, 4 tau)"
[ -s one/stress.csv ] || fail "sfr run: no stress.csv"
head -1 one/stress.csv | grep -q "ztop = " || fail "stress.csv: the first line does not give ztop"
sed -n 2p one/stress.csv | grep -qx "x,z,s_xx,s_zz,s_xz,s_yy,p,psi_deg,f_x,f_z" || fail "stress.csv: header $(sed -n 2p one/stress.csv)"
[ "$(wc -l < one/stress.csv)" -gt 50 ] || fail "stress.csv: too few nodes"
grep -q '"particles_exited": [1-9]' one/summary.json || fail "sfr run: nothing left through the orifice"
ok "a sfr run writes stress.csv and drains"

gf run -q "${SMALL[@]}" --set run.duration=2 -o two
expect_rc 0 "sfr run to 2 tau"
gf run -q --resume two --set run.duration=4
expect_rc 0 "sfr resume to 4 tau"
cmp -s one/exits.csv two/exits.csv || fail "a resumed sfr run differs from one done in one go (exits.csv)"
cmp -s one/stress.csv two/stress.csv || fail "a resumed sfr run's stress.csv differs"
ok "a resumed sfr run is the same as one done in one go"

gf render one
expect_rc 0 "render a sfr run"
[ -s one/render/stress.png ] || fail "render: no stress.png"
grep -qxF "one/render/stress.png" out || fail "render: stdout does not list one/render/stress.png"
ok "render draws stress.png"

gf run -q --set packing.particles=1500 --set container.width=12 --set container.depth=6 \
    --set container.orifice_diameter=5 --set run.duration=1 -o plain
expect_rc 0 "diffusive run"
[ ! -e plain/stress.csv ] || fail "a diffusive run wrote stress.csv"
ok "a diffusive run writes no stress.csv"

gf run -q "${SMALL[@]}" --set spot.bias_exponent=3 --set run.recirculate=on --set run.duration=3 -o biased
expect_rc 0 "sfr with the free-surface bias, recirculating"
grep -q '"particles_exited": [1-9]' biased/summary.json || fail "sfr with bias: nothing left through the orifice"
ok "sfr with the free-surface bias (spot.bias_exponent) recirculates"

gf run -q "${SMALL[@]}" --set stress.wall_friction_angle=40 -o bad
expect_rc 2 "wall friction above internal friction"
expect_err "stress.wall_friction_angle" "wall friction above internal friction"
gf run -q --set spot.flow_rule=sfr --set container.shape=cylinder --set container.radius=10 \
    --set container.hopper_angle=60 --set container.outlet_diameter=5 --set container.inner_radius=3 -o bad
expect_rc 2 "sfr with a central column"
expect_err "container.inner_radius" "sfr with a central column"
ok "refused combinations exit 2 naming the key"

echo "cli $NAME: $PASS passed, 0 failed"
exit 0
