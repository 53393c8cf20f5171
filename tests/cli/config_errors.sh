#!/usr/bin/env bash
# CLI test: `granflow config` output round-trips, and every kind of bad
# command line or configuration exits 2 with a message that names the culprit
# (file:line, section, key, option).
# usage: bash tests/cli/config_errors.sh GRANFLOW_BINARY TESTS_DATA_DIR
NAME=config_errors
source "$(dirname "$0")/lib.bash" "$@"
expect_no_stdout() { [ ! -s "$T/out" ] || fail "$1: printed something on stdout despite the error"; }

# --- the effective configuration is a valid INI that reads back to itself ---
gf config
expect_rc 0 "granflow config"
grep -q '^\[spot\]$' out && grep -q '^w = ' out || fail "granflow config: no [spot] section with key w in the output"
cp out default.ini
ok "granflow config prints an INI with a [spot] section"

gf config default.ini
expect_rc 0 "granflow config default.ini"
cmp -s default.ini out || fail "granflow config default.ini: output differs from the file it read"
ok "granflow config FILE reads the printed defaults back to identical output"

gf config --set container.width=12.345678901234567 --set spot.w=0.1 --set spot.ball_centre=end \
    --set container.orifice_shape=slit --set run.seed=18446744073709551615 \
    --set "packing.file=some dir/p.dump" --set relax.radius=4.25
expect_rc 0 "granflow config --set (non-default values)"
cp out custom.ini
grep -qx 'width = 12.345678901234567' custom.ini || fail "config --set container.width=12.345678901234567 not printed at full precision"
grep -qx 'w = 0.1' custom.ini || fail "config --set spot.w=0.1 not printed as 'w = 0.1'"
gf config custom.ini
expect_rc 0 "granflow config custom.ini"
cmp -s custom.ini out || fail "granflow config custom.ini: output differs from the file it read"
ok "non-default values (17 digits, enums, uint64 max, path with a space) round-trip"

# --- a cylinder: its config reads back to itself; bad shapes are refused ----
gf config --set container.shape=cylinder --set container.radius=10 --set container.hopper_angle=30 \
    --set container.outlet_diameter=6 --set container.outlet_length=4 --set container.inner_radius=2
expect_rc 0 "granflow config (a cylinder)"
cp out cylinder.ini
grep -qx 'width = 20' cylinder.ini || fail "a cylinder of radius 10: width is not its bounding box 20"
gf config cylinder.ini
expect_rc 0 "granflow config cylinder.ini"
cmp -s cylinder.ini out || fail "granflow config cylinder.ini: output differs from the file it read"
gf config --set container.shape=cylinder --set container.radius=5 --set container.outlet_diameter=12
expect_rc 2 "config: outlet wider than the cylinder"
expect_err "container.outlet_diameter" "config: outlet wider than the cylinder"
gf config --set container.shape=cylinder --set container.inner_radius=2
expect_rc 2 "config: a column on a flat base"
expect_err "container.hopper_angle" "config: a column on a flat base"
gf config --set container.shape=cone
expect_rc 2 "config: container.shape=cone"
expect_err "container.shape" "config: container.shape=cone"
ok "a cylinder's config round-trips; bad cylinders exit 2 naming the key"

# --- checks across keys name where each key was set -------------------------
printf '[container]\nwidth = 50\norifice_diameter = 60\n' > silo.ini
gf config silo.ini
expect_rc 2 "config silo.ini (orifice wider than the box)"
expect_err "silo.ini:3: container.orifice_diameter = 60 must be less than container.width = 50 (silo.ini:2)" \
    "config silo.ini (orifice wider than the box)"
expect_no_stdout "config silo.ini (orifice wider than the box)"
gf config silo.ini --set container.width=40
expect_err "silo.ini:3: container.orifice_diameter = 60 must be less than container.width = 40 (--set)" \
    "config silo.ini --set container.width=40"
