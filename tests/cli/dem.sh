#!/usr/bin/env bash
# granflow dem / calibrate / compare on the command line: inputs written,
# usage errors and their exit codes, --timestep understood by analyze.
NAME=dem
source "$(dirname "$0")/lib.bash" "$@"

# expect_code CODE ARGS...: granflow ARGS must exit with CODE.
expect_code() {
    local want=$1
    shift
    gf "$@"
    expect_rc "$want" "granflow $*"
    ok "granflow $* -> $want"
}

expect_code 2 dem --set packing.particles=100            # no -o
expect_code 2 dem --set dem.timestep=0.01 -o "$T/x"       # too long for kn
expect_code 0 dem -q --set container.width=12 --set packing.particles=200 --set dem.fill_method=generate -o "$T/d"
for f in in.fill in.drain config.ini fill.data; do [ -s "$T/d/$f" ] || fail "granflow dem did not write $f"; done
ok "inputs written"
grep -q 'wall/gran/region hertz/history' "$T/d/in.drain" || fail "in.drain has no base with a hole"
grep -q 'dump_modify snap pad 9 sort id time yes' "$T/d/in.drain" || fail "in.drain dumps without ITEM: TIME"
grep -q '^\[dem\]' "$T/d/config.ini" || fail "config.ini lacks [dem]"
expect_code 2 calibrate "$T/d"                            # no -o
expect_code 2 compare "$T/d"                              # one run only
expect_code 2 calibrate "$T/d" -o "$T/p.ini" --bogus
# A dump with TIMESTEP only: analyze needs --timestep (an alias of --set dump.dt=).
cat > "$T/steps.dump" <<'DUMP'
ITEM: TIMESTEP
0
ITEM: NUMBER OF ATOMS
2
ITEM: BOX BOUNDS ff ff ff
-5 5
-3 3
0 10
ITEM: ATOMS id x y z
1 0 0 1
2 1 0 2
ITEM: TIMESTEP
10000
ITEM: NUMBER OF ATOMS
1
ITEM: BOX BOUNDS ff ff ff
-5 5
-3 3
0 10
ITEM: ATOMS id x y z
2 1 0 1.5
DUMP
expect_code 2 analyze outflow "$T/steps.dump" -q --no-plots -o "$T/a"
expect_code 0 analyze outflow "$T/steps.dump" -q --no-plots -o "$T/a" --timestep 1e-4 --set container.orifice_diameter=4 \
    --set container.width=10 --set container.depth=6 # two particles span no silo: its walls given
grep -q '"particles_exited": 1' "$T/a/summary.json" || fail "outflow of the dump is not 1 particle"
ok "analyze --timestep"
# A silo too small for most of the thesis' measurements (600 particles, 10 d
# wide, 5 tau, the correlation region and the profiles cut by the walls):
# calibrate says what it could not measure and still writes five positive
# numbers, never nan (--no-refine: the refinement has its own test).
gf run -q --set container.width=10 --set container.depth=6 --set container.orifice_diameter=4 \
    --set packing.particles=600 --set run.duration=5 --set output.snapshot_interval=0.5 -o tiny
expect_rc 0 "run tiny"
gf calibrate tiny --no-refine -o tiny.ini
expect_rc 0 "calibrate tiny --no-refine"
grep -q '^note: ' out || fail "calibrate of a tiny silo printed no note of what it could not measure: $(cat out)"
grep -qi 'nan' tiny.ini && fail "tiny.ini holds a nan: $(grep -i nan tiny.ini)"
for k in radius step_xy w insertion_rate move_rate; do
    v=$(sed -n "s/^$k *= *//p" tiny.ini | head -1)
    awk -v v="$v" 'BEGIN { exit !(v == v + 0 && v > 0) }' || fail "tiny.ini: $k = '$v' is not a positive number"
