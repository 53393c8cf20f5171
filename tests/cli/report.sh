#!/usr/bin/env bash
# CLI test: `granflow report DIR` writes DIR/report.html, one self-contained
# page: every picture of analysis/, render/ and compare/ inlined as a data URI
# (the first decodes back to the very bytes of its PNG), the run and analysis
# summaries (in words, with units, 4 significant digits; what means nothing
# for the run left out with the reason), the DEM comparison table with the
# DEM and spot slices side by side, and config.ini; nothing refers to another file. An LGA run's sheet and
# density maps are all on its page. Headless Chromium
# (scripts/deps.sh installs it) renders the page to a PNG that must carry far
# more than a blank page does. Bad arguments exit 2.
# usage: bash tests/cli/report.sh GRANFLOW_BINARY TESTS_DATA_DIR
NAME=report
source "$(dirname "$0")/lib.bash" "$@"

SILO=(--set packing.particles=1500 --set container.width=12 --set container.depth=6
      --set container.orifice_diameter=5 --set run.duration=4 --set output.snapshot_interval=1)
gf run -q "${SILO[@]}" -o run
expect_rc 0 "run"
gf analyze run
expect_rc 0 "analyze"
gf render run
expect_rc 0 "render"
# A second run (another seed) stands in for the DEM: compare reads LAMMPS dumps.
gf run -q "${SILO[@]}" --set run.seed=2 -o dem
expect_rc 0 "run (seed 2)"
gf compare dem run
expect_rc 0 "compare dem run"
[ -f run/compare/summary.csv ] || fail "compare wrote no run/compare/summary.csv"
ok "a small run, analysed, rendered and compared"

gf report run
expect_rc 0 "report run"
H=run/report.html
[ -s $H ] || fail "no $H"
expect_err "run/report.html"
ok "report run writes run/report.html"

# Every picture is on the page, inlined, but the plots left out as not
# meaningful for this run (listed on the page; the zones of this box silo
# without recirculation among them); nothing points elsewhere.
left=$(sed -n 's/.*<p class="omit">Plots left out[^:]*: \(.*\)\.<\/p>.*/\1/p' $H | tr -d ' ' | tr ',' '\n')
echo "$left" | grep -qx zones || fail "report: the zones plot of a box silo without recirculation is not left out"
for m in $left; do
    [ -f run/analysis/$m.png ] || fail "report: lists $m as left out, but there is no run/analysis/$m.png"
    grep -q "alt=\"$m: " $H && fail "report: the plot $m is listed as left out, and drawn"
