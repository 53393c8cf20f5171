#!/usr/bin/env bash
# CLI test: `granflow run` writes a complete run directory; --resume extends a
# run bit-for-bit like a run done in one go; resume errors (no run, corrupt
# checkpoint, changed physics) are reported; SIGINT/SIGTERM stop with exit
# 130 and a checkpoint that resumes.
# usage: bash tests/cli/run_resume.sh GRANFLOW_BINARY TESTS_DATA_DIR
NAME=run_resume
source "$(dirname "$0")/lib.bash" "$@"
BGPID=
cleanup() {
    if [ -n "$BGPID" ]; then kill -KILL "$BGPID" 2>/dev/null; wait "$BGPID" 2>/dev/null; fi
    rm -rf "$T"
}
SKIP=0
skip() {
    SKIP=$((SKIP + 1))
    echo "skip - $*"
}
# json FILE KEY: the value of a top-level scalar key of summary.json (quotes removed).
json() { sed -n "s/^[[:space:]]*\"$2\":[[:space:]]*\"\{0,1\}\([^\",]*\)\"\{0,1\},\{0,1\}[[:space:]]*$/\1/p" "$1"; }
# same_number A B: numerically equal (summary.json prints %.9g).
same_number() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a != "" && b != "" && a + 0 == b + 0) }'; }
# digest DIR: checksums of every file in DIR (to prove a failed command changed nothing).
digest() { (cd "$1" && find . -type f -print0 | sort -z | xargs -0 cksum); }

TINY=(--set container.width=12 --set packing.particles=300 --set output.snapshot_interval=0.1)

# --- a fresh run writes the whole run directory ------------------------------
gf run -q "${TINY[@]}" --set run.duration=0.3 -o A
expect_rc 0 "run -o A (duration 0.3)"
for f in config.ini snapshots/snap_000000.dump exits.csv summary.json checkpoint.bin; do
    [ -s "A/$f" ] || fail "run -o A: A/$f missing or empty"
done
[ -z "$(find A -name '*.tmp')" ] || fail "run -o A left temporary files: $(find A -name '*.tmp')"
ok "run writes config.ini, snapshots/, exits.csv, summary.json, checkpoint.bin"

[ "$(head -n 1 A/snapshots/snap_000000.dump)" = "ITEM: TIME" ] || fail "snap_000000.dump: first line is not 'ITEM: TIME'"
grep -q '^ITEM: ATOMS id type x y z' A/snapshots/snap_000000.dump || fail "snap_000000.dump: no 'ITEM: ATOMS id type x y z'"
[ "$(sed -n '/^ITEM: NUMBER OF ATOMS/{n;p;}' A/snapshots/snap_000000.dump)" = 300 ] || fail "snap_000000.dump: not 300 atoms"
ok "snap_000000.dump is a LAMMPS dump starting with ITEM: TIME, 300 atoms"

[ "$(head -n 1 A/exits.csv | tr -d '\r')" = "id,time,x,y,pass,entry_time,entry_r" ] || fail "exits.csv: header is not 'id,time,x,y,pass,entry_time,entry_r'"
ok "exits.csv has the header id,time,x,y,pass,entry_time,entry_r"

for key in particles_initial particles_remaining particles_exited spots_inserted spot_moves relax_calls \
    simulated_time wall_seconds steps_per_second; do
    grep -q "\"$key\":" A/summary.json || fail "summary.json: key $key missing"
done
[ "$(json A/summary.json particles_initial)" = 300 ] || fail "summary.json: particles_initial is not 300"
same_number "$(json A/summary.json simulated_time)" 0.3 || fail "summary.json: simulated_time is not 0.3"
[ "$(json A/summary.json status)" = complete ] || fail "summary.json: status is not \"complete\""
n0=$(json A/summary.json particles_initial) nr=$(json A/summary.json particles_remaining) ne=$(json A/summary.json particles_exited)
[ $((nr + ne)) -eq "$n0" ] || fail "summary.json: particles_remaining + particles_exited != particles_initial"
ok "summary.json has every key, status complete, simulated_time 0.3, counts add up"

gf config A/config.ini
expect_rc 0 "granflow config A/config.ini"
grep -qx 'width = 12' out || fail "A/config.ini does not record container.width = 12"
ok "A/config.ini is a valid configuration recording the --set values"

# --- a second fresh run into the same directory is refused -------------------
before=$(digest A)
gf run -q "${TINY[@]}" --set run.duration=0.3 -o A
expect_rc 2 "second run into A without --force"
expect_err "--resume" "second run into A without --force"
[ "$(digest A)" = "$before" ] || fail "the refused second run changed files in A"
ok "second run into A without --force: exit 2, suggests --resume, A unchanged"

gf run -q --resume A default.ini
expect_rc 2 "run --resume A with a CONFIG argument"
ok "--resume with a CONFIG argument: exit 2"

# --- resume extends a run exactly like a run done in one go ---------------------
gf run -q --resume A --set run.duration=0.6
expect_rc 0 "run --resume A --set run.duration=0.6"
same_number "$(json A/summary.json simulated_time)" 0.6 || fail "after resume: simulated_time is $(json A/summary.json simulated_time), not 0.6"
[ "$(json A/summary.json status)" = complete ] || fail "after resume: status is not \"complete\""
ok "--resume --set run.duration=0.6: exit 0, simulated_time 0.6"