printf '[packing]\ntypes = 1,x\n' > types.ini
gf config types.ini
expect_rc 2 "config types.ini (bad packing.types)"
expect_err "types.ini:2: packing.types = 1,x: 'x' is not an atom type" "config types.ini (bad packing.types)"
ok "cross-key and validation-time errors start with FILE:LINE and quote the other key's place"

printf '[container]\nshape = cylinder\norifice_diameter = 6\n' > cylorifice.ini
gf config cylorifice.ini
expect_rc 2 "config: orifice_diameter in a cylinder"
expect_err "cylorifice.ini:3: container.orifice_diameter = 6 does nothing in a cylinder" "config: orifice_diameter in a cylinder"
expect_err "container.outlet_diameter = 8 (default)" "config: orifice_diameter in a cylinder"
gf config cylinder.ini --set container.outlet_diameter=5
expect_rc 0 "config: a cylinder's effective config with a new outlet"
grep -qx 'orifice_diameter = 5' out || fail "a cylinder's orifice_diameter does not follow a new outlet_diameter"
ok "container.orifice_diameter set in a cylinder exits 2 naming container.outlet_diameter"

# --- --set errors -----------------------------------------------------------
gf config --set spot.w=abc
expect_rc 2 "config --set spot.w=abc"
expect_err "spot.w" "config --set spot.w=abc"
expect_err "abc" "config --set spot.w=abc"
expect_no_stdout "config --set spot.w=abc"
ok "--set spot.w=abc: exit 2 naming spot.w and the value"

gf config --set spot.frobnicate=1
expect_rc 2 "config --set spot.frobnicate=1"
expect_err "frobnicate" "config --set spot.frobnicate=1"
ok "--set of an unknown key: exit 2 naming the key"

gf config --set nosuchsection.w=1
expect_rc 2 "config --set nosuchsection.w=1"
expect_err "nosuchsection" "config --set nosuchsection.w=1"
ok "--set of an unknown section: exit 2 naming the section"

gf config --set relax.alpha=1.5
expect_rc 2 "config --set relax.alpha=1.5"
expect_err "relax.alpha" "config --set relax.alpha=1.5"
expect_err "out of range" "config --set relax.alpha=1.5"
expect_no_stdout "config --set relax.alpha=1.5"
ok "--set relax.alpha=1.5: exit 2, out of range, names relax.alpha"

gf config --set relax.alpha
expect_rc 2 "config --set relax.alpha (no '=')"
expect_err "relax.alpha" "config --set relax.alpha (no '=')"
expect_err "section.key=value" "config --set relax.alpha (no '=')"
ok "malformed --set (no '='): exit 2, shows the expected form"

gf config --set
expect_rc 2 "config --set (no value)"
expect_err "--set" "config --set (no value)"
ok "--set without its argument: exit 2"

gf config --set relax.radius=1
expect_rc 2 "config --set relax.radius=1 (below spot.radius)"
expect_err "relax.radius" "config --set relax.radius=1"
expect_err "spot.radius" "config --set relax.radius=1"
ok "cross-key constraint (relax.radius < spot.radius): exit 2 naming both keys"

# --- errors in a config file: file:line and the key -------------------------
printf '# a comment\n\n[spot]\nradius = 2\n; another comment\nfrobnicate = 3\n' >unknown_key.ini
gf config unknown_key.ini
expect_rc 2 "config unknown_key.ini"
expect_err "unknown_key.ini:6" "config unknown_key.ini (key on line 6)"
expect_err "frobnicate" "config unknown_key.ini"
expect_no_stdout "config unknown_key.ini"
ok "unknown key in a file: exit 2 with unknown_key.ini:6 and the key"

printf '[spot]\nradius = 2\n\n[nosuchsection]\nw = 3\n' >unknown_section.ini
gf config unknown_section.ini
expect_rc 2 "config unknown_section.ini"
expect_err "unknown_section.ini:4" "config unknown_section.ini (section on line 4)"
expect_err "nosuchsection" "config unknown_section.ini"
ok "unknown section in a file: exit 2 with unknown_section.ini:4 and the section"

