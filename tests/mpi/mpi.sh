#!/usr/bin/env bash
# MPI test (build-mpi only, label mpi): `mpirun -np N granflow run` writes the
# run directory of a single process, byte for byte, for 1, 2 and 4 ranks with
# 1 and 2 threads each; a run stopped at 2 ranks and resumed at 1 matches the
# uninterrupted one. summary.json is compared without its timing fields
# (t_relax, wall_seconds, steps_per_second); checkpoint.bin without the two
# timing doubles of its stored counters (spot_seconds, relax_seconds) and the
# CRC that covers them.
# usage: bash tests/mpi/mpi.sh GRANFLOW_BINARY(MPI build) TESTS_DATA_DIR [MPIRUN]
NAME=mpi
source "$(dirname "$0")/../cli/lib.bash" "$1" "$2"
MPIRUN=${3:-mpirun}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_mpi_yield_when_idle=1
mpi() { # mpi NP ARGS...: granflow on NP ranks
    local np=$1
    shift
    LAST="mpirun -np $np granflow $*"
    "$MPIRUN" --oversubscribe -np "$np" "$GF" "$@" >"$T/out" 2>"$T/err"
    RC=$?
}

# A wide slit (44 of 50 d) starts spots in every column of blocks at once, so
# every colour phase has several busy blocks and every rank runs some of them
# (above a narrow orifice the spots of a short run stay in one column of
# blocks: rank 0 would run them all and the exchange would go untested).
SILO=(--set container.width=50 --set container.depth=4 --set container.orifice_shape=slit
      --set container.orifice_diameter=44 --set packing.particles=6000
      --set spot.step_z=0.2 --set run.mode=fixed --set run.order=spatial
      --set output.snapshot_interval=0.5)
export GF_MPI_STATS=1
# took: the words rank 0 took from the other ranks in the last mpi run (> 0:
# the others ran blocks and their changes were exchanged).
took() { sed -n 's/.*rank 0 took \([0-9]*\) words.*/\1/p' "$T/err"; }
# same A B: the two run directories hold the same results.
same() {
    local a=$1 b=$2 f
    for f in $(cd "$a" && ls snapshots/*) exits.csv; do
        cmp -s "$a/$f" "$b/$f" || fail "$b/$f differs from $a/$f"
    done
    diff <(grep -vE '"(t_relax|wall_seconds|steps_per_second)"' "$a/summary.json") \
         <(grep -vE '"(t_relax|wall_seconds|steps_per_second)"' "$b/summary.json") >/dev/null ||
        fail "$b/summary.json differs from $a/summary.json (timing fields aside)"
    python3 - "$a/checkpoint.bin" "$b/checkpoint.bin" <<'PY' || fail "$b/checkpoint.bin differs from $a/checkpoint.bin"
import sys
a, b = (open(p, "rb").read() for p in sys.argv[1:3])
assert len(a) == len(b), "sizes differ"
d = [i for i in range(len(a)) if a[i] != b[i] and not 24 <= i < 28]  # 24..27: the CRC
# what may differ: the two timing doubles (16 bytes) of the stored counters
assert not d or d[-1] - d[0] < 16, "differs at bytes %s" % d[:10]
PY
}

gf run -q "${SILO[@]}" --set run.duration=2 --set run.threads=1 -o S
expect_rc 0 "single process, no mpirun"
[ "$(ls S/snapshots | wc -l)" -eq 5 ] || fail "expected 5 snapshots, got $(ls S/snapshots | wc -l)"
[ "$(wc -l <S/exits.csv)" -gt 5 ] || fail "the silo did not flow ($(wc -l <S/exits.csv) lines in exits.csv)"
for np in 1 2 4; do
    for t in 1 2; do
        mpi $np run -q "${SILO[@]}" --set run.duration=2 --set run.threads=$t -o "R${np}T$t"
        expect_rc 0 "$np ranks, $t threads"
        same S "R${np}T$t"
        [ "$np" -eq 1 ] || [ "$(took)" -gt 0 ] || fail "$np ranks: rank 0 took no words from the others: $(cat "$T/err")"
        ok "$np ranks x $t threads: the single process's snapshots, exits, summary and checkpoint"
    done
done
[ -z "$(ls -d "${TMPDIR:-/tmp}"/granflow-rank* 2>/dev/null)" ] || echo "note: scratch dirs left in ${TMPDIR:-/tmp}"

# Stopped at t = 1 on 2 ranks, resumed on 1 process to t = 2.
mpi 2 run -q "${SILO[@]}" --set run.duration=1 --set run.threads=2 -o P
expect_rc 0 "2 ranks to t = 1"
gf run -q --resume P --set run.duration=2
expect_rc 0 "resumed on 1 process"
same S P
ok "2 ranks to t = 1, then 1 process to t = 2: the uninterrupted run"
# and the other way: 1 process to t = 1, 4 ranks to t = 2
gf run -q "${SILO[@]}" --set run.duration=1 --set run.threads=1 -o Q
expect_rc 0 "1 process to t = 1"
mpi 4 run -q --resume Q --set run.duration=2
expect_rc 0 "resumed on 4 ranks"
same S Q
ok "1 process to t = 1, then 4 ranks to t = 2: the uninterrupted run"

# The event engine is not split between ranks: refused with a message.
mpi 2 run -q --set packing.particles=500 --set run.duration=0.1 -o E
[ "$RC" -ne 0 ] || fail "2 ranks with the event engine: expected a refusal"
grep -q "run.order = spatial" err || fail "the refusal does not name run.order: $(cat err)"
ok "2 ranks refuse the event engine, naming run.mode/run.order"
echo "cli $NAME: $PASS passed"