gf run -q "${TINY[@]}" --set run.duration=0.6 -o B
expect_rc 0 "run -o B (duration 0.6 in one go)"
last=$(ls B/snapshots | tail -n 1)
[ -n "$last" ] && [ "$last" = "$(ls A/snapshots | tail -n 1)" ] ||
    fail "resumed and one-go runs end with different snapshots: A $(ls A/snapshots | tail -n 1), B $last"
cmp -s "A/snapshots/$last" "B/snapshots/$last" || fail "A/snapshots/$last (resumed) differs from B/snapshots/$last (one go)"
for f in B/snapshots/*.dump; do
    cmp -s "$f" "A/snapshots/${f##*/}" || fail "snapshot ${f##*/}: resumed run differs from the one-go run"
done
ok "resumed run's snapshots (last: $last) are byte-identical to the one-go run's"

# Longer, so that particles leave: exits.csv must match too.
gf run -q --resume A --set run.duration=3
expect_rc 0 "run --resume A --set run.duration=3"
gf run -q "${TINY[@]}" --set run.duration=3 -o C
expect_rc 0 "run -o C (duration 3 in one go)"
[ "$(json C/summary.json particles_exited)" -gt 0 ] || fail "no particle left C in 3 tau: exits.csv comparison would be empty"
last=$(ls C/snapshots | tail -n 1)
cmp -s "A/snapshots/$last" "C/snapshots/$last" || fail "snapshot $last: run resumed twice differs from the one-go run"
cmp -s A/exits.csv C/exits.csv || fail "exits.csv: run resumed twice differs from the one-go run"
for key in particles_exited spots_inserted spot_moves relax_calls simulated_time; do
    [ "$(json A/summary.json $key)" = "$(json C/summary.json $key)" ] ||
        fail "summary.json $key: resumed $(json A/summary.json $key), one go $(json C/summary.json $key)"
done
ok "run resumed twice (0.3 -> 0.6 -> 3) matches one go: last snapshot, exits.csv, counters"

# --force starts afresh and drops the old run's later snapshots.
gf run -q "${TINY[@]}" --set run.duration=0.3 --force -o B
expect_rc 0 "run --force -o B (duration 0.3 over a 0.6 run)"
same_number "$(json B/summary.json simulated_time)" 0.3 || fail "after --force: simulated_time is not 0.3"
[ ! -e B/snapshots/snap_000006.dump ] || fail "after --force: the old run's snap_000006.dump is still there"
ok "--force overwrites a run and removes its later snapshots"

# A hopper (cylinder, funnel, pipe, column) resumes byte-identically too.
HOP=(--set container.shape=cylinder --set container.radius=5 --set container.hopper_angle=60
     --set container.outlet_diameter=6 --set container.outlet_length=2 --set container.inner_radius=1
     --set packing.particles=800 --set output.snapshot_interval=0.5)
gf run -q "${HOP[@]}" --set run.duration=1 -o H1
expect_rc 0 "run (a hopper, 1 tau)"
gf run -q --resume H1 --set run.duration=2
expect_rc 0 "run --resume H1 --set run.duration=2"
gf run -q "${HOP[@]}" --set run.duration=2 -o H2
expect_rc 0 "run (a hopper, 2 tau)"
cmp -s H1/snapshots/snap_000004.dump H2/snapshots/snap_000004.dump || fail "resumed hopper: snapshot at 2 tau differs"
cmp -s H1/exits.csv H2/exits.csv || fail "resumed hopper: exits.csv differs"
[ "$(wc -l < H2/exits.csv)" -gt 1 ] || fail "the hopper run had no exits"
ok "a hopper run resumed (1 -> 2 tau) matches one go: snapshot and exits"

# --- resume errors ------------------------------------------------------------
mkdir empty_dir
gf run -q --resume empty_dir
expect_rc 2 "run --resume empty_dir"
expect_err "empty_dir" "run --resume empty_dir"
gf run -q --resume no_such_dir --set run.duration=1
expect_rc 2 "run --resume no_such_dir"
expect_err "no_such_dir" "run --resume no_such_dir"
[ ! -e no_such_dir ] || fail "run --resume no_such_dir created no_such_dir"
ok "--resume of a directory without a run: exit 2 naming it"

cp -R C D
before=$(digest D)
gf run -q --resume D --set run.duration=4 --set spot.w=400
expect_rc 2 "run --resume D --set spot.w=400 (physics changed)"
expect_err "checkpoint" "run --resume D --set spot.w=400"
[ "$(digest D)" = "$before" ] || fail "the refused resume with spot.w=400 changed files in D"
gf run -q --resume D --set run.duration=4 --set container.width=14
expect_rc 2 "run --resume D --set container.width=14 (geometry changed)"
ok "changing physics or geometry on resume: exit 2, run untouched"

size=$(wc -c <D/checkpoint.bin)
printf 'XXXXXXXXXXXXXXXX' | dd of=D/checkpoint.bin bs=1 seek=$((size / 2)) conv=notrunc 2>/dev/null
before=$(digest D)
gf run -q --resume D --set run.duration=4
expect_rc 3 "run --resume D with a corrupted checkpoint.bin"
expect_err "checksum" "run --resume D with a corrupted checkpoint.bin"
expect_err "checkpoint.bin" "run --resume D with a corrupted checkpoint.bin"
[ "$(digest D)" = "$before" ] || fail "resume from a corrupted checkpoint changed files in D"
ok "corrupted checkpoint.bin: exit 3 with 'checksum', nothing written"

head -c $((size / 3)) C/checkpoint.bin >D/checkpoint.bin
gf run -q --resume D --set run.duration=4
expect_rc 3 "run --resume D with a truncated checkpoint.bin"
expect_err "checkpoint.bin" "run --resume D with a truncated checkpoint.bin"
ok "truncated checkpoint.bin: exit 3 naming it"

# --- SIGINT / SIGTERM -------------------------------------------------------------
# interrupt SIGNAL DIR: starts a long tiny run into DIR, sends SIGNAL after a
# moment; sets RC (or RC=skip if the run ended before the signal).
interrupt() {
    local sig=$1 dir=$2 waited=0
    LAST="granflow run -q ${TINY[*]} --set output.snapshot_interval=5 --set run.duration=1000000 -o $dir (then kill -$sig)"
    "$GF" run -q "${TINY[@]}" --set output.snapshot_interval=5 --set run.duration=1000000 -o "$dir" \
        >"$T/out" 2>"$T/err" &
    BGPID=$!
    sleep 1
    if ! kill -"$sig" "$BGPID" 2>/dev/null; then
        wait "$BGPID"
        RC=$?
        BGPID=
        echo "  (the run ended with exit $RC before SIG$sig was sent)"
        RC=skip
        return
    fi
    while kill -0 "$BGPID" 2>/dev/null && [ $waited -lt 100 ]; do
        sleep 0.1
        waited=$((waited + 1))
    done
    if kill -0 "$BGPID" 2>/dev/null; then
        kill -KILL "$BGPID" 2>/dev/null
        wait "$BGPID" 2>/dev/null
        BGPID=
        RC=hung
        fail "run did not stop within 10 s of SIG$sig"
    fi
    wait "$BGPID"
    RC=$?
    BGPID=
}

interrupt INT I
if [ "$RC" = skip ]; then
    skip "SIGINT: the run finished before the signal; interrupt and resume not tested"
else
    expect_rc 130 "SIGINT during run -o I"
    [ -s I/checkpoint.bin ] || fail "SIGINT: no I/checkpoint.bin"
    [ "$(json I/summary.json status)" = interrupted ] ||
        fail "SIGINT: summary.json status is '$(json I/summary.json status)', not 'interrupted'"
    expect_err "--resume" "SIGINT during run -o I"
    ok "SIGINT: exit 130, checkpoint.bin written, summary.json status interrupted"

    reached=$(json I/summary.json simulated_time)
    # The next multiple of the snapshot interval (5) at least 5 tau beyond, so both runs end on a snapshot.
    until=$(awk -v t="$reached" 'BEGIN { printf "%d", 5 * int(t / 5) + 10 }')
    gf run -q --resume I --set run.duration="$until"
    expect_rc 0 "run --resume I --set run.duration=$until (interrupted at t = $reached)"
    same_number "$(json I/summary.json simulated_time)" "$until" || fail "after resuming I: simulated_time is not $until"
    [ "$(json I/summary.json status)" = complete ] || fail "after resuming I: status is not complete"
    ok "resume after SIGINT at t = $reached to $until: exit 0, status complete"

    gf run -q "${TINY[@]}" --set output.snapshot_interval=5 --set run.duration="$until" -o J
    expect_rc 0 "run -o J (duration $until in one go)"
    last=$(ls J/snapshots | tail -n 1)
    cmp -s "I/snapshots/$last" "J/snapshots/$last" ||
        fail "snapshot $last: run interrupted at t = $reached and resumed differs from the one-go run"
    cmp -s I/exits.csv J/exits.csv || fail "exits.csv: run interrupted at t = $reached and resumed differs from the one-go run"
    ok "interrupted + resumed run matches the one-go run to $until (last snapshot, exits.csv)"
fi

interrupt TERM K
if [ "$RC" = skip ]; then
    skip "SIGTERM: the run finished before the signal"
else
    expect_rc 130 "SIGTERM during run -o K"
    [ -s K/checkpoint.bin ] || fail "SIGTERM: no K/checkpoint.bin"
    [ "$(json K/summary.json status)" = interrupted ] || fail "SIGTERM: summary.json status is not 'interrupted'"
    ok "SIGTERM: exit 130, checkpoint.bin written, status interrupted"
fi

if [ "$SKIP" -gt 0 ]; then
    echo "cli $NAME: $PASS passed, 0 failed, $SKIP skipped"
else
    echo "cli $NAME: $PASS passed, 0 failed"
fi
exit 0