done
pics=$(ls run/analysis/*.png run/render/*.png run/compare/*.png | wc -l)
nleft=$(echo "$left" | grep -c .)
imgs=$(grep -o '<img src="data:image/png;base64,' $H | wc -l)
[ "$imgs" -eq $((pics - nleft)) ] || fail "report: $imgs inlined images, $pics pictures in the run, $nleft left out"
grep -Eo '(src|href)="[^"]{0,12}' $H | grep -v '"data:' && fail "report refers to other files"
ok "all $pics pictures but the $nleft left out ($(echo $left)) inlined, no external references"

# The first image is analysis/outflow.png (measurements in their order), byte for byte.
sed -n 's/.*<img src="data:image\/png;base64,\([^"]*\)".*/\1/p' $H | head -1 | base64 -d > first.png
cmp -s first.png run/analysis/outflow.png || fail "the first inlined image does not decode to analysis/outflow.png"
ok "the base64 of outflow.png decodes to the file"

# Summaries, comparison and config on the page, with the run's own values:
# each row the quantity in words, the value (4 significant digits), the unit
# and the key; what is left out, with the reason.
exited=$(sed -n 's/.*"particles_exited": \([0-9]*\).*/\1/p' run/summary.json)
grep -q "<tr><th>particles that left through the orifice</th><td class=\"num\">$exited</td><td>particles</td><td><code>particles_exited</code></td></tr>" $H ||
    fail "report: no particles_exited = $exited row in words with its unit"
rate=$(sed -n 's/.*"flow_rate": \([0-9.e+-]*\).*/\1/p' run/analysis/summary.json)
rate4=$(awk -v r="$rate" 'BEGIN { printf "%.4g", r }')
grep -q "<tr><th>steady outflow rate</th><td class=\"num\">$rate4</td><td>particles/tau</td><td><code>flow_rate</code></td></tr>" $H ||
    fail "report: no flow_rate = $rate4 (4 digits of $rate) row in words with its unit"
grep -q "<th>Quantity</th><th>Value</th><th>Unit</th><th>Key</th>" $H || fail "report: no Quantity/Value/Unit/Key header"
grep -q "<li>radial zones (<code>zones_count</code>), .*: a box silo without recirculation" $H ||
    fail "report: the zones of a box silo without recirculation are not left out with the reason"
grep -q "<td><code>zones_count</code>" $H && fail "report: zones_count is still in a table"
grep -q "DEM and spot model side by side" $H || fail "report: no comparison section"
grep -q "<th>Quantity</th><th>dem</th><th>spot</th><th>difference</th><th>relative difference</th><th>Unit</th><th>Key</th>" $H ||
    fail "report: no comparison table in words with units"
grep -q '<figure class="sheet"><input type="checkbox" class="zoom" id="zoom[0-9]*"><label class="zoom" for="zoom[0-9]*"><img src="data:image/png;base64,' $H ||
    fail "report: the contact sheet is not a full-width figure that a click enlarges"
grep -q 'alt="DEM: central slices"' $H && grep -q 'alt="spot model: central slices' $H ||
  fail "report: the DEM and spot slices are not both there"
grep -q "^orifice_diameter = 5$" $H || fail "report: config.ini (orifice_diameter = 5) not on the page"
ok "summaries, DEM comparison and config on the page"

# -o elsewhere; a directory without a run; bad arguments.
gf report run -o elsewhere.html -q
expect_rc 0 "report -o"
cmp -s elsewhere.html $H || fail "report -o writes a different page"
mkdir empty
gf report empty
expect_rc 2 "report of an empty directory"
expect_err "not a run directory"
gf report
expect_rc 2 "report without DIR"
gf report run --set spot.radius=2
expect_rc 2 "report with --set"
[ -z "$(find . -name '*.tmp')" ] || fail "temporary files left: $(find . -name '*.tmp')"
ok "-o, an empty directory (2), missing DIR (2), --set (2)"

# An LGA run directory: its sheet and every density map.
gf lga -q --set lga.scenario=pile --set lga.iterations=300 -o lga
expect_rc 0 "lga pile, 300 iterations"
gf report lga -q
expect_rc 0 "report lga"
pics=$(ls lga/*.png lga/maps/*.png | wc -l)
imgs=$(grep -o '<img src="data:image/png;base64,' lga/report.html | wc -l)
[ "$imgs" -eq "$pics" ] && [ "$pics" -gt 2 ] || fail "report lga: $imgs inlined images, $pics pictures"
grep -q "^scenario = pile$" lga/report.html || fail "report lga: config not on the page"
ok "an LGA run: all $pics pictures inlined"

# Rendered by a browser: the page draws far more than a blank one (where
# chromium is installed; report.layout measures the layout).
if ! command -v chromium >/dev/null; then
    echo "cli $NAME: $PASS passed (the browser check skipped: no chromium)"
    exit 0
fi
shot() { # HTML PNG
  timeout 120 chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --user-data-dir="$T/chrome" \
    --window-size=1280,4000 --screenshot="$T/$2" "file://$T/$1" >/dev/null 2>&1
  [ -s "$T/$2" ] || fail "chromium wrote no $2"
  [ "$(head -c 8 "$T/$2" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || fail "$2 is not a PNG"
}
printf '<!DOCTYPE html><html><body></body></html>\n' > blank.html
shot blank.html blank.png
shot $H report.png
b=$(stat -c %s blank.png) r=$(stat -c %s report.png)
[ "$r" -gt $((20 * b)) ] || fail "the rendered report ($r bytes) is not much more than a blank page ($b bytes)"
size=$(od -An -tu1 -j16 -N8 report.png | awk '{ print $1*16777216 + $2*65536 + $3*256 + $4 "x" $5*16777216 + $6*65536 + $7*256 + $8 }')
[ "$size" = 1280x4000 ] || fail "report.png is $size, not 1280x4000"
[ -n "${GF_REPORT_KEEP:-}" ] && cp report.png "$GF_REPORT_KEEP"
ok "chromium renders the page: $r bytes of PNG against $b for a blank page"
echo "cli $NAME: $PASS passed"