done
grep -q 'refine' err && fail "--no-refine still refined"
ok "calibrate of a tiny silo: notes, fallbacks, five positive numbers ($(grep -c '^note: ' out) notes)"
# --runs N bounds the refinement's spot runs; a bad N is refused, named.
gf calibrate tiny --runs 1 -o tiny1.ini
expect_rc 0 "calibrate tiny --runs 1"
grep -q 'run 1/1' err || fail "--runs 1: no 'run 1/1' progress line: $(grep refine err | head -3)"
grep -q 'run 2/' err && fail "--runs 1 made a second run"
for bad in 0 101 abc ''; do
    gf calibrate tiny --runs "$bad" -o bad.ini
    expect_rc 2 "calibrate --runs '$bad'"
    grep -q -- "--runs" err || fail "calibrate --runs '$bad': the error does not name --runs: $(cat err)"
done
[ -e bad.ini ] && fail "a refused --runs wrote bad.ini"
ok "calibrate --runs: one run with --runs 1; 0, 101, abc and '' refused"
# The velocity profiles are named for the container (gf_velocity_profile_name):
# v_z(x) across a box, v_z(r) about a cylinder's axis, in compare's table,
# summary.md and figure script and in calibrate's notes (the tiny cylinder's
# profiles are too short to fit, so the note on their variance is printed).
gf compare tiny tiny --no-plots -o cmp_box
expect_rc 0 "compare tiny tiny"
grep -q 'Var of v_z(x) at z = ' out || fail "compare of a box: no 'Var of v_z(x)' row: $(cat out)"
grep -q 'v_z(r)' out cmp_box/summary.md cmp_box/compare.gp && fail "compare of a box says v_z(r)"
grep -q 'Gaussian fits of v_z(x)' cmp_box/summary.md || fail "summary.md of a box does not name v_z(x)"
# window.parts: the sub-windows behind the uncertainties, as many as asked
# when the window holds 3 frames a part (tiny's 2-5 tau holds 7: 2 of the
# default 4; 0-5 tau holds 11: 3 of 3); out of [2, 64] refused by name.
grep -q 'standard errors over 2 sub-windows' out || fail "compare: not 2 sub-windows in 7 frames: $(grep sub-windows out)"
gf compare tiny tiny --no-plots --set window.t0=0 --set window.parts=3 -o cmp_parts
expect_rc 0 "compare --set window.parts=3"
grep -q 'standard errors over 3 sub-windows' out || fail "compare: window.parts=3 not used: $(grep sub-windows out)"
gf compare tiny tiny --no-plots --set window.parts=1 -o cmp_parts1
expect_rc 2 "compare --set window.parts=1"
grep -q 'window.parts' err || fail "window.parts=1: the error does not name the key: $(cat err)"
ok "compare: window.parts sets the sub-windows of the uncertainties; 1 refused"
gf run -q --set container.shape=cylinder --set container.radius=5 \
    --set packing.particles=600 --set run.duration=5 --set output.snapshot_interval=0.5 -o cyl
expect_rc 0 "run cyl"
gf compare cyl cyl --no-plots -o cmp_cyl
expect_rc 0 "compare cyl cyl"
grep -q 'Var of v_z(r) at z = ' out || fail "compare of a cylinder: no 'Var of v_z(r)' row: $(cat out)"
# The rows' DEM column lines up with the header's (names up to 34 characters).
awk '/^  quantity / { at = index($0, "DEM") } /^  Var of / && at && substr($0, at - 1, 2) !~ /^ [-0-9]/ { bad = 1 } END { exit bad || !at }' out ||
    fail "compare of a cylinder: the Var rows do not line up with the header: $(grep -E '^  (quantity|Var of)' out)"
