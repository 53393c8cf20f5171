#!/usr/bin/env bash
# CLI test: the failures a hostile user found (issue 16), one regression test
# each, the issue's own command made small. Each fails on the code before the
# fix (noted per test). docs/reliability.md lists the guarantees they check.
# usage: bash tests/cli/reliability.sh GRANFLOW_BINARY TESTS_DATA_DIR
NAME=reliability
source "$(dirname "$0")/lib.bash" "$@"
json() { sed -n "s/^[[:space:]]*\"$2\":[[:space:]]*\"\{0,1\}\([^\",]*\)\"\{0,1\},\{0,1\}[[:space:]]*$/\1/p" "$1"; }
# wait_for FILE SECONDS: until FILE exists (false if it never does).
wait_for() {
    local i
    for ((i = 0; i < $2 * 10; i++)); do [ -e "$1" ] && return 0; sleep 0.1; done
    return 1
}
TINY=(--set container.width=12 --set packing.particles=300 --set output.snapshot_interval=0.1)

# --- 1. huge containers: every size-derived count checked (old: segfault) -----
for key in container.width container.depth; do
    gf pack --set $key=1e20 --set packing.particles=100 -o x.dump
    expect_rc 2 "pack --set $key=1e20"
    expect_err "$key=1e20: out of range" "pack --set $key=1e20"
done
gf pack -q --set container.width=100000 --set container.depth=100000 --set packing.particles=100 -o x.dump
expect_rc 2 "pack on a 1e5 x 1e5 footprint"
expect_err "larger than the generator's limit" "pack on a 1e5 x 1e5 footprint"
ok "huge container.width / depth: exit 2 with the range, no crash"

# --- 2. runs Ctrl-C can stop (old: loops for ever / ignores signals) ----------
gf run -q "${TINY[@]}" --set run.checkpoint_interval=1e-20 -o C
expect_rc 2 "run.checkpoint_interval=1e-20"
expect_err "run.checkpoint_interval = 1e-20 is too small" "run.checkpoint_interval=1e-20"
gf run -q "${TINY[@]}" --set output.snapshot_interval=1e-300 -o C
expect_rc 2 "output.snapshot_interval=1e-300"
expect_err "output.snapshot_interval = 1e-300 is too small" "output.snapshot_interval=1e-300"
[ ! -e C ] || fail "a refused run created its directory"
ok "intervals too small for run.duration are refused up front"

# Packing generation of many spheres in a small box stops on SIGINT.
start run -q --set packing.particles=300000 --set container.width=10 --set container.depth=10 --set container.orifice_diameter=4 -o G
sleep 1
kill -INT "$BGPID"
finish 15
LAST="run (packing 300000 in a 10 x 10 box), SIGINT after 1 s"
expect_rc 130 "SIGINT while building the packing"
expect_err "interrupted while building the packing" "SIGINT while building the packing"
grep -qF -- "--resume" "$T/err" && fail "SIGINT while building the packing: offers a --resume of nothing"
[ ! -e G ] || fail "SIGINT while building the packing: the run directory was created"
ok "SIGINT during packing generation: exit 130 within seconds, nothing written"

# --- 3. physical ranges; a run that cannot progress is an error ---------------
for a in spot.insertion_rate=1e308 relax.radius=1e10 packing.layer_thickness=1e-300; do
    for mode in event fixed; do
        gf run -q "${TINY[@]}" --set run.mode=$mode --set $a -o "R-$mode-${a%%=*}"
        expect_rc 2 "run --set $a (run.mode=$mode)"
        expect_err "${a%%=*}" "run --set $a"
    done
done
gf pack -q --set packing.layer_thickness=1e-300 --set packing.particles=100 -o lt.dump
expect_rc 2 "pack --set packing.layer_thickness=1e-300"
gf run -q "${TINY[@]}" --set spot.insertion_rate=1e6 -o R-rate
expect_rc 2 "spot.insertion_rate=1e6 with spot.move_rate=28"
expect_err "too high for spot.move_rate" "spot.insertion_rate=1e6"
ok "insertion_rate, relax.radius, layer_thickness out of their physical ranges: exit 2"

