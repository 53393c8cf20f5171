#!/usr/bin/env bash
# MPI ranks must run the same settings (build-mpi only, label mpi; issue 26):
# ranks given another run.seed, container.width or run.duration, or resuming
# from different checkpoints, all stop before the first step with exit code 2
# and rank 0 names the key that differs (they used to corrupt the heap, run
# with particles beyond the walls, or hang); run.threads may differ. A rank
# other than 0 writes nothing, so a job killed with SIGKILL leaves no
# $TMPDIR/granflow-rank* behind (it used to leave a scratch run directory
# with full snapshots per rank).
# usage: bash tests/mpi/agree.sh GRANFLOW_BINARY(MPI build) TESTS_DATA_DIR [MPIRUN]
NAME=mpi_agree
HERE=$(cd "$(dirname "$0")" && pwd)
source "$HERE/../cli/lib.bash" "$1" "$2"
source "$HERE/lib.bash" "${3:-}"
mkdir -p "$T/tmp"
export TMPDIR=$T/tmp
TINY=(--set container.width=12 --set container.depth=6 --set container.orifice_diameter=4
      --set packing.particles=1500 --set run.duration=3 --set run.threads=1
      --set run.mode=fixed --set run.order=spatial)
# two "RANK0 ARGS" -- "RANK1 ARGS": one rank each (an MPMD job), at most 120 s.
two() {
    local a=() b=()
    while [ "$1" != -- ]; do a+=("$1"); shift; done
    shift
    b=("$@")
    LAST="mpirun -np 1 granflow ${a[*]} : -np 1 granflow ${b[*]}"
    timeout -s KILL 120 "$MPIRUN" --oversubscribe -np 1 "$GF" "${a[@]}" : -np 1 "$GF" "${b[@]}" >"$T/out" 2>"$T/err"
    RC=$?
    [ "$RC" -ne 137 ] || fail "the ranks hung (killed after 120 s)"
}

two run -q "${TINY[@]}" --set run.seed=1 -o S -- run -q "${TINY[@]}" --set run.seed=2 -o S
expect_rc 2 "ranks with run.seed 1 and 2"
expect_err "rank 1 has run.seed = 2 where rank 0 has 1" "ranks with different seeds"
[ ! -e S ] || fail "ranks with different seeds: rank 0 made its run directory"
[ "$(grep -c 'Exit code: *2' "$T/err")" -ge 1 ] || fail "mpirun does not report exit code 2: $(cat "$T/err")"
ok "ranks with different run.seed stop before the first step, exit code 2, naming run.seed"

two run -q "${TINY[@]}" -o W -- run -q "${TINY[@]}" --set container.width=14 -o W
expect_rc 2 "rank 1 with container.width = 14"
expect_err "rank 1 has container.width = 14 where rank 0 has 12" "ranks with different widths"
ok "a rank with another container.width stops all of them, naming the key"

two run -q "${TINY[@]}" -o D -- run -q "${TINY[@]}" --set run.duration=4 -o D
expect_rc 2 "rank 1 with run.duration = 4"
expect_err "rank 1 has run.duration = 4 where rank 0 has 3" "ranks with different durations"
ok "a rank with another run.duration stops all of them (it used to hang for ever)"

two run -q "${TINY[@]}" -o H -- run -q "${TINY[@]}" --set run.threads=2 -o H
expect_rc 0 "rank 1 with run.threads = 2"
gf run -q "${TINY[@]}" -o H1
cmp -s H/exits.csv H1/exits.csv || fail "2 ranks of 1 and 2 threads: exits.csv differs from one process's"
ok "run.threads may differ between ranks: the single process's exits"

# resume from a checkpoint per rank (a directory per node): they must be the same
gf run -q "${TINY[@]}" --set run.duration=2 -o B
expect_rc 0 "a run to t = 2"
cp -r H1 A
two run -q --resume A --set run.duration=4 -- run -q --resume B --set run.duration=4
expect_rc 2 "ranks resuming different checkpoints"
expect_err "rank 1 has checkpoint.bin = " "ranks resuming different checkpoints"
cp A/checkpoint.bin B/checkpoint.bin
two run -q --resume A --set run.duration=4 -- run -q --resume B --set run.duration=4
expect_rc 0 "ranks resuming the same checkpoint from two directories"
ok "ranks resuming different checkpoints stop, naming checkpoint.bin; the same one in two directories resumes"

# SIGKILL to a 2-rank run once it has begun: nothing left in $TMPDIR.
LAST="mpirun -np 2 granflow run (rank 1 killed with SIGKILL)"
timeout -s KILL 120 "$MPIRUN" --oversubscribe -np 2 "$GF" run -q "${TINY[@]}" --set run.duration=60 \
    --set output.snapshot_interval=0.5 -o K >"$T/out" 2>"$T/err" &
pid=$!
for k in $(seq 1200); do
    [ -e K/snapshots/snap_000001.dump ] && break
    sleep 0.05
done
[ -e K/snapshots/snap_000001.dump ] || fail "the 2-rank run wrote no snapshot"
ls "$TMPDIR" | grep -q granflow-rank && fail "rank 1 writes a scratch directory: $(ls "$TMPDIR")"
mp=$(pgrep -P "$pid")
for k in $(pgrep -P "$mp"); do
    tr '\0' '\n' <"/proc/$k/environ" 2>/dev/null | grep -q '^OMPI_COMM_WORLD_RANK=1$' && kill -KILL "$k"
done
wait "$pid"
[ -z "$(ls "$TMPDIR" | grep granflow-rank)" ] || fail "SIGKILL left $(ls "$TMPDIR" | grep granflow-rank) in \$TMPDIR"
ok "rank 1 killed with SIGKILL: nothing of it left in \$TMPDIR (rank 1 writes no files)"
echo "cli $NAME: $PASS passed"
