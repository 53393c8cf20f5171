#!/usr/bin/env bash
# Paired A/B timing of two granflow binaries (docs/performance.md, "The 10 us
# target"): both resume copies of the same run directory at the same time,
# one thread each, one per core (taskset), swapping cores every round, and
# the ratio of their steps_per_second (summary.json) is what is read. Run it
# on an otherwise idle 2-core machine.
#
#   scripts/paired-bench.sh A_BINARY B_BINARY RUN_DIR [ROUNDS [TAU]]
#
# RUN_DIR: a run directory with a checkpoint (e.g. runs/silo after `make
# run`); each run goes TAU further (default 1) with run.threads = 1.
# Prints each round's steps/s and the ratio B/A, then the median ratio.
set -euo pipefail
if [ $# -lt 3 ]; then
    sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'
    exit 2
fi
a=$1 b=$2 dir=$3 rounds=${4:-5} tau=${5:-1}
for f in "$a" "$b"; do [ -x "$f" ] || { echo "paired-bench: $f is not an executable" >&2; exit 2; }; done
[ -f "$dir/checkpoint.bin" ] || { echo "paired-bench: $dir has no checkpoint.bin" >&2; exit 2; }
command -v taskset >/dev/null || { echo "paired-bench: taskset (util-linux) is missing" >&2; exit 2; }
t0=$(sed -n 's/.*"simulated_time": *\([0-9.e+-]*\).*/\1/p' "$dir/summary.json" | head -n 1)
t1=$(awk -v t="$t0" -v d="$tau" 'BEGIN { print t + d }')
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
sps() { sed -n 's/.*"steps_per_second": *\([0-9.e+-]*\).*/\1/p' "$1/summary.json" | head -n 1; }
ratios=()
for ((k = 1; k <= rounds; k++)); do
    rm -rf "$tmp/a" "$tmp/b"
    cp -r "$dir" "$tmp/a"
    cp -r "$dir" "$tmp/b"
    ca=$(( (k + 1) % 2 )) cb=$(( k % 2 ))
    taskset -c "$ca" "$a" run -q --resume "$tmp/a" --set run.duration="$t1" --set run.threads=1 &
    pa=$!
    taskset -c "$cb" "$b" run -q --resume "$tmp/b" --set run.duration="$t1" --set run.threads=1 &
    pb=$!
    wait "$pa"
    wait "$pb"
    sa=$(sps "$tmp/a") sb=$(sps "$tmp/b")
    r=$(awk -v x="$sa" -v y="$sb" 'BEGIN { printf "%.4f", y / x }')
    ratios+=("$r")
    echo "round $k: A $sa (core $ca)  B $sb (core $cb)  B/A $r"
done
printf '%s\n' "${ratios[@]}" | sort -n | awk '{ v[NR] = $1 } END { m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2;
    printf "median B/A over %d rounds: %.4f (min %.4f, max %.4f)\n", NR, m, v[1], v[NR] }'