grep -q 'Gaussian fits of v_z(r)' cmp_cyl/summary.md || fail "summary.md of a cylinder does not name v_z(r)"
grep -q "set title 'v_z(r) at z = " cmp_cyl/compare.gp || fail "compare.gp of a cylinder does not title v_z(r)"
grep -q 'v_z(x)' out cmp_cyl/summary.md cmp_cyl/compare.gp && fail "compare of a cylinder says v_z(x): $(grep -h 'v_z(x)' out cmp_cyl/*)"
gf calibrate cyl --no-refine -o cyl.ini
expect_rc 0 "calibrate cyl --no-refine"
grep -q '^note: the v_z(r) profile variance' out || fail "calibrate of a cylinder: no note naming v_z(r): $(cat out)"
grep -q 'v_z(x)' out && fail "calibrate of a cylinder says v_z(x): $(grep 'v_z(x)' out)"
grep -q 'cylinder of radius 5 d (cyl/config.ini:[0-9]*),.* outlet 8 d (cyl/config.ini:[0-9]*)$' err || fail "calibrate of a cylinder: header does not name its radius and outlet: $(grep snapshots err)"
grep -q 'orifice' err && fail "calibrate of a cylinder names an orifice: $(grep orifice err)"
ok "profiles named for the container: v_z(x) in a box, v_z(r) in a cylinder (compare table, summary.md, compare.gp, calibrate note and header)"
# A DEM reference without exits.csv (the tiny run's snapshots and config.ini,
# all LAMMPS leaves): the exits are read off the snapshots (every 0.5 tau), so
# its residence times are exits.csv's to within 0.25 tau, and compare has
# residence-time rows with uncertainties.
mkdir demlike && cp tiny/snapshots/*.dump tiny/config.ini demlike/
gf analyze rtd demlike --no-plots
expect_rc 0 "analyze rtd of dumps without exits.csv"
expect_err "exits (read off the snapshots, times within +- 0.25 tau)" "analyze rtd of dumps"
gf analyze rtd tiny --no-plots -q
expect_rc 0 "analyze rtd tiny"
val() { sed -n "s/^ *\"$2\": *\([^,]*\),*\$/\1/p" "$1/analysis/summary.json"; }
[ "$(val demlike rtd_exited)" = "$(val tiny rtd_exited)" ] || fail "exits read off the snapshots: $(val demlike rtd_exited), exits.csv: $(val tiny rtd_exited)"
[ "$(val demlike rtd_resolution)" = 0.25 ] && [ "$(val tiny rtd_resolution)" = 0 ] ||
    fail "rtd_resolution: dumps $(val demlike rtd_resolution) (want 0.25), run $(val tiny rtd_resolution) (want 0)"
awk -v a="$(val demlike rtd_mean)" -v b="$(val tiny rtd_mean)" -v e="$(val demlike rtd_mean_err)" \
    'BEGIN { d = a - b; if (d < 0) d = -d; exit !(a > 0 && d <= 0.25 && e >= 0.25 / sqrt(3)) }' ||
    fail "rtd_mean from the snapshots $(val demlike rtd_mean) +- $(val demlike rtd_mean_err), from exits.csv $(val tiny rtd_mean): not within 0.25 tau"
ok "rtd of dumps without exits.csv: $(val demlike rtd_exited) exits, mean $(val demlike rtd_mean) tau (exits.csv: $(val tiny rtd_mean))"
gf compare demlike tiny --no-plots -o cmp_rtd
expect_rc 0 "compare demlike tiny"
grep -Eq '^  mean residence time \(tau\) +[0-9.]+ \+- [0-9.e-]+ +[0-9.]+ \+- [0-9.e-]+ +[-+][0-9.]+% \+- ' out ||
    fail "compare: no residence-time row with uncertainties: $(cat out)"
grep -q 'DEM read off the snapshots, +- 0.25 tau, spot exits.csv' out || fail "compare does not state the exit-time resolution"
grep -Eq '^    of layer 1 \(tau\) ' out || fail "compare: no per-layer residence-time row"
grep -q '^| 1 | [0-9]* | [0-9.]* +- ' cmp_rtd/summary.md || fail "summary.md: no residence times by layer"
grep -Eq '^rtd_mean,[0-9.]+,[0-9.]+,' cmp_rtd/summary.csv || fail "summary.csv: no rtd_mean of both runs"
[ -s cmp_rtd/dem_rtd.csv ] && [ -s cmp_rtd/spot_rtd.csv ] || fail "compare wrote no dem_rtd.csv / spot_rtd.csv"
ok "compare of a DEM without exits.csv: residence-time rows with uncertainties, summary.md, summary.csv"
echo "cli $NAME: $PASS passed, 0 failed"
