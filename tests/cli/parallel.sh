#!/usr/bin/env bash
# CLI test: the parallel spatial fixed step writes byte-identical run
# directories (snapshots, exits) with 1, 2 and 4 threads, and `granflow bench`
# reports its figures (one thread and all, efficiency, memory, projected
# drainage, the 10x silo) as JSON. Nothing here is timed.
# ctest: nosan (the same bytes for any thread count is checked under the
# sanitizers by the parallel.* and domains.* suites, bench's figures by bench.*)
# usage: bash tests/cli/parallel.sh GRANFLOW_BINARY TESTS_DATA_DIR
NAME=parallel
source "$(dirname "$0")/lib.bash" "$@"

# A 12 x 6 silo of 4000 spheres whose spots climb fast enough (step_z 0.2) to
# fill several slabs within 5 tau, so two slabs of a colour run side by side.
SILO=(--set container.width=12 --set container.depth=6 --set packing.particles=4000
      --set spot.step_z=0.2 --set spot.insertion_rate=150 --set run.mode=fixed --set run.order=spatial
      --set run.duration=5 --set output.snapshot_interval=1)
for t in 1 2 4; do
    gf run -q "${SILO[@]}" --set run.threads=$t -o "T$t"
    expect_rc 0 "spatial run with $t threads"
done
[ "$(ls T1/snapshots | wc -l)" -eq 6 ] || fail "expected 6 snapshots, got $(ls T1/snapshots | wc -l)"
for t in 2 4; do
    for f in $(cd T1 && ls snapshots/*.dump) exits.csv; do
        cmp -s "T1/$f" "T$t/$f" || fail "T$t/$f differs from T1/$f (1 thread)"
    done
done
ok "1, 2 and 4 threads: byte-identical snapshots and exits"
[ "$(wc -l <T1/exits.csv)" -gt 20 ] || fail "the silo did not flow ($(wc -l <T1/exits.csv) lines in exits.csv)"
ok "the silo flows"

# --- bench: every figure issue 7 asks for, on a small silo --------------------
gf bench --json --particles 2000 --set container.width=14 --warmup 2 --window 0.3
expect_rc 0 "bench --json on a small silo"
for key in spot_us relax_us step_us steps_per_second steps_per_second_1thread parallel_efficiency threads \
           memory_bytes_per_particle peak_rss_bytes_per_particle projected_drain_seconds large_particles \
           large_step_us large_steps_per_second; do
    grep -q "\"$key\": " out || fail "bench --json has no $key"
done
ok "bench --json reports all its keys"
python3 - "$T/out" <<'EOF' || fail "bench figures out of range: $(cat "$T/out")"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["engine"] == "domains" and d["particles"] == 2000 and d["large_particles"] == 20000
assert d["domains"] >= 1 and d["barriers_per_tau"] > 0 and d["peak_rss_bytes"] > 0
assert "projected_speedup_256" in d and "exchange_bytes_per_phase_per_domain" in d
# One process: one rank, its peak RSS, nothing exchanged, every particle in its region (issue 23).
assert d["ranks"] == 1 and len(d["rank_peak_rss_bytes"]) == 1 and 0 < d["rank_peak_rss_bytes"][0] <= d["peak_rss_bytes"]
assert d["rank_exchange_bytes_per_phase"] == [0]
assert 0 < d["rank_region_particles"][0] <= 2000 and d["rank_slab_particles"] == d["rank_region_particles"]
assert d["steps_per_second"] > 0 and d["steps_per_second_1thread"] > 0 and d["step_us"] > 0
assert 0 < d["parallel_efficiency"] <= 1.5
assert 50 < d["memory_bytes_per_particle"] < 5000
assert d["projected_drain_seconds"] > 0
EOF
ok "bench figures are positive and in range"
gf bench --json --particles 2000 --set container.width=14 --warmup 0.5 --window 0.1 --spatial --no-large
expect_rc 0 "bench --spatial --no-large"
grep -q '"engine": "spatial"' out || fail "bench --spatial did not time the spatial engine"
ok "bench --spatial times the spatial fixed step"
gf bench --json --particles 2000 --set container.width=14 --warmup 0.5 --window 0.1 --sweep --no-large
expect_rc 0 "bench --sweep --no-large"
python3 - "$T/out" <<'EOF' || fail "bench --sweep figures out of range: $(cat "$T/out")"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["engine"] == "sweep" and d["blocks"] > 0 and d["barriers_per_tau"] > 0
assert 0 < d["serial_fraction"] < 1
assert 1 <= d["projected_speedup_2"] <= d["projected_speedup_16"] <= d["projected_speedup_256"]
EOF
ok "bench --sweep times the sweep engine and projects its speedup"
gf bench --json --particles 2000 --set container.width=14 --warmup 1 --window 0.2 --event --no-large
expect_rc 0 "bench --event --no-large"
grep -q '"engine": "event"' out || fail "bench --event did not time the event engine"
grep -q '"large_particles"' out && fail "bench --no-large still timed the large silo"
ok "bench --event --no-large"
echo "cli $NAME: $PASS passed"
