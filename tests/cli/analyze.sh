#!/usr/bin/env bash
# CLI test: `granflow analyze` on a short real run writes every measurement's
# CSV files and plot, and headline numbers within sanity bounds (flow rate > 0,
# 0.5 < phi < 0.7 in the bulk); one measurement alone updates its numbers and
# keeps the others'; bad options and unknown names exit 2, a missing run 1.
# usage: bash tests/cli/analyze.sh GRANFLOW_BINARY TESTS_DATA_DIR
NAME=analyze
source "$(dirname "$0")/lib.bash" "$@"

# A 20 x 8 silo, 4000 particles (~22 d tall), 12 tau, a snapshot every tau.
gf run -q --set packing.particles=4000 --set container.width=20 --set run.duration=12 \
    --set output.snapshot_interval=1 -o run
expect_rc 0 "run (4000 particles, 12 tau)"

# The papers' regions and heights sit higher than this small silo: scale them down.
SETS=(--set velocity.heights=4,8,12 --set velocity.y_z0=6 --set velocity.y_z1=14
      --set diffusion.z0=12 --set diffusion.xhalf=4 --set correlation.size=8 --set correlation.zc=10
      --set gr.x0=-7 --set gr.x1=7 --set gr.z0=4 --set gr.z1=14 --set density.z0=5 --set density.z1=15
      --set surface.dx=1.0 --set window.t0=4)
gf analyze run "${SETS[@]}"
expect_rc 0 "analyze run"
A=run/analysis
for f in outflow density surface rtd rtd_hist velocity_field velocity_profiles velocity_variance \
         velocity_depth diffusion correlation gr g3 badness voronoi voronoi_profile; do
    [ -s "$A/$f.csv" ] || fail "analyze: $A/$f.csv missing or empty"
    [ "$(wc -l < "$A/$f.csv")" -ge 2 ] || fail "analyze: $A/$f.csv has no data rows"
done
ok "every measurement wrote its CSV files"
for m in outflow velocity diffusion correlation gr voronoi density surface badness rtd; do
    [ -s "$A/$m.png" ] || fail "analyze: plot $A/$m.png missing"
    [ "$(head -c 4 "$A/$m.png" | od -An -c | tr -d ' ')" = '211PNG' ] || fail "$A/$m.png is not a PNG"
    [ -s "$A/$m.gp" ] || fail "analyze: gnuplot script $A/$m.gp missing"
done
ok "every measurement drew its plot (PNG) from a kept gnuplot script"
grep -q 'skipped' "$A/summary.json" && fail "analyze: some measurement was skipped: $(grep skipped "$A/summary.json")"

# Headline numbers: present and sane.
num() { sed -n "s/^ *\"$1\": \([-0-9.eE+]*\),\{0,1\}$/\1/p" "$A/summary.json"; }
for k in flow_rate velocity_variance_slope velocity_variance_intercept diffusion_length correlation_length \
         bulk_packing_fraction badness surface_angle; do
    [ -n "$(num $k)" ] || fail "summary.json: no number for $k: $(grep "\"$k\"" "$A/summary.json")"
done
awk -v v="$(num flow_rate)" 'BEGIN { exit !(v > 0) }' || fail "flow_rate $(num flow_rate) is not > 0"
awk -v v="$(num bulk_packing_fraction)" 'BEGIN { exit !(v > 0.5 && v < 0.7) }' ||
    fail "bulk_packing_fraction $(num bulk_packing_fraction) is not in (0.5, 0.7)"
awk -v v="$(num badness)" 'BEGIN { exit !(v >= 0 && v < 0.01) }' || fail "badness $(num badness) is not in [0, 0.01)"
ok "summary.json: flow rate $(num flow_rate) > 0, bulk phi $(num bulk_packing_fraction), every headline key"

