#!/usr/bin/env bash
# CLI test: `granflow render DIR` draws a small run: by default three layer
# slices, one phi slice and a contact sheet, all valid PNG files of the
# documented size; --times/--colour (layer, phi, phi-raw)/--format/--sheet/-o choose other
# pictures; bad options exit 2, a missing run 1, a malformed snapshot 3, and
# no temporary file is left behind.
# usage: bash tests/cli/render.sh GRANFLOW_BINARY TESTS_DATA_DIR
NAME=render
source "$(dirname "$0")/lib.bash" "$@"

# is_png FILE: starts with the 8-byte PNG signature.
is_png() { [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ]; }
# png_size FILE: "WIDTH HEIGHT" from the IHDR chunk (bytes 17-24, big-endian).
png_size() { od -An -tu1 -j16 -N8 "$1" | awk '{ print $1*16777216 + $2*65536 + $3*256 + $4, $5*16777216 + $6*65536 + $7*256 + $8 }'; }
no_tmp() { [ -z "$(find "$1" -name '*.tmp')" ] || fail "$2 left temporary files: $(find "$1" -name '*.tmp')"; }

# A 12 x 6 silo with a 5 d orifice, 1500 particles, 4 tau, a snapshot every tau (5 frames).
gf run -q --set packing.particles=1500 --set container.width=12 --set container.depth=6 \
    --set container.orifice_diameter=5 --set run.duration=4 --set output.snapshot_interval=1 -o run
expect_rc 0 "run (1500 particles, 4 tau)"
[ "$(ls run/snapshots | wc -l)" -eq 5 ] || fail "run: expected 5 snapshots, got $(ls run/snapshots | wc -l)"

# --- defaults -------------------------------------------------------------------
gf render run
expect_rc 0 "render run"
for f in slice_000000.png slice_000002.png slice_000004.png slice_000004_phi.png sheet.png; do
    [ -s "run/render/$f" ] || fail "render run: run/render/$f missing or empty"
    is_png "run/render/$f" || fail "render run: run/render/$f is not a PNG file"
    grep -qxF "run/render/$f" out || fail "render run: stdout does not list run/render/$f"
done
[ "$(ls run/render | wc -l)" -eq 5 ] || fail "render run: expected 5 files in run/render, got: $(ls run/render | tr '\n' ' ')"
no_tmp run "render run"
ok "render writes first/middle/last layer slices, a phi slice and a contact sheet (PNG)"

# 10 px per d: width (12 + 4) d = 160 px; the phi slice adds the colour bar (10 d = 100 px).
read -r w h < <(png_size run/render/slice_000000.png)
[ "$w" -eq 160 ] || fail "slice_000000.png is $w px wide, expected (12 + 4) d x 10 px = 160"
[ "$h" -gt 100 ] && [ "$h" -lt 1000 ] || fail "slice_000000.png is $h px tall"
read -r w2 h2 < <(png_size run/render/slice_000004.png)
[ "$w2" -eq 160 ] && [ "$h2" -eq "$h" ] || fail "slices differ in size ($w x $h and $w2 x $h2)"
read -r w h < <(png_size run/render/slice_000004_phi.png)
[ "$w" -eq 260 ] || fail "slice_000004_phi.png is $w px wide, expected 160 + 100 for the colour bar"
# the sheet: 5 panels at half scale, (12 + 4) d x 5 px = 80 px each
read -r w h < <(png_size run/render/sheet.png)
[ "$w" -eq 400 ] || fail "sheet.png is $w px wide, expected 5 panels x 80 px"
ok "picture sizes follow the scale (slices 160 px, phi + bar 260 px, sheet 5 x 80 px)"

gf render run --scale 6 -o scaled -q
expect_rc 0 "render --scale 6"
read -r w h < <(png_size scaled/slice_000000.png)
[ "$w" -eq 96 ] || fail "--scale 6: slice is $w px wide, expected 16 d x 6 px = 96"
[ ! -s out ] || fail "render -q printed: $(head -n 3 out)"
ok "--scale 6 gives 96 px wide slices; -q prints nothing"

# --- choosing pictures --------------------------------------------------------------
gf render run --times 1,3.2 --colour phi --format svg -o sel
expect_rc 0 "render --times 1,3.2 --colour phi --format svg"
[ "$(ls sel | tr '\n' ' ')" = "slice_000001_phi.svg slice_000003_phi.svg " ] ||
    fail "--times 1,3.2 --colour phi --format svg: expected slice_000001_phi.svg slice_000003_phi.svg, got: $(ls sel | tr '\n' ' ')"
