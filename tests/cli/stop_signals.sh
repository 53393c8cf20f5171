#!/usr/bin/env bash
# CLI test: the long commands besides run, pack, lga and calibrate's
# refinement stop on SIGTERM/SIGINT (docs/reliability.md, "Nothing stuck"):
# exit 130 with one line saying so, no process left behind, nothing
# half-written that looks complete. Old code: SIGTERM killed granflow
# (exit 143, no message) and left LAMMPS running.
# usage: bash tests/cli/stop_signals.sh GRANFLOW_BINARY TESTS_DATA_DIR
NAME=stop_signals
source "$(dirname "$0")/lib.bash" "$@"
# The stand-in LAMMPS's processes too, if a check failed with them running.
cleanup() {
    if [ -n "$BGPID" ]; then kill -KILL "$BGPID" 2>/dev/null; wait "$BGPID" 2>/dev/null; fi
    for f in "$T"/D/*.pid; do [ -e "$f" ] && kill -KILL "$(cat "$f")" 2>/dev/null; done
    rm -rf "$T"
}
# wait_line TEXT SECONDS: until the background command's stderr holds TEXT.
wait_line() {
    local i
    for ((i = 0; i < $2 * 20; i++)); do grep -qF -- "$1" "$T/bgerr" 2>/dev/null && return 0; sleep 0.05; done
    return 1
}
# wait_for FILE SECONDS: until FILE exists.
wait_for() {
    local i
    for ((i = 0; i < $2 * 20; i++)); do [ -s "$1" ] && return 0; sleep 0.05; done
    return 1
}
alive() { kill -0 "$1" 2>/dev/null && ! grep -q '^State:.*Z' "/proc/$1/status" 2>/dev/null; }

# --- analyze: 300 snapshots; g(r) out to 20 d takes minutes per frame --------
gf run -q --set packing.particles=2000 --set output.snapshot_interval=0.05 --set run.duration=15 -o R
expect_rc 0 "run (2,000 particles, 301 snapshots)"
[ "$(ls R/snapshots | wc -l)" -eq 301 ] || fail "run wrote $(ls R/snapshots | wc -l) snapshots, not 301"
start analyze --no-plots R --set window.t0=0 --set gr.rmax=20 --set gr.x0=-30 --set gr.x1=30 --set gr.z0=0 \
    --set gr.z1=100
wait_line "reading R" 10 || fail "analyze: no 'reading' line after 10 s"
sleep 1
kill -TERM "$BGPID"
finish 5
LAST="granflow analyze R (301 snapshots), SIGTERM after 1 s"
expect_rc 130 "SIGTERM during analyze"
expect_err "granflow analyze: stopped by a signal (" "SIGTERM during analyze"
expect_err "summary.json not written" "SIGTERM during analyze"
[ "$(wc -l <"$T/err")" -eq 2 ] || fail "analyze: expected the 'reading' line and one message, got $(wc -l <"$T/err") lines"
[ ! -e R/analysis/summary.json ] || fail "an interrupted analyze wrote summary.json"
for f in R/analysis/*.csv; do
    [ -e "$f" ] || continue
    case $f in *.tmp*) fail "analyze left a temporary file $f" ;; esac
done
ok "analyze: SIGTERM -> exit 130 within 5 s, one message, no summary.json"

# --- bench: SIGTERM during the warm-up --------------------------------------
start bench --particles 2000 --warmup 100000 --no-large --set run.threads=1
wait_line "warming up" 20 || fail "bench: no 'warming up' line after 20 s"
sleep 0.3
kill -TERM "$BGPID"
finish 5
LAST="granflow bench --warmup 100000, SIGTERM in the warm-up"
expect_rc 130 "SIGTERM during bench's warm-up"
expect_err "granflow bench: stopped by a signal" "SIGTERM during bench's warm-up"
ok "bench: SIGTERM in the warm-up -> exit 130 within 5 s, one message"

# --- dem --run with a stand-in LAMMPS that takes its time --------------------
# It prints what in.fill/in.drain print, writes what LAMMPS would have begun
# writing (a settled.restart in the fill, snapshots in the drain), then waits
# with a child of its own: both must be gone after the stop.
cat >fake-lmp <<'EOF'
#!/usr/bin/env bash
echo "LAMMPS (stand-in)"
if [ "$2" = in.fill ]; then
    echo "granflow-phase fill 300 10"
    echo "  100 0.5 120 0.01"
    echo partial >settled.restart
else
    echo "granflow-phase drain 300 8"
    echo "  100 0.5 290 0.01"
    if [ -z "${FAKE_NO_SNAPSHOT:-}" ]; then
        printf 'ITEM: TIMESTEP\n0\n' >snapshots/snap_000000000.dump
        printf 'ITEM: TIMESTEP\n1000\nITEM: NUM' >snapshots/snap_000001000.dump
    fi
fi
# FAKE_CLOSE_OUTPUT: it closes its output first (LAMMPS ending its run but
# not yet gone): the rest of the wait is granflow's waitpid.
[ -n "${FAKE_CLOSE_OUTPUT:-}" ] && exec >/dev/null 2>&1
sleep 60 &
echo $! >sleep.pid
echo $$ >lmp.pid
wait
EOF
chmod +x fake-lmp
DEM=(--set container.width=10 --set container.depth=6 --set container.orifice_diameter=5 --set packing.particles=300 --set run.duration=8
    --set dem.mpi_ranks=1)
export GF_LMP=$T/fake-lmp
start dem "${DEM[@]}" -o D --run
wait_for D/lmp.pid 10 || fail "dem --run: the stand-in LAMMPS did not start in 10 s"
kill -TERM "$BGPID"
finish 15
LAST="granflow dem --run (stand-in LAMMPS in the fill), SIGTERM"
expect_rc 130 "SIGTERM during dem --run"
expect_err "granflow dem: stopped by a signal (LAMMPS (D/in.fill) stopped on request" "SIGTERM during dem --run"
for p in lmp sleep; do alive "$(cat D/$p.pid)" && fail "dem --run: the stand-in's $p process is still running"; done
[ ! -e D/settled.restart ] || fail "dem --run stopped in the fill: the partial settled.restart is still there"
grep -q "^interrupted: LAMMPS was stopped during the fill" D/interrupted.txt ||
    fail "dem --run: D/interrupted.txt missing or not about the fill"
ok "dem --run: SIGTERM -> LAMMPS and its child ended, exit 130, settled.restart removed, interrupted.txt"

rm -f D/*.pid
start dem "${DEM[@]}" -o D --drain-only
wait_for D/lmp.pid 10 || fail "dem --drain-only: the stand-in LAMMPS did not start in 10 s"
kill -INT "$BGPID"
finish 15
LAST="granflow dem --drain-only (stand-in LAMMPS in the drain), SIGINT"
expect_rc 130 "SIGINT during dem --drain-only"
for p in lmp sleep; do alive "$(cat D/$p.pid)" && fail "dem --drain-only: the stand-in's $p process is still running"; done
[ -e D/snapshots/snap_000000000.dump ] || fail "dem --drain-only: an earlier snapshot was removed"
[ ! -e D/snapshots/snap_000001000.dump ] || fail "dem --drain-only: the newest (partial) snapshot is still there"
grep -q "^interrupted: LAMMPS was stopped during the drain" D/interrupted.txt ||
    fail "dem --drain-only: D/interrupted.txt missing or not about the drain"
grep -q "^removed: snapshots/snap_000001000.dump" D/interrupted.txt || fail "interrupted.txt does not name the removed snapshot"
ok "dem --drain-only: SIGINT -> exit 130, the newest snapshot removed, interrupted.txt says so"

# Stopped before this drain wrote a snapshot: the newest one is an earlier
# drain's, whole, and stays.
rm -f D/*.pid D/interrupted.txt
printf 'ITEM: TIMESTEP\n2000\n' >D/snapshots/snap_000002000.dump
touch -d '1 hour ago' D/snapshots/snap_000002000.dump
FAKE_NO_SNAPSHOT=1 start dem "${DEM[@]}" -o D --drain-only
wait_for D/lmp.pid 10 || fail "dem --drain-only (no snapshot): the stand-in LAMMPS did not start in 10 s"
kill -INT "$BGPID"
finish 15
LAST="granflow dem --drain-only (stand-in LAMMPS writes no snapshot), SIGINT"
expect_rc 130 "SIGINT during dem --drain-only before its first snapshot"
[ -e D/snapshots/snap_000002000.dump ] || fail "dem --drain-only: an earlier drain's snapshot was removed"
grep -q "^removed: nothing (the newest snapshot, snap_000002000.dump, is older than this drain)" D/interrupted.txt ||
    fail "interrupted.txt does not say the older snapshot was kept: $(cat D/interrupted.txt)"
ok "dem --drain-only stopped before its first snapshot: an earlier drain's snapshot kept, interrupted.txt says so"

# --- stops that stop (issue 26) ----------------------------------------------
# LAMMPS closed its output but has not ended: Ctrl-C still stops it (old: a
# blocking waitpid looped on EINTR until the stand-in's 60 s were over).
rm -rf D
FAKE_CLOSE_OUTPUT=1 start dem "${DEM[@]}" -o D --run
wait_for D/lmp.pid 10 || fail "dem --run (output closed): the stand-in LAMMPS did not start in 10 s"
sleep 0.5
kill -INT "$BGPID"
finish 15
LAST="granflow dem --run (stand-in LAMMPS closed its output), SIGINT"
expect_rc 130 "SIGINT during dem --run after LAMMPS closed its output"
for p in lmp sleep; do alive "$(cat D/$p.pid)" && fail "dem --run (output closed): the stand-in's $p process is still running"; done
ok "dem --run: SIGINT after LAMMPS closed its output -> exit 130, LAMMPS and its child ended"

# granflow killed with SIGKILL runs no code: its guard ends LAMMPS' group
# (old: LAMMPS and its child went on, orphaned).
rm -rf D
start dem "${DEM[@]}" -o D --run
wait_for D/lmp.pid 10 || fail "dem --run (kill -9): the stand-in LAMMPS did not start in 10 s"
kill -KILL "$BGPID"
finish 5
gone=
for ((i = 0; i < 100; i++)); do
    alive "$(cat D/lmp.pid)" || alive "$(cat D/sleep.pid)" || { gone=1; break; }
    sleep 0.1
done
[ -n "$gone" ] || fail "dem --run killed with SIGKILL: the stand-in LAMMPS or its child still runs 10 s later"
ok "dem --run: kill -9 of granflow ends LAMMPS and its child within 10 s"
echo "cli $NAME: $PASS passed, 0 failed"
