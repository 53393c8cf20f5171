#!/usr/bin/env bash
# CLI test: granflow reads its summary.json files with a JSON library
# (jansson), so the same file re-saved in another layout reads the same:
# compact JSON (as `json.dump`, `jq -c` write it) gives `granflow report` the
# same tables, and `granflow analyze NAME` keeps the other measurements'
# numbers from it. A summary.json that is not JSON fails both with exit 3 and
# the file and line, and leaves no page or summary half-written.
# usage: bash tests/cli/json_read.sh GRANFLOW_BINARY TESTS_DATA_DIR
NAME=json_read
source "$(dirname "$0")/lib.bash" "$@"

gf run -q --set packing.particles=1500 --set container.width=12 --set container.depth=6 \
   --set container.orifice_diameter=5 --set run.duration=3 --set output.snapshot_interval=1 -o run
expect_rc 0 "run (1500 particles, 3 tau)"
gf analyze run -q --no-plots
expect_rc 0 "analyze"
gf report run -q -o pretty.html
expect_rc 0 "report (pretty summary.json)"

# Both summaries re-saved as compact JSON, members in the same order.
compact() { python3 -c 'import json, sys; d = json.load(open(sys.argv[1]))
open(sys.argv[1], "w").write(json.dumps(d, separators=(",", ":")))' "$1"; }
cp run/analysis/summary.json pretty_analysis.json
compact run/summary.json
compact run/analysis/summary.json
[ "$(wc -l < run/summary.json)" -eq 0 ] || fail "python did not write compact JSON"
gf report run -q -o compact.html
expect_rc 0 "report (compact summary.json)"
tables() { sed -n '/<table class="kv">/,/<\/table>/p' "$1"; }
[ -n "$(tables pretty.html)" ] || fail "no key-value tables in pretty.html"
diff <(tables pretty.html) <(tables compact.html) > tables.diff ||
  fail "compact summary.json gives other tables: $(head -5 tables.diff)"
exited=$(python3 -c 'import json; print(json.load(open("run/summary.json"))["particles_exited"])')
grep -q "<td class=\"num\">$exited</td><td>particles</td><td><code>particles_exited</code>" compact.html ||
  fail "no particles_exited = $exited row"
ok "report: compact summary.json, the same tables as the pretty one"

# analyze NAME reads the compact analysis/summary.json and keeps the other numbers.
gf analyze outflow run -q --no-plots
expect_rc 0 "analyze outflow (compact summary.json)"
python3 - run/analysis/summary.json pretty_analysis.json <<'PY' || fail "analyze outflow lost numbers of the compact summary.json"
import json, sys
new, old = (json.load(open(p)) for p in sys.argv[1:])
lost = [k for k in old if k not in new]
assert not lost, lost
assert new["bulk_packing_fraction"] == old["bulk_packing_fraction"]
PY
ok "analyze outflow keeps the other measurements' numbers of a compact summary.json"

# Not JSON: exit 3, the file and line named, nothing half-written.
printf '{\n  "frames": 3,\n  "flow_rate": 1.5.2\n}\n' > run/analysis/summary.json
cp run/analysis/summary.json broken.json
gf analyze outflow run -q --no-plots
expect_rc 3 "analyze outflow (broken summary.json)"
expect_err "run/analysis/summary.json:3:"
cmp -s broken.json run/analysis/summary.json || fail "analyze rewrote the broken summary.json"
rm -f run/report.html
gf report run -q
expect_rc 3 "report (broken summary.json)"
expect_err "run/analysis/summary.json:3:"
[ -e run/report.html ] && fail "report wrote a page from a broken summary.json"
[ -z "$(find . -name '*.tmp')" ] || fail "temporary files left: $(find . -name '*.tmp')"
ok "a summary.json that is not JSON: exit 3 naming file and line, nothing written"
echo "cli $NAME: $PASS passed"
