#!/usr/bin/env bash
# Layout test of `granflow report` in a browser: headless Chromium draws the
# page of a run directory whose pictures are solid colours of known sizes,
# and the screenshots are measured (tests/tools/png_probe: the box of each
# colour's pixels), so the test checks where and how large each picture is,
# not only that the page loads:
#   - the contact sheet (render/sheet.png) spans >= 90% of a 1280-pixel
#     window, above the other pictures, its aspect kept;
#   - a plot (analysis/outflow.png) fills one column of two (30-50% of the
#     width), its aspect kept; a slice is no wider than a column;
#   - the plots of measurements left out (zones of a box silo without
#     recirculation, the surface of a surface that did not move) are not drawn;
#   - a click enlarges: with the sheet's checkbox ticked (what a click on it
#     does) it covers the window's width on a dark backdrop, and so does a plot.
# Exit 77 (CTest SKIP_RETURN_CODE) when chromium is not installed.
# usage: bash tests/report_layout.sh GRANFLOW_BINARY TESTS_DATA_DIR PNG_PROBE
NAME=report_layout
if ! command -v chromium >/dev/null; then
    echo "cli $NAME: skipped: chromium is not installed (scripts/deps.sh installs it)"
    exit 77
fi
PROBE=${3:?usage: $0 GRANFLOW_BINARY TESTS_DATA_DIR PNG_PROBE}
case $PROBE in /*) ;; *) PROBE=$PWD/$PROBE ;; esac
source "$(dirname "$0")/cli/lib.bash" "$@"
[ -x "$PROBE" ] || fail "$PROBE is not an executable"

W=1280
# shot HTML PNG HEIGHT: Chromium's screenshot of the page, W x HEIGHT.
shot() {
    timeout 120 chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --user-data-dir="$T/chrome" \
        --window-size=$W,$3 --screenshot="$T/$2" "file://$T/$1" >/dev/null 2>&1
    [ -s "$T/$2" ] || fail "chromium wrote no $2"
    [ "$("$PROBE" size "$T/$2")" = "$W $3" ] || fail "$2 is $("$PROBE" size "$T/$2"), not $W x $3"
}
# box PNG COLOUR: sets X0 Y0 X1 Y1 (the box of the colour's pixels) and BW BH (its size); fails when absent.
box() {
    local b
    b=$("$PROBE" box "$T/$1" "$2") || fail "png_probe box $1 $2"
    [ "$b" != none ] || fail "$1: no pixel of colour $2 (the picture is not drawn)"
    read -r X0 Y0 X1 Y1 _ <<<"$b"
    BW=$((X1 - X0 + 1)) BH=$((Y1 - Y0 + 1))
}
# aspect WHAT W H: the box BW x BH has the aspect of a W x H picture, within 2%.
aspect() {
    awk -v bw="$BW" -v bh="$BH" -v w="$2" -v h="$3" 'BEGIN { r = (bh / bw) / (h / w); exit !(r > 0.98 && r < 1.02) }' ||
        fail "$1 drawn $BW x $BH, not in the aspect of its $2 x $3 picture"
}

# A run directory: a box silo without recirculation, a surface that did not move.
mkdir -p run/analysis run/render
printf '[container]\nshape = box\n[run]\nrecirculate = off\n' > run/config.ini
cat > run/summary.json <<'EOF'
{
  "status": "complete",
  "particles_initial": 1500,
  "particles_exited": 125,
  "particles_reinserted": 0,
  "simulated_time": 4,
  "steps_per_second": 68973.5
}
EOF
cat > run/analysis/summary.json <<'EOF'
{
  "frames": 5,
  "flow_rate": 39.69080648,
  "surface_angle": -0.3519371912,
  "badness": 1.411590747e-07,
  "zones_count": 4,
  "transit_mean": 2.529206141,
  "passes_max": 1
}
EOF
printf 'time_tau,slope,angle_deg\n0,-0.00614254,-0.3519371912\n1,-0.00614254,-0.3519371912\n' > run/analysis/surface.csv
"$PROBE" make run/render/sheet.png 400 166 ff00ff &&
    "$PROBE" make run/render/slice_000000.png 160 259 ffff00 &&
    "$PROBE" make run/analysis/outflow.png 1100 800 00ffff &&
    "$PROBE" make run/analysis/zones.png 1100 800 ff8000 &&
    "$PROBE" make run/analysis/surface.png 1100 800 808000 || fail "png_probe make"
gf report run -q
expect_rc 0 "report run"
ok "a run directory with pictures of known colours and sizes, reported"

shot run/report.html page.png 2400
box page.png ff00ff
sheet_y0=$Y0
[ "$BW" -ge $((W * 90 / 100)) ] || fail "the contact sheet is $BW pixels wide, under 90% of the $W-pixel window"
[ "$X0" -le $((W * 5 / 100)) ] || fail "the contact sheet starts at x = $X0, not at the window's left edge"
aspect "the contact sheet" 400 166
ok "the contact sheet spans $BW of $W pixels ($X0..$X1), $BH tall, aspect kept"

box page.png 00ffff
[ "$BW" -ge $((W * 30 / 100)) ] && [ "$BW" -le $((W * 50 / 100)) ] ||
    fail "the outflow plot is $BW pixels wide: not one column of two (30-50% of $W)"
aspect "the outflow plot" 1100 800
plot_w=$BW
[ "$Y1" -lt "$sheet_y0" ] || fail "the contact sheet (y = $sheet_y0) is not below the analysis' plots (to y = $Y1)"
box page.png ffff00
[ "$BW" -le $((W * 50 / 100)) ] || fail "a slice is $BW pixels wide, wider than a column"
ok "a plot fills one column of two ($plot_w of $W pixels wide), under it the sheet, then the slices"

for c in ff8000 808000; do
    [ "$("$PROBE" box "$T/page.png" $c)" = none ] || fail "a plot left out (colour $c) is drawn"
done
ok "the zones and surface plots, left out for this run, are not drawn"

# A click ticks the picture's hidden checkbox; the page with it ticked shows
# what the click shows.
sed 's/<figure class="sheet"><input type="checkbox"/& checked/' run/report.html > zoom_sheet.html
grep -q 'class="sheet"><input type="checkbox" checked' zoom_sheet.html || fail "no checkbox on the contact sheet"
shot zoom_sheet.html zoom_sheet.png 900
box zoom_sheet.png ff00ff
[ "$BW" -ge $((W * 95 / 100)) ] || fail "the enlarged contact sheet is $BW pixels wide, not the window's width"
[ "$Y0" -le 40 ] || fail "the enlarged contact sheet starts at y = $Y0, not at the top of the window"
corner=$("$PROBE" pixel "$T/zoom_sheet.png" $((W - 3)) 897)
[ $((16#${corner:0:2})) -lt 80 ] || fail "no dark backdrop behind the enlarged sheet (corner pixel $corner)"
sed 's/\(<input type="checkbox" class="zoom" id="zoom0"\)/\1 checked/' run/report.html > zoom_plot.html
shot zoom_plot.html zoom_plot.png 900
box zoom_plot.png 00ffff
[ "$BW" -ge $((W * 95 / 100)) ] || fail "the enlarged outflow plot is $BW pixels wide, not the window's width"
ok "a click enlarges: the sheet and a plot cover the window's width on a dark backdrop"
# GF_REPORT_KEEP=DIR keeps the screenshots (to look at them).
[ -n "${GF_REPORT_KEEP:-}" ] && cp page.png zoom_sheet.png zoom_plot.png "$GF_REPORT_KEEP"/
echo "cli $NAME: $PASS passed"