printf '[run]\nduration = 1\n[relax]\nalpha = 1.5\n' >range.ini
gf config range.ini
expect_rc 2 "config range.ini (relax.alpha = 1.5)"
expect_err "range.ini:4" "config range.ini (value on line 4)"
expect_err "alpha" "config range.ini"
expect_err "1.5" "config range.ini"
ok "out-of-range value in a file: exit 2 with range.ini:4, the key and the value"

printf '[spot]\nw = 12abc\n' >number.ini
gf config number.ini
expect_rc 2 "config number.ini (w = 12abc)"
expect_err "number.ini:2" "config number.ini"
expect_err "12abc" "config number.ini"
ok "malformed number in a file: exit 2 with number.ini:2 and the value"

printf '[spot]\nw 3\n' >syntax.ini
gf config syntax.ini
expect_rc 2 "config syntax.ini (line without '=')"
expect_err "syntax.ini:2" "config syntax.ini"
ok "line without '=' in a file: exit 2 with syntax.ini:2"

printf 'w = 3\n' >nosection.ini
gf config nosection.ini
expect_rc 2 "config nosection.ini (key before any section)"
expect_err "nosection.ini:1" "config nosection.ini"
ok "key outside any section: exit 2 with nosection.ini:1"

# A file error wins over later --set options, and the file's later lines are not needed.
gf config unknown_key.ini --set spot.w=5
expect_rc 2 "config unknown_key.ini --set spot.w=5"
expect_err "unknown_key.ini:6" "config unknown_key.ini --set spot.w=5"
ok "file error reported even when --set options follow"

# --- missing file -----------------------------------------------------------
gf config no_such_file.ini
[ "$RC" -eq 1 ] || [ "$RC" -eq 2 ] || fail "config no_such_file.ini: expected exit code 1 or 2, got $RC"
expect_err "no_such_file.ini" "config no_such_file.ini"
expect_no_stdout "config no_such_file.ini"
ok "missing config file: exit $RC naming no_such_file.ini"

# --- options and commands ---------------------------------------------------
for cmd in config run pack; do
    gf "$cmd" --frobnicate
    expect_rc 2 "$cmd --frobnicate"
    expect_err "--frobnicate" "$cmd --frobnicate"
done
ok "unknown option --frobnicate: exit 2 naming it (config, run, pack)"

gf frobnicate
expect_rc 2 "granflow frobnicate"
expect_err "frobnicate" "granflow frobnicate"
ok "unknown command: exit 2 naming it"

gf help
expect_rc 0 "granflow help"
for word in run pack config bench; do
    grep -qw -- "$word" out || fail "granflow help does not mention '$word'"
done
# Every option a command takes is in its synopsis (granflow CMD --help; and in the README's).
for cmd in analyze calibrate compare; do
    line=$("$GF" "$cmd" --help | sed -n '1,2p')
    readme=$(grep -E "^granflow $cmd " "$DATA/../../README.md")
    for opt in --timestep --config --set; do
        grep -qF -- "$opt" <<<"$line" || fail "granflow $cmd --help: the synopsis lacks $opt"
        grep -qF -- "$opt" <<<"$readme" || fail "README: the granflow $cmd synopsis lacks $opt"
    done
done
ok "granflow help: exit 0, mentions run, pack, config, bench"

gf --help
expect_rc 0 "granflow --help"
grep -qw bench out || fail "granflow --help does not print the usage"
ok "granflow --help: exit 0 with the usage"

# --- an extra positional argument must not be silently ignored -------------
gf config default.ini custom.ini
expect_rc 2 "config default.ini custom.ini (two CONFIG files; the second was silently ignored)"
expect_err "custom.ini" "config default.ini custom.ini"
ok "extra positional argument: exit 2 naming it"

echo "cli $NAME: $PASS passed, 0 failed"
exit 0
