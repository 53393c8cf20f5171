#!/usr/bin/env bash
# granflow dem --continue (issue 27 item 4): a drain interrupted by SIGTERM
# goes on from its newer restart file (dem.restart_interval; the drain writes
# drain.a.restart and drain.b.restart in turn). A real LAMMPS run of 600
# spheres in an 8 x 6 box, 6 tau of drainage (~10 s on one core), stopped
# once a snapshot after its second restart exists, then continued. Checks:
# the snapshots follow one another every 0.25 tau from 0 to the end with
# no gap, each ITEM: TIME is its step's; no particle comes back and every
# id of the settled packing is either still there or left (count + exits =
# initial, and analyze agrees); a second --continue of the finished drain
# is refused, a longer run.duration continues it. Errors: a drain written
# seconds ago without interrupted.txt (its LAMMPS may still run), no
# restart file, both restart files cut short (LAMMPS' error naming each),
# another configuration. Then a recirculating drain (300 spheres, 4 tau): 300 in
# every snapshot, reinserted.txt in time order across the restart and
# exits.csv with one row per reinsertion over the whole drain.
# ctest: nosan
NAME=dem_continue
source "$(dirname "$0")/lib.bash" "$@"

BOX=(--set container.width=8 --set container.depth=6 --set container.orifice_diameter=4
    --set packing.particles=600 --set dem.fill_method=generate --set dem.settle_time=2 --set dem.settle_ke=1e-3
    --set dem.mpi_ranks=1 --set output.snapshot_interval=0.25 --set dem.restart_interval=0.5)

# waits_for FILE SECONDS: until FILE exists (false if not in time).
waits_for() {
    local i
    for ((i = 0; i < $2 * 10; i++)); do
        [ -e "$1" ] && return 0
        kill -0 "$BGPID" 2>/dev/null || return 1
        sleep 0.1
    done
    return 1
}

# snap_times DIR: "time step count" of each snapshot, in name (step) order.
snap_times() { for f in "$1"/snapshots/snap_*.dump; do echo "$(sed -n 2p "$f") $(sed -n 4p "$f") $(sed -n 6p "$f")"; done; }

