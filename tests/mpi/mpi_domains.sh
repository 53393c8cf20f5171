#!/usr/bin/env bash
# MPI test of the domain engine (run.order = domains; build-mpi only, label
# mpi): for one decomposition, 1, 2 and 4 ranks with 1 and 2 threads each
# write the single process's run directory byte for byte (snapshots,
# exits.csv, summary.json without its timing fields), the ranks each running
# their own slab of domains (issue 23: a tall silo cut into 4 slabs along z,
# every halo checked after every phase, and two broken halos caught); a run stopped at
# 4 ranks resumes on 1 process to the uninterrupted run; a rank killed with
# SIGKILL ends the job with a non-zero status within 30 s, and the
# checkpoint written before it resumes.
# usage: bash tests/mpi/mpi_domains.sh GRANFLOW_BINARY(MPI build) TESTS_DATA_DIR [MPIRUN]
NAME=mpi_domains
HERE=$(cd "$(dirname "$0")" && pwd)
source "$HERE/../cli/lib.bash" "$1" "$2"
source "$HERE/lib.bash" "${3:-}"

# A wide slit (44 of 50 d) starts spots over most of the width at once, and
# 4 sectors per axis (~5.5 d) cut the silo into 9 x 18 sectors: every phase
# has several busy sectors and every rank runs some of them. The window is
# the default before 2026-11-27 (0.02, not 0.005): a quarter of the phases,
# each exchanged between the ranks, for the same checks.
SILO=(--set container.width=50 --set container.depth=4 --set container.orifice_shape=slit
      --set container.orifice_diameter=44 --set packing.particles=6000
      --set spot.step_z=0.2 --set run.mode=fixed --set run.order=domains --set parallel.sectors=4
      --set parallel.window=0.02 --set output.snapshot_interval=0.5)
