#!/usr/bin/env bash
# CLI test: `granflow lga` runs each of the LGA paper's problems small and
# fast (pile, channel, mass- and funnel-flow silo) and writes its maps,
# contact sheet, CSVs and summary; bad keys and values exit 2 with the key
# named; a non-empty directory is refused without --force.
# usage: bash tests/cli/lga.sh GRANFLOW_BINARY TESTS_DATA_DIR
NAME=lga
source "$(dirname "$0")/lib.bash" "$@"

is_png() { [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ]; }
no_tmp() { [ -z "$(find "$1" -name '*.tmp')" ] || fail "$2 left temporary files: $(find "$1" -name '*.tmp')"; }
# json KEY FILE: the value of a top-level key of summary.json
json() { sed -n "s/^  \"$1\": \\(.*\\),\$/\\1/p; s/^  \"$1\": \\(.*\\)\$/\\1/p" "$2" | head -n 1; }

# --- pile -------------------------------------------------------------------
gf lga -q --set lga.scenario=pile --set lga.width=80 --set lga.height=30 --set lga.particles=300 \
    --set lga.feed_rate=2 --set lga.snapshot_interval=50 -o pile
expect_rc 0 "lga pile"
for f in config.ini outflow.csv profile.csv sheet.png summary.json maps/map_000000.png maps/map_000050.png; do
    [ -s "pile/$f" ] || fail "lga pile: pile/$f missing or empty"
done
is_png pile/sheet.png || fail "pile/sheet.png is not a PNG file"
is_png pile/maps/map_000050.png || fail "pile/maps/map_000050.png is not a PNG file"
[ "$(json scenario pile/summary.json)" = '"pile"' ] || fail "pile summary: scenario is $(json scenario pile/summary.json)"
[ "$(json particles_added pile/summary.json)" = 300 ] || fail "pile summary: particles_added is not 300"
angle=$(json slope_angle pile/summary.json)
awk -v a="$angle" 'BEGIN { exit !(a > 10 && a < 45) }' || fail "pile summary: slope_angle '$angle' is not a sane angle"
head -n 1 pile/profile.csv | grep -qx 'x,height' || fail "pile/profile.csv has no x,height header"
head -n 1 pile/outflow.csv | grep -qx 'iteration,outflow,particles,added' || fail "pile/outflow.csv header"
grep -q '^\[lga\]$' pile/config.ini && grep -qx 'scenario = pile' pile/config.ini || fail "pile/config.ini lacks [lga] scenario = pile"
no_tmp pile "lga pile"
ok "pile: maps, sheet, outflow.csv, profile.csv, summary.json with slope_angle ($angle degrees)"

# the effective config reads back and reruns identically (a run is a function of its config)
gf lga -q pile/config.ini -o pile2
expect_rc 0 "lga pile/config.ini"
cmp -s pile/outflow.csv pile2/outflow.csv || fail "rerun from pile/config.ini gave a different outflow.csv"
cmp -s pile/profile.csv pile2/profile.csv || fail "rerun from pile/config.ini gave a different profile.csv"
ok "rerunning config.ini reproduces the run exactly"

# --- channel ----------------------------------------------------------------
gf lga -q --set lga.scenario=channel --set lga.width=16 --set lga.height=80 --set lga.iterations=120 -o channel
expect_rc 0 "lga channel"
[ -s channel/waves.csv ] || fail "lga channel: no waves.csv"
[ "$(wc -l < channel/waves.csv)" -eq 14 ] || fail "channel/waves.csv: expected a header and 13 rows (every 10 iterations)"
[ "$(json particles_final channel/summary.json)" = "$(json particles_initial channel/summary.json)" ] ||
    fail "channel: particles not conserved"
[ "$(json particles_initial channel/summary.json)" = 896 ] || fail "channel: 0.7 x 16 x 80 = 896 particles expected"
[ "$(json wave_variance_ratio channel/summary.json)" != null ] || fail "channel summary: no wave_variance_ratio"
[ "$(ls channel/maps | tr '\n' ' ')" = "map_000000.png map_000060.png map_000120.png " ] ||
    fail "channel: expected maps at 0, 60 and 120, got $(ls channel/maps | tr '\n' ' ')"
ok "channel: waves.csv, particles conserved, wave variance in the summary"

# --- silo, mass and funnel flow ---------------------------------------------
for flow in mass funnel; do
    gf lga -q --set lga.silo_flow=$flow --set lga.width=30 --set lga.height=20 --set lga.outlet_width=6 \
        --set lga.particles=400 -o silo-$flow
    expect_rc 0 "lga silo ($flow)"
    n=$(json iterations_to_empty silo-$flow/summary.json)
    [ "$n" -gt 0 ] 2>/dev/null || fail "silo ($flow): iterations_to_empty is '$n'"
    [ "$(json particles_final silo-$flow/summary.json)" = 0 ] || fail "silo ($flow) did not empty"
    out=$(awk -F, 'NR > 1 { s += $2 } END { print s }' silo-$flow/outflow.csv)
    [ "$out" = 400 ] || fail "silo ($flow): outflow.csv adds up to $out, not 400"
    last=$(tail -n 1 silo-$flow/outflow.csv | cut -d, -f1)
    [ "$last" = "$n" ] || fail "silo ($flow): outflow.csv ends at $last, emptied at $n"
    # when the outflow left: the last outflow is the emptying; t50 < t90 <= t99 <= it
    [ "$(json iterations_to_stop silo-$flow/summary.json)" = "$n" ] || fail "silo ($flow): iterations_to_stop is not $n"
    t50=$(json t50 silo-$flow/summary.json) t90=$(json t90 silo-$flow/summary.json) t99=$(json t99 silo-$flow/summary.json)
    [ 0 -lt "$t50" ] && [ "$t50" -lt "$t90" ] && [ "$t90" -le "$t99" ] && [ "$t99" -le "$n" ] 2>/dev/null ||
        fail "silo ($flow): t50 $t50, t90 $t90, t99 $t99 are not ordered within $n iterations"
    half=$(awk -F, 'NR > 1 { s += $2; if (s >= 200) { print $1; exit } }' silo-$flow/outflow.csv)
    [ "$half" = "$t50" ] || fail "silo ($flow): t50 is $t50, outflow.csv reaches 200 of 400 at $half"