# The same run with gzipped snapshots: the same summary, number for number;
# a snapshot cut short is a data error (rc 3) naming the file.
cp -r run run_gz
rm -rf run_gz/analysis
gzip run_gz/snapshots/*.dump
gf analyze run_gz "${SETS[@]}" --no-plots
expect_rc 0 "analyze run_gz (gzipped snapshots)"
diff <(grep -v '"source"' "$A/summary.json") <(grep -v '"source"' run_gz/analysis/summary.json) > diff.txt ||
    fail "summary.json differs between plain and gzipped snapshots: $(head -5 diff.txt)"
ok "analyze: gzipped snapshots give the same summary.json"
last=$(ls run_gz/snapshots/*.dump.gz | tail -1)
head -c $(($(stat -c %s "$last") / 2)) "$last" > cut.gz && mv cut.gz "$last"
gf analyze outflow run_gz "${SETS[@]}" --no-plots
expect_rc 3 "analyze run_gz with a truncated .gz"
grep -q "$(basename "$last").*truncated gzip file" err || fail "the error does not name the truncated file: $(cat err)"
gf run -q --set packing.file="$last" -o run_cut
expect_rc 3 "run --set packing.file=<truncated .gz>"
ok "a truncated .gz is rc 3 with the file named (analyze, run --set packing.file=)"

# One measurement: its numbers change with its options, the others stay.
before=$(num flow_rate)
gf analyze density run "${SETS[@]}" --set density.z0=0 --set density.z1=3
expect_rc 0 "analyze density"
[ "$(num flow_rate)" = "$before" ] || fail "analyze density changed flow_rate ($before -> $(num flow_rate))"
grep -q '^time_tau,count$' "$A/density.csv" || fail "density.csv header: $(head -1 "$A/density.csv")"
ok "analyze NAME DIR reruns one measurement and keeps the other numbers"

gf analyze --list
expect_rc 0 "analyze --list"
[ "$(grep -c '^  [a-z]' out)" -eq 11 ] || fail "analyze --list: expected 11 measurements"
ok "--list names the 11 measurements"

gf analyze nosuch run
expect_rc 2 "unknown measurement"
grep -q "unknown measurement" err || fail "unknown measurement: message"
gf analyze run --set gr.rmax=abc
expect_rc 2 "bad option value"
grep -q "gr.rmax" err || fail "bad option value: message does not name gr.rmax"
gf analyze run --set nosuch.key=1
expect_rc 2 "unknown option key"
grep -q "nosuch.key" err || fail "unknown option key: message does not name it"
gf analyze run --bogus
expect_rc 2 "unknown flag"
gf analyze
expect_rc 2 "no directory"
gf analyze missing-dir
expect_rc 1 "missing run"
grep -q "missing-dir" err || fail "missing run: message does not name the path"
cp run/analysis/summary.json summary_before_window.json
gf analyze run --no-plots --set window.t0=10 --set window.t1=5
expect_rc 2 "reversed window (t0 = 10, t1 = 5)"
expect_err "window.t0 = 10 must be less than window.t1 = 5" "reversed window"
gf analyze run --no-plots --set window.t0=100
expect_rc 2 "window.t0 after the last snapshot"
expect_err "window.t0 = 100 leaves no window: the automatic window.t1 is 12 tau" "window.t0 after the last snapshot"
cmp -s run/analysis/summary.json summary_before_window.json || fail "a refused window changed summary.json"
ok "bad command lines exit 2 naming the key; a missing run exits 1 naming it"

# A run of one snapshot: gnuplot warns of empty ranges and cannot draw some
# plots; its chatter must not reach the terminal, and a plot it cannot draw is
# one warning line naming the script and gnuplot's reason.
gf run -q --set run.duration=0.5 --set packing.particles=800 --set container.width=12 -o tiny
expect_rc 0 "run (one snapshot)"
gf analyze tiny
expect_rc 0 "analyze a one-snapshot run"
if command -v gnuplot >/dev/null; then
    ! grep -q '^Warning\|^plot \|^ *\^' err || fail "gnuplot's own output reached stderr"
    ! grep -q 'gnuplot failed' err || grep -q 'gnuplot failed on .*\.gp: .*line' err ||
        fail "a failed plot's warning does not give gnuplot's reason"
fi
ok "gnuplot's output is kept from the terminal; a failed plot gives its reason"

echo "cli $NAME: $PASS passed"