# check_series DIR T_END N0 RECIRC: snapshots every 0.25 tau from 0 to
# T_END, each TIME = TIMESTEP * 1e-4; plain: the ids of each are among the
# previous one's (no particle comes back), N0 at the start; recirculating:
# N0 in each.
check_series() {
    local bad
    bad=$(snap_times "$1" | awk -v end="$2" '
        { d = $1 - $2 * 1e-4; if (d < 0) d = -d; if (d > 1e-9) { print "TIME " $1 " at step " $2; exit }
          if (NR == 1 && $1 != 0) { print "first at t = " $1; exit }
          if (NR > 1 && ($1 - prev < 0.2499 || $1 - prev > 0.2501)) { print "gap from " prev " to " $1; exit }
          prev = $1 }
        END { if (prev < end - 1e-9 || prev > end + 1e-9) print "last at t = " prev ", not " end }')
    [ -z "$bad" ] || fail "$1: snapshots do not follow every 0.25 tau: $bad"
    if [ "$4" = 1 ]; then
        bad=$(snap_times "$1" | awk -v n="$3" '$3 != n { print "t = " $1 ": " $3; exit }')
        [ -z "$bad" ] || fail "$1: not $3 particles in every snapshot: $bad"
        return
    fi
    bad=$(awk -v n0="$3" 'FNR == 1 { k++ } FNR > 11 { seen[k, $1] = 1; c[k]++ }
        END { if (c[1] != n0) { print "first snapshot has " c[1]; exit }
              for (j = 2; j <= k; j++) for (key in seen) { split(key, a, SUBSEP)
                  if (a[1] == j && !((j - 1, a[2]) in seen)) { print "id " a[2] " back in snapshot " j; exit } } }' \
        "$1"/snapshots/snap_*.dump)
    [ -z "$bad" ] || fail "$1: $bad"
}

# ---- a plain drain, stopped after its second restart file ----
start dem -q "${BOX[@]}" --set run.duration=6 -o d --run
waits_for d/drain.b.restart 120 || { finish 1; fail "the drain wrote no drain.b.restart (rc $RC): $(cat "$T/err")"; }
# A snapshot after the restart (t = 1.25, or later): the tail the continuation drops.
waits_for d/snapshots/snap_000012500.dump 60 || { finish 1; fail "no snapshot after drain.b.restart"; }
kill -TERM "$BGPID"
finish 30
expect_rc 130 "SIGTERM during the drain"
grep -q '^continue: granflow dem -o d --continue' d/interrupted.txt || fail "interrupted.txt does not name --continue: $(cat d/interrupted.txt)"
grep -q '^restart 5000 drain.a.restart drain.b.restart$' d/in.drain || fail "in.drain has no 'restart 5000 drain.a.restart drain.b.restart'"
n_before=$(ls d/snapshots | wc -l)
ok "drain stopped by SIGTERM with $n_before snapshots; interrupted.txt names --continue"

# ---- errors, on copies (cp -a: the times of the files kept) ----
cp -a d busy && rm busy/interrupted.txt
gf dem -o busy --continue
expect_rc 2 "--continue of a drain written seconds ago, without interrupted.txt"
expect_err "the drain's LAMMPS may still be running there" "--continue of a drain that may still run"
expect_err "(--force if you know it is not)" "--continue of a drain that may still run"
[ "$(ls busy/snapshots | wc -l)" -eq "$n_before" ] || fail "--continue of a busy drain removed snapshots"
cp -a d nores && rm nores/drain.a.restart nores/drain.b.restart
gf dem -o nores --continue
expect_rc 2 "--continue without a restart file"
expect_err "no restart file to continue from" "--continue without a restart file"
# Cut by hand after granflow stopped the drain: newer than interrupted.txt, so --force.
cp -a d cut && truncate -s 1000 cut/drain.a.restart && truncate -s 1000 cut/drain.b.restart
gf dem -o cut --continue --force
expect_rc 3 "--continue with both restart files cut short"
expect_err "cut/drain.a.restart: LAMMPS cannot read it (ERROR" "--continue with both restart files cut short"
expect_err "cut/drain.b.restart: LAMMPS cannot read it (ERROR" "--continue with both restart files cut short"
gf dem -o d --continue --set dem.kn=1e5
expect_rc 2 "--continue --set dem.kn"
expect_err "--continue changes only run.duration" "--continue --set dem.kn"
cp -a d other && sed -i 's/^timestep *= *0.0001$/timestep = 5e-05/' other/config.ini
gf dem -o other --continue
expect_rc 2 "--continue with another dem.timestep in config.ini"
expect_err "dem.timestep = 5e-05: the configuration is not the one this drain ran with" "another dem.timestep"
[ "$(ls d/snapshots | wc -l)" -eq "$n_before" ] || fail "a refused --continue changed d/snapshots"
ok "refused: written seconds ago (2), no restart file (2), both cut short (3, naming each), --set dem.kn (2), another dem.timestep (2)"

# ---- the continuation: the newer restart file cut short goes on from the other one ----
newer=$(ls -t d/drain.?.restart | head -1)
truncate -s 2000 "$newer"
gf dem -o d --continue --force
expect_rc 0 "granflow dem --continue"
expect_err "$newer: LAMMPS cannot read it (ERROR" "--continue past a cut restart file"
grep -q 'went on from d/drain.[ab].restart at t = [0-9.]* tau (of 6); kept [0-9]* snapshots up to it, removed [0-9]* after it' err ||
    fail "--continue does not say what it kept and removed: $(cat err)"
[ -e d/interrupted.txt ] && fail "interrupted.txt is still there after the drain ended"
check_series d 6 600 0
# Every id is the settled packing's (no new one appeared), and analyze's
# exits are the ids gone by the end (it counts those already below the
# base, z < 0, in the last snapshot as gone too).
ids=$(awk 'FNR > 11 { print $1 }' d/snapshots/snap_*.dump | sort -un | wc -l)
[ "$ids" -eq 600 ] || fail "$ids distinct ids over the snapshots, not the 600 of the settled packing"
n_end=$(awk 'FNR > 11 && $4 >= 0' d/snapshots/snap_000060000.dump | wc -l)
gf analyze d --no-plots -o an
expect_rc 0 "analyze the continued drain"
exited=$(sed -n 's/.*"particles_exited": \([0-9]*\).*/\1/p' an/summary.json)
[ $((n_end + exited)) -eq 600 ] || fail "analyze: $exited exited + $n_end left above the base is not 600"
[ "$exited" -gt 20 ] || fail "only $exited particles left the silo in 6 tau"
ok "continued: snapshots every 0.25 tau from 0 to 6, no particle back, $n_end left + $exited exited = 600"

gf dem -o d --continue
expect_rc 2 "--continue of a finished drain"
expect_err "the drain ran to its end (t = 6 tau" "--continue of a finished drain"
gf dem -o d --continue --set run.duration=7
expect_rc 0 "--continue --set run.duration=7"
check_series d 7 600 0
grep -q '^duration *= *7$' d/config.ini || fail "config.ini does not hold the longer run.duration"
ok "a finished drain: nothing to continue (2); a longer run.duration continues it to t = 7"
# New inputs in the directory: the earlier drain's restart files go with its in.drain.
gf dem -q "${BOX[@]}" --set run.duration=6 -o d --force
expect_rc 0 "granflow dem --force over the continued run"
for f in drain.a.restart drain.b.restart in.continue log.continue; do [ -e "d/$f" ] && fail "new inputs left d/$f"; done
gf dem -o d --continue
expect_rc 2 "--continue after new inputs"
expect_err "no restart file to continue from" "--continue after new inputs"
ok "new inputs remove the earlier drain's restart files: nothing to continue"

# ---- a recirculating drain ----
start dem -q "${BOX[@]}" --set packing.particles=300 --set run.recirculate=on --set run.duration=4 -o rc --run
waits_for rc/drain.b.restart 120 || { finish 1; fail "the recirculating drain wrote no drain.b.restart"; }
waits_for rc/snapshots/snap_000012500.dump 60 || { finish 1; fail "no snapshot after drain.b.restart (recirculating)"; }
kill -TERM "$BGPID"
finish 30
expect_rc 130 "SIGTERM during the recirculating drain"
gf dem -o rc --continue
expect_rc 0 "--continue of the recirculating drain"
check_series rc 4 300 1
t0=$(sed -n 's/.*went on from rc\/drain.[ab].restart at t = \([0-9.]*\) tau.*/\1/p' err)
[ -n "$t0" ] || fail "--continue did not say where it went on from: $(cat err)"
nre=$(grep -vc '^#' rc/reinserted.txt)
[ "$(head -1 rc/reinserted.txt | cut -c1-40)" = "# granflow reinsertions, exit plane z = " ] || fail "reinserted.txt lost its header"
grep -v '^#' rc/reinserted.txt | awk '$2 < prev { bad = 1 } { prev = $2 } END { exit bad }' ||
    fail "reinserted.txt is not in time order across the restart"
rows=$(($(wc -l < rc/exits.csv) - 1))
[ "$rows" -eq "$nre" ] || fail "exits.csv has $rows rows for $nre reinsertions"
before=$(awk -F, -v t="$t0" 'NR > 1 && $2 < t' rc/exits.csv | wc -l)
after=$(awk -F, -v t="$t0" 'NR > 1 && $2 >= t' rc/exits.csv | wc -l)
[ "$before" -gt 0 ] && [ "$after" -gt 0 ] || fail "exits.csv: $before exits before t = $t0, $after after: not the whole drain"
awk -F, 'NR > 1 && ($2 < 0 || $2 > 4) { bad = 1 } END { exit bad }' rc/exits.csv || fail "exits.csv: a time outside 0..4 tau"
ok "recirculating: 300 in every snapshot, $nre reinsertions in time order, exits.csv $before before t = $t0 and $after after"
echo "cli $NAME: $PASS passed, 0 failed"
