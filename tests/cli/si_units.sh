#!/usr/bin/env bash
# Units on import (dump.diameter, dump.gravity): a DEM run in SI units (d =
# 0.004 m, g = 9.81 m/s^2), made from a small granflow run by
# scripts/dem_to_si.py, analysed, calibrated and compared gives the same
# numbers, bit for bit, as the same dumps in d and tau; without the keys it
# is refused naming them; the container's walls come from the particles, not
# from the DEM box (1 d wider on each side here), and the messages say where
# each size came from; packing.file in metres is imported with the keys.
NAME=si_units
source "$(dirname "$0")/lib.bash" "$@"
SCRIPT=$(cd "$(dirname "$0")/../../scripts" && pwd)/dem_to_si.py
PY=$(command -v python3) || fail "python3 is needed to make the SI dumps"
SI=(--set dump.diameter=0.004 --set dump.gravity=9.81)

gf run -q --set container.width=10 --set container.depth=6 --set container.orifice_diameter=4 \
    --set packing.particles=600 --set run.duration=5 --set output.snapshot_interval=0.5 -o run
expect_rc 0 "the small run"
"$PY" "$SCRIPT" run si --with-time --twin d >/dev/null || fail "dem_to_si.py --with-time"
"$PY" "$SCRIPT" run lig --twin ligd >/dev/null || fail "dem_to_si.py (TIMESTEP only)"
grep -q '^-0.024 0.024$' si/dump.0000000000 || fail "the SI box is not 12 d = 0.048 m wide: $(sed -n 6,8p si/dump.0000000000)"
ok "SI dumps (box 1 d wider than the walls each side, no config.ini) and their twins in d and tau"

# Without the keys: refused, naming them (not a container size it made up).
gf analyze si --no-plots -o a_bad
expect_rc 2 "analyze of an SI dump read in d"
expect_err "dump.diameter=0.004" "the SI dump read in d"
expect_err "mean diameter of 0.004 d" "the SI dump read in d"
grep -q 'container.width' err && fail "the error blames the container: $(cat err)"
ok "an SI dump without dump.diameter: $(tail -n 1 err | head -c 150)..."

# analyze: the same summary and tables, bit for bit; the walls from the particles.
gf analyze d --no-plots -o a_d
expect_rc 0 "analyze d"
gf analyze si --no-plots -o a_si "${SI[@]}"
expect_rc 0 "analyze si"
expect_err "(width: particle extent; depth: particle extent)" "analyze si"
expect_err "read with d = 0.004 and tau = 0.0201928" "analyze si"
w=$(sed -n 's/.*container \([0-9.]*\) x \([0-9.]*\) d.*/\1 \2/p' err)
awk -v w="$w" 'BEGIN { split(w, a, " "); exit !(a[1] > 9.9 && a[1] <= 10.01 && a[2] > 5.9 && a[2] <= 6.01) }' ||
    fail "the container is not the walls' 10 x 6 d (the box is 12 x 8): '$w'"
cmp -s a_d/summary.json a_si/summary.json || fail "analyze: summary.json differs: $(diff a_d/summary.json a_si/summary.json | head)"
for f in a_d/*.csv; do
    cmp -s "$f" "a_si/${f#a_d/}" || fail "analyze: ${f#a_d/} differs"
done
ok "analyze: SI and d/tau give the same summary.json and $(ls a_d/*.csv | wc -l) tables; container $w d from the particles"
# LIGGGHTS writes no ITEM: TIME: TIMESTEP x dump.dt, in seconds.
gf analyze lig --no-plots -o a_lig "${SI[@]}" --timestep 1e-5
expect_rc 0 "analyze lig"
gf analyze ligd --no-plots -o a_ligd
cmp -s a_lig/summary.json a_ligd/summary.json || fail "analyze (TIMESTEP x 1e-5 s): $(diff a_lig/summary.json a_ligd/summary.json | head)"
ok "analyze: dump.dt in seconds for an SI dump without ITEM: TIME"

# calibrate: the same measurements and parameters; params.ini in d, no units left to apply.
gf calibrate d --no-refine --set container.orifice_diameter=4 -o p_d.ini
expect_rc 0 "calibrate d"
cp out cal_d.txt
printf '[dump]\ndiameter = 0.004\ngravity = 9.81\n[container]\norifice_diameter = 4\n' >dem.ini
gf calibrate si --no-refine --config dem.ini -o p_si.ini
expect_rc 0 "calibrate si --config dem.ini"
cmp -s out cal_d.txt || fail "calibrate: the printed calibration differs: $(diff cal_d.txt out | head)"
expect_err "orifice 4 d (dem.ini:5)" "calibrate si: where the orifice came from"
diff <(grep -v '^file = ' p_d.ini) <(grep -v '^file = ' p_si.ini) >/dev/null || fail "params.ini differs: $(diff p_d.ini p_si.ini | head)"
cmp -s p_d.ini.packing.dump p_si.ini.packing.dump || fail "the initial packings of params.ini differ"
grep -A4 '^\[dump\]' p_si.ini | grep -q '^diameter = 1$' || fail "params.ini would convert its packing (in d) again"
ok "calibrate: SI and d/tau give the same parameters (spot.radius = $(awk '/^\[spot\]/ { s = 1 } s && /^radius = / { print $3; exit }' p_si.ini))"

# compare: the DEM run in SI beside the spot run.
gf compare d run --no-plots -o cmp_d
expect_rc 0 "compare d run"
cp out cmp_d.txt
gf compare si run --no-plots -o cmp_si "${SI[@]}"
expect_rc 0 "compare si run"
cmp -s out cmp_d.txt || fail "compare: the printed table differs: $(diff cmp_d.txt out | head)"
cmp -s cmp_d/summary.csv cmp_si/summary.csv || fail "compare: summary.csv differs"
ok "compare: SI and d/tau give the same comparison"

# A run of granflow is in d and tau: the keys are refused there.
gf analyze run --no-plots -o a_run "${SI[@]}"
expect_rc 2 "analyze of a granflow run with dump.diameter"
expect_err "is a run of granflow" "analyze run with dump.diameter"

# packing.file in metres.
gf run -q --set packing.file=si/dump.0000000000 --set container.width=10 --set container.depth=6 \
    --set container.orifice_diameter=4 --set run.duration=0.5 -o imp_bad
expect_rc 3 "packing.file in metres read in d"
expect_err "dump.diameter" "packing.file in metres read in d"
gf run -q --set packing.file=si/dump.0000000000 "${SI[@]}" --set container.width=10 --set container.depth=6 \
    --set container.orifice_diameter=4 --set run.duration=0.5 -o imp
expect_rc 0 "packing.file in metres with dump.diameter"
n=$(awk '/^ITEM: NUMBER OF ATOMS/ { getline; print; exit }' imp/snapshots/snap_000000.dump)
[ "$n" = 600 ] || fail "the imported packing has $n particles, not 600"
zmax=$(awk 'f { if ($5 > m) m = $5 } /^ITEM: ATOMS/ { f = 1 } END { print m }' imp/snapshots/snap_000000.dump)
awk -v z="$zmax" 'BEGIN { exit !(z > 5 && z < 12) }' || fail "imported heights are not in d: top $zmax"
ok "packing.file in metres: refused without dump.diameter, imported in d with it (top at z = $zmax d)"
echo "cli $NAME: $PASS passed"