# Nothing can reach exit_z = -1000 (spots are born 1000 d below the packing).
gf run -q "${TINY[@]}" --set output.snapshot_interval=1 --set container.exit_z=-1000 --set run.duration=40 -o N
expect_rc 1 "run with nothing able to leave"
expect_err "no particle has left the silo in 10 tau" "run with nothing able to leave"
[ "$(json N/summary.json status)" = failed ] || fail "run with nothing able to leave: summary.json status is '$(json N/summary.json status)', not failed"
ok "a silo that cannot drain: exit 1, summary.json status failed"

# --- 4. nothing lost with the defaults (old: no exits, rc 129 on SIGHUP) ------
start run -q "${TINY[@]}" --set run.stall_time=0 --set run.checkpoint_interval=0 --set run.duration=5000 -o K
wait_for K/snapshots/snap_000030.dump 20 || fail "run -o K: no snapshot 30 after 20 s"
sleep 0.2
kill -KILL "$BGPID"; wait "$BGPID" 2>/dev/null; BGPID=
[ "$(head -n 1 K/exits.csv)" = "id,time,x,y,pass,entry_time,entry_r" ] || fail "kill -9: exits.csv missing or without its header"
[ "$(wc -l <K/exits.csv)" -gt 10 ] || fail "kill -9 after t = 3: exits.csv holds $(($(wc -l <K/exits.csv) - 1)) exits"
[ "$(json K/summary.json status)" = running ] || fail "kill -9: summary.json missing or not 'running'"
[ "$(json K/summary.json particles_exited)" -gt 10 ] || fail "kill -9: summary.json counts no exits"
ok "kill -9 with checkpoint_interval = 0: exits.csv and summary.json are on disk"

start run -q "${TINY[@]}" --set run.stall_time=0 --set run.duration=5000 -o H
wait_for H/snapshots/snap_000005.dump 20 || fail "run -o H: no snapshot 5 after 20 s"
kill -HUP "$BGPID"
finish 15
LAST="run -o H, SIGHUP"
expect_rc 130 "SIGHUP"
[ -s H/checkpoint.bin ] || fail "SIGHUP: no checkpoint"
[ "$(json H/summary.json status)" = interrupted ] || fail "SIGHUP: summary.json status is not interrupted"
reached=$(json H/summary.json simulated_time)
gf run -q --resume H --set run.duration="$(awk -v t="$reached" 'BEGIN { print t + 0.5 }')"
expect_rc 0 "resume after SIGHUP"
ok "SIGHUP (a closed terminal) checkpoints like SIGINT: exit 130, resumable"

# --- 5. one run per directory, --force starts clean (old: mixed runs, rc 0) ---
gf run -q "${TINY[@]}" --set run.duration=3 -o F
expect_rc 0 "run -o F"
gf analyze F --no-plots
expect_rc 0 "analyze F"
[ -d F/analysis ] || fail "analyze F wrote no F/analysis"
# A fresh run into F without --force is refused (GF_ERR_EXISTS), and the
# CLI adds the flags that answer it on that status, not on the wording.
gf run -q "${TINY[@]}" --set run.duration=0.2 -o F
expect_rc 2 "a fresh run into F, which holds a run"
expect_err "F already holds a run" "a fresh run into F"
expect_err "(resume it with --resume F, overwrite it with --force, or choose another -o)" "a fresh run into F"
start run -q "${TINY[@]}" --set run.stall_time=0 --set run.checkpoint_interval=0 --set run.duration=5000 --force -o F
wait_for F/snapshots/snap_000002.dump 20 || fail "run --force -o F: no snapshot 2 after 20 s"
sleep 0.3
# While it runs, a second run into F fails, with or without --force.
gf run -q "${TINY[@]}" --set run.duration=0.2 --force -o F
expect_rc 2 "a second run into F"
expect_err "F is in use by another granflow run" "a second run into F"
kill -KILL "$BGPID"; wait "$BGPID" 2>/dev/null; BGPID=
[ ! -e F/checkpoint.bin ] || fail "killed --force run: the old run's checkpoint.bin is still there"
[ ! -e F/analysis ] || fail "killed --force run: the old run's analysis/ is still there"
[ "$(json F/summary.json status)" = running ] || fail "killed --force run: summary.json is not the new run's"
ok "--force clears the old run first; a second run into a busy directory fails clearly"