export GF_MPI_STATS=1
same() {
    local a=$1 b=$2 f
    for f in $(cd "$a" && ls snapshots/*) exits.csv; do
        cmp -s "$a/$f" "$b/$f" || fail "$b/$f differs from $a/$f"
    done
    diff <(grep -vE '"(t_relax|wall_seconds|steps_per_second)"' "$a/summary.json") \
         <(grep -vE '"(t_relax|wall_seconds|steps_per_second)"' "$b/summary.json") >/dev/null ||
        fail "$b/summary.json differs from $a/summary.json (timing fields aside)"
}

gf run -q "${SILO[@]}" --set run.duration=2 --set run.threads=1 -o S
expect_rc 0 "single process, no mpirun"
[ "$(wc -l <S/exits.csv)" -gt 5 ] || fail "the silo did not flow ($(wc -l <S/exits.csv) lines in exits.csv)"
for np in 1 2 4; do
    for t in 1 2; do
        mpi $np run -q "${SILO[@]}" --set run.duration=2 --set run.threads=$t -o "R${np}T$t"
        expect_rc 0 "$np ranks, $t threads"
        same S "R${np}T$t"
        [ "$np" -eq 1 ] || [ "$(took)" -gt 0 ] || fail "$np ranks: rank 0 took no words from the others: $(cat "$T/err")"
        ok "$np ranks x $t threads: the single process's snapshots, exits and summary"
    done
done

# Stopped at t = 1 on 4 ranks (GF_MPI_CHECK=1: the ranks' states agree after
# every phase), resumed on 1 process to t = 2.
GF_MPI_CHECK=1 mpi 4 run -q "${SILO[@]}" --set run.duration=1 --set run.threads=1 -o P
expect_rc 0 "4 ranks to t = 1 (GF_MPI_CHECK=1)"
gf run -q --resume P --set run.duration=2
expect_rc 0 "resumed on 1 process"
same S P
ok "4 ranks to t = 1, then 1 process to t = 2: the uninterrupted run"

# Slabs (issue 23 item 3): each rank runs its own slab of domains along the
# tallest axis and sends what its moves changed to its neighbour slabs only.
# A tall silo cut into 4 slabs along z: GF_MPI_CHECK=1 compares every rank's
# halo with its owners' records after every phase (and the whole states once
# gathered), and the run directory is the single process's. (By t = 3 the
# spots have risen through rank 0's halo: its neighbour gets its moves.)
TALL=(--set container.width=16 --set container.depth=4 --set packing.particles=5000
      --set container.orifice_diameter=6 --set spot.step_z=0.2 --set run.mode=fixed --set run.order=domains
      --set parallel.sectors=4 --set output.snapshot_interval=0.5)
gf run -q "${TALL[@]}" --set run.duration=3 --set run.threads=1 -o TS
expect_rc 0 "tall silo, single process"
[ "$(wc -l <TS/exits.csv)" -gt 5 ] || fail "the tall silo did not flow ($(wc -l <TS/exits.csv) lines in exits.csv)"
GF_MPI_CHECK=1 mpi 4 run -q "${TALL[@]}" --set run.duration=3 --set run.threads=1 -o T4
expect_rc 0 "tall silo, 4 ranks (GF_MPI_CHECK=1: halos checked after every phase)"
same TS T4
near=$(sed -n 's/.*per phase (slabs: \([0-9]*\) per phase to its neighbours.*/\1/p' "$T/err")
[ -n "$near" ] || fail "no per-phase bytes of rank 0 over slabs: $(cat "$T/err")"
[ "$near" -gt 100 ] || fail "rank 0 sent its neighbour $near bytes per phase: the spots never reached its halo"
[ "$(took)" -gt 0 ] || fail "tall silo, 4 ranks: rank 0 took nothing from its neighbour"
ok "tall silo, 4 slabs along z: every halo equals its owners' records after every phase ($near bytes a phase to the neighbour); the single process's run directory"

# The check catches a halo gone wrong: with the moved positions kept from the
# neighbours (a test-only break), GF_MPI_CHECK fails the run naming the ranks.
GF_MPI_TEST_BREAK=moved GF_MPI_CHECK=1 mpi 4 run -q "${TALL[@]}" --set run.duration=3 --set run.threads=1 -o TB
[ "$RC" -ne 0 ] || fail "positions kept from the neighbours: the run passed GF_MPI_CHECK"
grep -q "a ghost differs from its owner's particle" "$T/err" || fail "no halo message: $(cat "$T/err")"
ok "a halo missing the neighbours' moved positions fails GF_MPI_CHECK: $(grep -o 'ranks [0-9]* and [0-9]* hold' "$T/err" | head -1)"

# A particle moved into a rank's region from beyond it is sent whole, with its
# list row (that rank's record of it is old). On the wide slit with no
# snapshot (no gather) before t = 2, the run with GF_MPI_CHECK=1 passes and
# gives the single process's exits; with that logging broken (test-only) the
# check fails.
GF_MPI_CHECK=1 mpi 4 run -q "${SILO[@]}" --set output.snapshot_interval=2 --set run.duration=2 --set run.threads=1 -o E4
expect_rc 0 "wide slit, 4 ranks, one gather in 2 tau (GF_MPI_CHECK=1)"
cmp -s S/exits.csv E4/exits.csv || fail "wide slit, one gather: exits.csv differs from the single process's"
GF_MPI_TEST_BREAK=entry GF_MPI_CHECK=1 mpi 4 run -q "${SILO[@]}" --set output.snapshot_interval=2 \
    --set run.duration=2 --set run.threads=1 -o EB
[ "$RC" -ne 0 ] || fail "particles entering a region not sent whole: the run passed GF_MPI_CHECK"
grep -q "a ghost differs from its owner's particle" "$T/err" || fail "no halo message: $(cat "$T/err")"
ok "particles entering a region are sent whole: without it GF_MPI_CHECK fails, with it the exits are the single process's"

# kill -9 of rank 1: mpirun ends the job (every rank) with a non-zero status
# within 30 s; the checkpoint written before it (every 0.5 tau) resumes.
LAST="mpirun -np 2 granflow run (rank 1 killed)"
start=$(date +%s)
timeout -s KILL 120 "$MPIRUN" --oversubscribe -np 2 "$GF" run -q "${SILO[@]}" --set run.duration=30 \
    --set run.threads=1 --set run.checkpoint_interval=0.5 -o K >"$T/out" 2>"$T/err" &
pid=$!
for k in $(seq 1200); do
    [ -e K/checkpoint.bin ] && break
    sleep 0.05
done
[ -e K/checkpoint.bin ] || fail "no checkpoint before the kill"
mp=$(pgrep -P "$pid")
for k in $(pgrep -P "$mp"); do
    tr '\0' '\n' <"/proc/$k/environ" 2>/dev/null | grep -q '^OMPI_COMM_WORLD_RANK=1$' && kill -KILL "$k"
done
killed=$(date +%s)
wait "$pid"
RC=$?
KRC=$RC
took_s=$(( $(date +%s) - killed ))
[ "$RC" -ne 0 ] || fail "rank 1 killed: the job exited 0"
# (137 is mpirun passing on rank 1's SIGKILL; a hang shows as the time.)
[ "$took_s" -le 30 ] || fail "rank 1 killed: the job took $took_s s to end (rank 0 hung)"
pgrep -f "$GF run -q" >/dev/null && fail "a rank is still running after the job ended"
gf run -q --resume K --set run.duration=2
expect_rc 0 "the checkpoint before the kill resumes"
ok "kill -9 of rank 1: the job ends with status $KRC within $took_s s; its last checkpoint resumes"
echo "cli $NAME: $PASS passed"