head -c 200 sel/slice_000001_phi.svg | grep -q -e '<?xml' -e '<svg' || fail "slice_000001_phi.svg is not SVG"
tail -c 100 sel/slice_000001_phi.svg | grep -q '</svg>' || fail "slice_000001_phi.svg is not complete"
expect_err "t = 3.2" "--times 3.2 (no snapshot there)"
ok "--times picks the nearest snapshots (and says so), --colour phi, --format svg"

# phi (the 2.2 d average, Fig. 4) and phi-raw (each particle's own cell, Fig. 6)
# are different pictures of the same size, with their own file names.
gf render run --times 4 --colour phi-raw -o raw
expect_rc 0 "render --times 4 --colour phi-raw"
[ "$(ls raw | tr '\n' ' ')" = "slice_000004_phi_raw.png " ] ||
    fail "--colour phi-raw: expected slice_000004_phi_raw.png, got: $(ls raw | tr '\n' ' ')"
is_png raw/slice_000004_phi_raw.png || fail "slice_000004_phi_raw.png is not a PNG file"
[ "$(png_size raw/slice_000004_phi_raw.png)" = "$(png_size run/render/slice_000004_phi.png)" ] ||
    fail "phi-raw slice is $(png_size raw/slice_000004_phi_raw.png), the phi slice $(png_size run/render/slice_000004_phi.png)"
! cmp -s raw/slice_000004_phi_raw.png run/render/slice_000004_phi.png ||
    fail "--colour phi-raw drew the same picture as the averaged phi slice"
gf render run --times 4 --colour phi -o avg -q
expect_rc 0 "render --times 4 --colour phi"
cmp -s avg/slice_000004_phi.png run/render/slice_000004_phi.png ||
    fail "--colour phi differs from the default phi slice (both should be the 2.2 d average)"
gf render run --sheet --colour phi-raw -q -o rawsheet
expect_rc 0 "render --sheet --colour phi-raw"
[ "$(ls rawsheet)" = sheet_phi_raw.png ] || fail "--sheet --colour phi-raw: expected sheet_phi_raw.png, got: $(ls rawsheet | tr '\n' ' ')"
ok "--colour phi-raw draws each particle's own packing fraction (*_phi_raw.png), unlike the averaged phi"

gf render run --sheet --format pdf -o sh
expect_rc 0 "render --sheet --format pdf"
[ "$(ls sh)" = sheet.pdf ] || fail "--sheet --format pdf: expected only sheet.pdf, got: $(ls sh | tr '\n' ' ')"
[ "$(head -c 4 sh/sheet.pdf)" = "%PDF" ] || fail "sheet.pdf does not start with %PDF"
ok "--sheet --format pdf writes only sheet.pdf"

gf render run --all -q -o all
expect_rc 0 "render --all"
[ "$(ls all | wc -l)" -eq 5 ] || fail "--all: expected 5 slices, got: $(ls all | tr '\n' ' ')"
ok "--all draws every snapshot"

# --- errors -----------------------------------------------------------------
gf render run --colour pink
expect_rc 2 "render --colour pink"
expect_err "--colour" "render --colour pink"
expect_err "phi-raw" "render --colour pink (lists the choices)"
gf render run --scale 0
expect_rc 2 "render --scale 0"
gf render run --format gif
expect_rc 2 "render --format gif"
gf render run --times 1,x
expect_rc 2 "render --times 1,x"
gf render run --frobnicate
expect_rc 2 "render --frobnicate"
expect_err "--frobnicate" "render --frobnicate"
gf render
expect_rc 2 "render without a directory"
ok "bad options and a missing DIR argument: exit 2 naming the option"

gf render no_such_run
expect_rc 1 "render no_such_run"
expect_err "no_such_run" "render no_such_run"
mkdir empty
gf render empty
expect_rc 2 "render of a directory without snapshots"
expect_err "empty" "render of a directory without snapshots"
ok "a missing run or one without snapshots: exit 1 (missing) or 2 (no snapshots: the command line names nothing to draw), naming it"

mkdir -p bad/snapshots
cp run/config.ini bad/
cp run/snapshots/snap_000000.dump bad/snapshots/
size=$(wc -c <run/snapshots/snap_000001.dump)
head -c $((size / 2)) run/snapshots/snap_000001.dump >bad/snapshots/snap_000001.dump
gf render bad
expect_rc 3 "render of a run with a truncated snapshot"
expect_err "snap_000001.dump" "render of a run with a truncated snapshot"
[ ! -e bad/render ] || [ -z "$(ls bad/render)" ] || fail "render of a bad run wrote: $(ls bad/render)"
ok "a truncated snapshot: exit 3 naming it, no pictures"

echo "cli $NAME: $PASS passed, 0 failed"
exit 0