# --- 6. impossible inputs (old: accepted, rc 0 / rc 1) -----------------------
printf 'x,y,z\n0,0,5\n0,0,5\n3,0,5\n' >same.csv
gf run -q --set packing.file=same.csv --set run.duration=0.2 -o I
expect_rc 3 "import with coincident centres"
expect_err "same.csv: particles id 1 and id 2 have the same centre" "import with coincident centres"
printf 'x,y,z,radius\n0,0,5,100\n3,0,5,0.5\n' >big.csv
gf run -q --set packing.file=big.csv --set run.duration=0.2 -o I
expect_rc 3 "import with radius 100"
expect_err "big.csv: particle id 1 has radius 100" "import with radius 100"
ok "coincident centres and a radius of 100 in an import: exit 3"

gf run -q "${TINY[@]}" --set output.snapshot_interval=1 --set run.duration=3 -o A
cp A/snapshots/snap_000000.dump A/snapshots/snap_000004.dump
sed -i '2s/.*/4/' A/snapshots/snap_000004.dump # the full first frame again, at t = 4
gf analyze A --no-plots
expect_rc 3 "analyze a series whose particle count grows"
expect_err "the particle count grows" "analyze a series whose particle count grows"
ok "analyze on a growing particle count: exit 3"

# --- 6b. reads with an end (issue 26; old: memory grew at ~0.5 GB/s, or ------
# ENOMEM read as the end of the file and the defaults run, rc 0; report wrote
# until the disk was full, or waited on a FIFO for ever). A memory limit keeps
# the old code's growth small; not under ASan, whose shadow memory needs more.
sanitized() { ldd "$GF" 2>/dev/null | grep -q 'libasan\|libubsan'; }
limited() { # limited KB CMD...: CMD under ulimit -v KB (none when sanitized) and a 60 s timeout
    local kb=$1; shift
    if sanitized; then timeout 60 "$@"; else (ulimit -v "$kb"; exec timeout 60 "$@"); fi
}
LAST="granflow run /dev/zero (ulimit -v 2000000)"
limited 2000000 "$GF" run -q /dev/zero "${TINY[@]}" --set run.duration=0.2 -o Z0 >"$T/out" 2>"$T/err"; RC=$?
expect_rc 2 "run /dev/zero"
expect_err "/dev/zero:1: line longer than 65536 bytes" "run /dev/zero"
[ ! -e Z0 ] || fail "run /dev/zero made its directory"
ok "a configuration without line ends: exit 2 naming file and line, not the defaults"

gf run -q "${TINY[@]}" --set run.duration=0.2 -o Z
expect_rc 0 "a short run for the readers"
mv Z/config.ini Z/config.keep && ln -s /dev/zero Z/config.ini
LAST="granflow run --resume Z, Z/config.ini -> /dev/zero"
limited 2000000 "$GF" run -q --resume Z >"$T/out" 2>"$T/err"; RC=$?
expect_rc 2 "resume with config.ini -> /dev/zero"
expect_err "Z/config.ini:1: line longer than 65536 bytes" "resume with config.ini -> /dev/zero"
rm Z/config.ini && mv Z/config.keep Z/config.ini
ok "resume: a config.ini linked to /dev/zero is refused"

mkdir -p Z/render && ln -s /dev/zero Z/render/x.png
LAST="granflow report Z, Z/render/x.png -> /dev/zero"
(ulimit -f 100000; exec timeout 60 "$GF" report Z) >"$T/out" 2>"$T/err"; RC=$?
expect_rc 1 "report with a picture linked to /dev/zero"
expect_err "Z/render/x.png: not a regular file (a character device)" "report with a picture linked to /dev/zero"
[ ! -e Z/report.html.tmp ] && [ ! -e Z/report.html ] || fail "report with a picture linked to /dev/zero left $(ls Z | grep report)"
rm Z/render/x.png
mv Z/summary.json Z/summary.keep && mkfifo Z/summary.json
LAST="granflow report Z, Z/summary.json a FIFO"
timeout 60 "$GF" report Z >"$T/out" 2>"$T/err"; RC=$?
expect_rc 1 "report with summary.json a FIFO"
expect_err "Z/summary.json: not a regular file (a FIFO)" "report with summary.json a FIFO"
rm Z/summary.json && mv Z/summary.keep Z/summary.json
mkdir -p Z/analysis && mkfifo Z/analysis/summary.json
LAST="granflow analyze outflow Z, Z/analysis/summary.json a FIFO"
timeout 60 "$GF" analyze outflow Z --no-plots >"$T/out" 2>"$T/err"; RC=$?
expect_rc 1 "analyze NAME with analysis/summary.json a FIFO"
expect_err "Z/analysis/summary.json: not a regular file (a FIFO)" "analyze NAME with analysis/summary.json a FIFO"
rm Z/analysis/summary.json
gf report Z
expect_rc 0 "report of the same directory made whole again"
ok "report and analyze read back only regular files: a FIFO or /dev/zero is refused, nothing left"