done
# a funnel that never empties (hopper past the repose angle, 2 d outlet) still says when its outflow left
gf lga -q --set lga.silo_flow=funnel --set lga.hopper_angle=75 --set lga.width=30 --set lga.height=20 \
    --set lga.outlet_width=2 --set lga.particles=400 -o silo-stuck
expect_rc 0 "lga silo (funnel, 75 degrees)"
[ "$(json iterations_to_empty silo-stuck/summary.json)" = null ] || fail "silo-stuck emptied"
stop=$(json iterations_to_stop silo-stuck/summary.json)
last=$(awk -F, 'NR > 1 && $2 > 0 { i = $1 } END { print i }' silo-stuck/outflow.csv)
[ "$stop" = "$last" ] || fail "silo-stuck: iterations_to_stop is '$stop', the last outflow in outflow.csv is at $last"
for k in t50 t90 t99; do
    [ "$(json $k silo-stuck/summary.json)" -gt 0 ] 2>/dev/null || fail "silo-stuck: $k is '$(json $k silo-stuck/summary.json)'"
done
hm=$(sed -n 's/^  "hopper_angle": \(.*\),$/\1/p' silo-mass/summary.json)
hf=$(sed -n 's/^  "hopper_angle": \(.*\),$/\1/p' silo-funnel/summary.json)
[ "$hm" = 20 ] && [ "$hf" = 60 ] || fail "hopper angles: mass $hm, funnel $hf (expected 20 and 60)"
ok "silo: mass ($(json iterations_to_empty silo-mass/summary.json) iterations) and funnel flow ($(json iterations_to_empty silo-funnel/summary.json)) empty; outflow.csv adds up"

# --- errors -----------------------------------------------------------------
gf lga --set lga.bogus=1 -o bad
expect_rc 2 "lga --set lga.bogus=1"
expect_err "unknown key 'bogus' in section [lga]" "lga --set lga.bogus=1"
[ ! -e bad ] || fail "a bad key still created the output directory"
gf lga --set lga.p=1.5 -o bad
expect_rc 2 "lga --set lga.p=1.5"
expect_err "out of range [0, 1]" "lga --set lga.p=1.5"
gf lga --set lga.scenario=heap -o bad
expect_rc 2 "lga --set lga.scenario=heap"
expect_err "not one of: pile, channel, silo" "lga --set lga.scenario=heap"
gf lga --set lga.outlet_width=500 -o bad
expect_rc 2 "lga --set lga.outlet_width=500"
expect_err "lga.outlet_width" "lga --set lga.outlet_width=500"
[ ! -e bad ] || fail "a bad geometry still created the output directory"
printf '[lga]\nscenario = silo\nq = -1\n' > bad.ini
gf lga bad.ini -o bad
expect_rc 2 "lga bad.ini"
expect_err "bad.ini:3" "lga bad.ini (q = -1)"
# Lattice sizes the scenario cannot use name the key and where it was set.
printf '[lga]\nscenario = pile\n\nwidth = 5\n' > small.ini
gf lga small.ini -o bad
expect_rc 2 "lga small.ini (a pile 5 columns wide)"
expect_err "small.ini:4: lga.width = 5 is too small: the pile needs at least 8 columns" "lga small.ini"
gf lga --set lga.scenario=channel --set lga.height=4 -o bad
expect_rc 2 "lga channel of 4 rows"
expect_err "--set: lga.height = 4 is too small: the channel needs at least 8 rows" "lga channel of 4 rows"
gf lga --set lga.width=100000 --set lga.height=100000 -o bad
expect_rc 2 "lga silo of 100000 x 100000"
expect_err "--set: lga.width = 100000 and lga.height = 100000 make a lattice of" "lga silo of 100000 x 100000"
expect_err "too large (at most 100000000 sites)" "lga silo of 100000 x 100000"
[ ! -e bad ] || fail "a bad lattice size still created the output directory"
ok "bad keys, values, scenarios and geometries exit 2 naming the key"

gf lga -q --set lga.scenario=channel --set lga.width=8 --set lga.height=20 --set lga.iterations=5 -o pile
expect_rc 2 "lga into a non-empty directory"
expect_err "(choose another -o, or overwrite it with --force)" "lga into a non-empty directory"
gf lga -q --force --set lga.scenario=channel --set lga.width=8 --set lga.height=20 --set lga.iterations=5 -o pile
expect_rc 0 "lga --force"
[ ! -e pile/maps/map_000050.png ] || fail "--force left the old run's maps behind"
ok "a non-empty directory needs --force, which clears the old maps"

echo "cli $NAME: $PASS passed, 0 failed"
