#!/usr/bin/env bash
# MPI test of a rank holding only its region (issue 23 item 3; build-mpi
# only, label mpi): the domain engine given a packing.file, every rank reads
# the file keeping its region's particles (src/spot/window.c). A tall silo
# packed once, re-sorted every 3,000 moves (each rank re-sorts its own
# window, gf_mpi_resort): 2 and 4 ranks (GF_MPI_CHECK=1: every halo checked
# after every phase) write the single process's run directory byte for byte;
# a run stopped at 4 ranks resumes on 1 process to the uninterrupted run; and
# the bench's ranks each hold the records of well under half the particles
# (rank_held_particles: a non-zero id; every rank held all of them before).
# usage: bash tests/mpi/mpi_window.sh GRANFLOW_BINARY(MPI build) TESTS_DATA_DIR [MPIRUN]
NAME=mpi_window
HERE=$(cd "$(dirname "$0")" && pwd)
source "$HERE/../cli/lib.bash" "$1" "$2"
source "$HERE/lib.bash" "${3:-}"

# 6,000 spheres 156 d tall: 6 domains along z, 4 slabs of them.
TALL=(--set container.width=8 --set container.depth=4 --set container.orifice_diameter=5
      --set spot.step_z=0.2 --set run.mode=fixed --set run.order=domains --set parallel.sectors=4
      --set output.snapshot_interval=0.5 --set run.reorder_interval=3000)
same() {
    local a=$1 b=$2 f
    for f in $(cd "$a" && ls snapshots/*) exits.csv; do
        cmp -s "$a/$f" "$b/$f" || fail "$b/$f differs from $a/$f"
    done
    diff <(grep -vE '"(t_relax|wall_seconds|steps_per_second)"' "$a/summary.json") \
         <(grep -vE '"(t_relax|wall_seconds|steps_per_second)"' "$b/summary.json") >/dev/null ||
        fail "$b/summary.json differs from $a/summary.json (timing fields aside)"
}

gf pack --set container.width=8 --set container.depth=4 --set container.orifice_diameter=5 --set packing.particles=6000 \
    -o tall.dump
expect_rc 0 "packing the tall silo"
FILE=(--set "packing.file=$PWD/tall.dump")
gf run -q "${TALL[@]}" "${FILE[@]}" --set run.duration=2 --set run.threads=1 -o S
expect_rc 0 "single process"
[ "$(wc -l <S/exits.csv)" -gt 5 ] || fail "the silo did not flow ($(wc -l <S/exits.csv) lines in exits.csv)"
builds=$(sed -n 's/.*"neighbour_list_builds": \([0-9]*\).*/\1/p' S/summary.json)
[ "${builds:-0}" -gt 3 ] || fail "the lists were re-sorted ${builds:-no} times: no re-sort to test"
for np in 2 4; do
    GF_MPI_CHECK=1 mpi $np run -q "${TALL[@]}" "${FILE[@]}" --set run.duration=2 --set run.threads=1 -o "R$np"
    expect_rc 0 "$np ranks reading their regions (GF_MPI_CHECK=1)"
    same S "R$np"
    ok "$np ranks, each reading its region of packing.file and re-sorting it ($builds list builds): every halo checked, the single process's run directory"
done

GF_MPI_CHECK=1 mpi 4 run -q "${TALL[@]}" "${FILE[@]}" --set run.duration=1 --set run.threads=1 -o P
expect_rc 0 "4 ranks to t = 1"
gf run -q --resume P --set run.duration=2
expect_rc 0 "resumed on 1 process"
same S P
ok "4 ranks reading their regions to t = 1, then 1 process to t = 2: the uninterrupted run"

# The bench reads counters only: the ranks keep their regions to the end,
# through their re-sorts.
mpi 4 bench --json --no-large --warmup 0.5 --window 0.1 --set run.threads=1 "${TALL[@]}" "${FILE[@]}" \
    --set run.reorder_interval=1000
expect_rc 0 "bench on 4 ranks"
held=$(python3 -c 'import json,sys; s=json.load(open(sys.argv[1])); print(s["particles"], *[int(h) for h in s["rank_held_particles"]])' "$T/out") ||
    fail "no rank_held_particles in the bench's JSON: $(head -c 300 "$T/out")"
read -r n h0 h1 h2 h3 <<<"$held"
for h in $h0 $h1 $h2 $h3; do
    [ "$h" -gt 0 ] && [ $((2 * h)) -lt "$n" ] || fail "a rank holds $h of $n particles (ranks: $h0 $h1 $h2 $h3)"
done
ok "the bench's 4 ranks hold $h0, $h1, $h2, $h3 of $n particles"
echo "cli $NAME: $PASS passed"