# More spheres than the process may ever hold: refused before the generator
# allocates (old: it allocated and zeroed gigabytes, then ran out of memory).
if ! sanitized; then
    LAST="granflow pack --set packing.particles=50000000 (ulimit -v 1000000)"
    (ulimit -v 1000000; exec timeout 60 "$GF" pack -q --set packing.particles=50000000 -o big.dump) >"$T/out" 2>"$T/err"; RC=$?
    expect_rc 1 "pack of 5e7 spheres under ulimit -v"
    expect_err "packing: 50000000 particles need about 10.0 GB to generate, more than the 1.0 GB this process may have (ulimit -v)" \
        "pack of 5e7 spheres under ulimit -v"
    ok "a packing that cannot fit in memory is refused up front, saying how much it needs"
fi

# --- 7. messages -------------------------------------------------------------
gf run -q --set "spot.w=$(printf '1\001\033[31mX\377')" -o M
expect_rc 2 "--set with binary bytes"
LC_ALL=C grep -q "$(printf '[\001\033\377]')" "$T/err" && fail "binary bytes echoed raw into the error"
expect_err '1\x01\x1B[31mX\xFF' "--set with binary bytes"
printf '[spot]\nw = 3\001\n' >bin.ini
gf run -q bin.ini -o M
expect_rc 2 "config file with a binary byte"
expect_err "w = '3\\x01'" "config file with a binary byte"
ok "binary bytes in input are escaped (\\xNN) in messages"

long=/nonexistent/$(printf 'a%.0s' $(seq 1000))
gf run -q --set "packing.file=$long" -o M
expect_rc 1 "packing.file with a 1012-byte path"
expect_err "No such file or directory" "packing.file with a 1012-byte path"
ok "a long path does not hide the reason of the error"

# A checkpoint larger than the file size limit: the write fails with EFBIG.
(trap '' XFSZ; ulimit -f 20; exec "$GF" run -q "${TINY[@]}" --set run.checkpoint_interval=0.1 --set run.duration=0.3 -o W) 2>"$T/err"
RC=$? LAST="run with ulimit -f 20 (checkpoint ~32 kB)"
expect_rc 1 "checkpoint over the file size limit"
expect_err "cannot write checkpoint: File too large" "checkpoint over the file size limit"
[ "$(json W/summary.json status)" = failed ] || fail "failed run: summary.json status is '$(json W/summary.json status)', not failed"
grep -qF "File too large" W/summary.json || fail "failed run: summary.json does not give the error"
ok "a failed checkpoint names the reason; summary.json says failed"

gf lga --set run.duration=5 -o L
expect_rc 2 "lga --set run.duration=5"
expect_err "run.duration = 5: the lattice-gas automaton does not use this key" "lga --set run.duration=5"
ok "lga refuses keys it does not use"

# A stalled silo (300 particles, 12 d wide: the flow stops near t = 16) stops early.
gf run "${TINY[@]}" --set output.snapshot_interval=1 --set run.duration=200 -o S
expect_rc 0 "run of a silo that stalls"
expect_err "the flow stopped: no particle has left since" "run of a silo that stalls"
[ "$(json S/summary.json status)" = stalled ] || fail "stalled silo: summary.json status is not stalled"
awk -v t="$(json S/summary.json simulated_time)" 'BEGIN { exit !(t < 100) }' || fail "stalled silo ran on to t = $(json S/summary.json simulated_time)"
[ "$(ls S/snapshots | wc -l)" -lt 100 ] || fail "stalled silo: $(ls S/snapshots | wc -l) snapshots"
ok "a stalled silo says so and stops (status stalled)"

echo "cli $NAME: $PASS passed, 0 failed"
