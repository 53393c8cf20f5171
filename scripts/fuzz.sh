#!/usr/bin/env bash
# Runs every libFuzzer harness of tests/fuzz (built by `make build-fuzz`) for
# FUZZ_SECONDS each (default 60), starting from its seeds and saved
# regressions (which are all replayed first). A crash, leak, sanitizer report
# or timeout is saved as tests/fuzz/<target>/regressions/<kind>-<sha1>: commit
# it, and `make test` replays it from then on. Exit 1 if any target failed.
# usage: bash scripts/fuzz.sh BUILD_DIR [TARGET...]
set -u
BUILD=${1:?usage: $0 BUILD_DIR [TARGET...]}
shift
SECONDS_EACH=${FUZZ_SECONDS:-60}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
TARGETS=("$@")
# Default: every target, as tests/fuzz/CMakeLists.txt lists them (GF_FUZZ_TARGETS).
[ ${#TARGETS[@]} -gt 0 ] || mapfile -t TARGETS < <(sed -n '/^set(GF_FUZZ_TARGETS/,/)/p' "$ROOT/tests/fuzz/CMakeLists.txt" |
    sed 's/^set(GF_FUZZ_TARGETS//; s/).*//' | tr -s ' \n' '\n' | grep -v '^$')
[ ${#TARGETS[@]} -gt 0 ] || { echo "fuzz: no targets in tests/fuzz/CMakeLists.txt"; exit 1; }
# The harnesses hand each input to the parsers as a file: in memory if possible.
if [ -w /dev/shm ]; then export TMPDIR=/dev/shm/gf-fuzz-$$; else export TMPDIR="$BUILD/fuzz-tmp-$$"; fi
mkdir -p "$TMPDIR"
trap 'rm -rf "$TMPDIR"' EXIT
# FUZZ_JOBS harnesses at a time (default: the number of cores; each is one
# process, and its FUZZ_SECONDS are wall seconds on a core of its own). The
# files the harnesses write carry their pid (tests/fuzz/fuzz_support.c).
JOBS=${FUZZ_JOBS:-$(nproc 2>/dev/null || echo 1)}
# fuzz_one TARGET: runs it, writes its line of the report to $TMPDIR/result-TARGET
# (and its name to $TMPDIR/failed-TARGET when it failed).
fuzz_one() {
    local t=$1 bin="$BUILD/tests/fuzz/fuzz_$1" corpus="$BUILD/corpus/$1" regress="$ROOT/tests/fuzz/$1/regressions"
    local log="$BUILD/fuzz-$t.log" rc runs
    mkdir -p "$corpus" "$regress"
    # The working corpus (first: new inputs go there), then the committed ones.
    "$bin" -max_total_time="$SECONDS_EACH" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
        -artifact_prefix="$regress/" -print_final_stats=1 \
        "$corpus" "$ROOT/tests/fuzz/$t/seeds" "$regress" >"$log" 2>&1
    rc=$?
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
    if [ $rc -ne 0 ]; then
        touch "$TMPDIR/failed-$t"
        { echo "fuzz $t: FAILED (exit $rc) after ${runs:-?} runs; input saved in $regress/, log $log"
          grep -m 3 -E "^(==[0-9]+==ERROR|SUMMARY|.*runtime error)" "$log" | sed 's/^/  /'; } > "$TMPDIR/result-$t"
    else
        echo "fuzz $t: ok, ${runs:-?} runs in ${SECONDS_EACH} s" > "$TMPDIR/result-$t"
    fi
}
for t in "${TARGETS[@]}"; do
    [ -x "$BUILD/tests/fuzz/fuzz_$t" ] || { echo "fuzz: $BUILD/tests/fuzz/fuzz_$t missing (make build-fuzz)"; exit 1; }
done
for t in "${TARGETS[@]}"; do
    while [ "$(jobs -rp | wc -l)" -ge "$JOBS" ]; do wait -n; done
    fuzz_one "$t" &
done
wait
failed=()
for t in "${TARGETS[@]}"; do
    cat "$TMPDIR/result-$t"
    [ ! -e "$TMPDIR/failed-$t" ] || failed+=("$t")
done
[ ${#failed[@]} -eq 0 ] || { echo "fuzz: failed: ${failed[*]}"; exit 1; }
