#!/usr/bin/env bash
# CLI test: results that came out wrong without a word, and messages that
# misled (issue 26, items 6 and 7). Each check fails on the code before its
# fix; docs/reliability.md lists the guarantees they hold.
# usage: bash tests/cli/silent_results.sh GRANFLOW_BINARY TESTS_DATA_DIR
NAME=silent_results
source "$(dirname "$0")/lib.bash" "$@"
TINY=(--set container.width=12 --set container.depth=6 --set container.orifice_diameter=4
      --set packing.particles=1500 --set run.duration=3 --set run.threads=1)
CYL=(--set container.shape=cylinder --set container.radius=6 --set container.outlet_diameter=4)
# zmin FILE.xyz: the lowest centre of an XYZ packing.
zmin() { awk 'NR > 2 && (m == "" || $4 < m) { m = $4 } END { print m }' "$1"; }

# --- a cylinder's exit plane far below the outlet (old: the generator's "bug"
# check at -100; at -60 half the spheres hung in the open below the outlet) ---
for ez in -100 -60; do
    gf pack -q "${TINY[@]}" "${CYL[@]}" --set container.exit_z=$ez -o c$ez.xyz
    expect_rc 0 "pack a cylinder with container.exit_z=$ez"
    [ "$(zmin c$ez.xyz)" = 0.5 ] || fail "cylinder, exit_z=$ez: lowest centre at $(zmin c$ez.xyz), not on the base (0.5)"
done
gf pack -q "${TINY[@]}" "${CYL[@]}" --set container.outlet_length=3 --set container.exit_z=-60 -o pipe.xyz
expect_rc 0 "pack a cylinder with a pipe and container.exit_z=-60"
[ "$(zmin pipe.xyz)" = -2.5 ] || fail "cylinder with a 3 d pipe, exit_z=-60: lowest centre at $(zmin pipe.xyz), not at the pipe's end (-2.5)"
gf run -q "${TINY[@]}" "${CYL[@]}" --set container.exit_z=-60 --set run.duration=20 -o deep
expect_rc 1 "run a cylinder with container.exit_z=-60"
expect_err "the exit plane is 60 d below the outlet" "run a cylinder with container.exit_z=-60"
ok "a deep exit plane: the packing rests on the outlet (or fills the pipe); the run says why nothing leaves"

# --- pack -o p.xyz keeps the radii of a bidisperse packing (old: dropped) ---
gf pack -q --set container.width=12 --set container.depth=6 --set packing.particles=300 \
    --set packing.radius2=0.35 --set packing.fraction2=0.5 -o bi.xyz
expect_rc 0 "pack a bidisperse packing -o bi.xyz"
gf pack -q --set packing.file=bi.xyz -o bi.csv
expect_rc 0 "re-import bi.xyz"
[ "$(tail -n +2 bi.csv | cut -d, -f6 | sort -u | tr '\n' ' ')" = "0.35 0.5 " ] ||
    fail "bi.xyz -> bi.csv: radii $(tail -n +2 bi.csv | cut -d, -f6 | sort -u | tr '\n' ' '), not 0.35 and 0.5"
ok "a bidisperse packing keeps its radii through XYZ"

# --- dem --run: a LAMMPS that exits 0 without writing (old: "done", rc 0),
# and one that crashes (old: exit 130, "stopped by a signal") ------------------
printf '#!/bin/sh\necho "LAMMPS (stand-in)"\nexit 0\n' >lmp-silent
printf '#!/bin/sh\necho "LAMMPS (stand-in)"\nkill -SEGV $$\n' >lmp-segv
chmod +x lmp-silent lmp-segv
DEM=(--set container.width=10 --set container.depth=6 --set container.orifice_diameter=5 --set packing.particles=300
    --set run.duration=8 --set dem.mpi_ranks=1)
GF_LMP=$T/lmp-silent gf dem -q "${DEM[@]}" -o D --run
expect_rc 1 "dem --run with a LAMMPS that exits 0 and writes nothing"
expect_err "LAMMPS ended the fill (D/in.fill) with exit status 0 but wrote no D/settled.restart" "dem --run, silent LAMMPS"
grep -qF "done" "$T/err" && fail "dem --run with a silent LAMMPS says done"
GF_LMP=$T/lmp-silent gf dem -q "${DEM[@]}" -o D --drain-only
expect_rc 1 "dem --drain-only with a LAMMPS that exits 0 and writes nothing"
expect_err "with exit status 0 but wrote no snapshot in D/snapshots" "dem --drain-only, silent LAMMPS"
ok "dem --run: a LAMMPS that exits 0 but writes nothing is an error (exit 1)"
GF_LMP=$T/lmp-segv gf dem -q "${DEM[@]}" -o D --run --force
expect_rc 1 "dem --run with a LAMMPS that segfaults"
expect_err "LAMMPS crashed on D/in.fill: killed by signal 11 (Segmentation fault); see D/log.fill" "dem --run, LAMMPS segfaults"
grep -qF "stopped by a signal" "$T/err" && fail "a LAMMPS segfault is reported as a stop"
[ ! -e D/interrupted.txt ] || fail "a LAMMPS segfault wrote interrupted.txt"
ok "dem --run: a LAMMPS crash is a failure (exit 1, the signal named), not an interruption"

# --- a column that closes the silo, refused before the packing (old: accepted,
# "cannot drain" after the packing was built) ---------------------------------
gf run -q --set container.shape=cylinder --set container.inner_radius=2 --set container.hopper_angle=1e-300 -o col
expect_rc 2 "run with inner_radius = 2, hopper_angle = 1e-300"
expect_err "every spot would be removed at its first step" "inner_radius = 2, hopper_angle = 1e-300"
[ ! -e col ] || fail "inner_radius = 2, hopper_angle = 1e-300: the run directory was created"
gf config --set container.shape=cylinder --set container.radius=0.5 --set container.outlet_diameter=4
expect_rc 2 "outlet_diameter = 4 in a cylinder of radius 0.5"
expect_err "must be less than the cylinder's diameter 2R = 1 (container.radius = 0.5)" "outlet_diameter = 4, radius = 0.5"
ok "a column that closes the silo is refused up front; the cylinder's bounds are printed worked out"

# --- analyze: particles gone from the last frame that exits.csv does not list
# (old: rc 0, no word) ---------------------------------------------------------
gf run -q "${TINY[@]}" --set output.snapshot_interval=1 -o A
expect_rc 0 "run -o A"
gf analyze A --no-plots
grep -qF "does not list" "$T/err" && fail "analyze of a whole run warns about exits.csv"
L=A/snapshots/snap_000003.dump
awk 'NR == 6 { print $1 - 100; next } NR >= 12 && NR < 112 { next } { print }' $L >x && mv x $L
gf analyze A --no-plots
expect_rc 0 "analyze a series whose last frame lost 100 unlisted particles"
expect_err "A/snapshots/snap_000003.dump (t = 3 tau): 100 particles of the first frame are gone (id 1, ...) but A/exits.csv does not list them" \
    "analyze a series whose last frame lost 100 unlisted particles"
ok "analyze warns when particles are gone that exits.csv does not list"

# --- a NUL inside a value (old: "radius = 2\0junk" read as 2) ----------------
printf '[spot]\nradius = 2\000junk\n' >nul.ini
gf config nul.ini
expect_rc 2 "config with a NUL inside a value"
expect_err "nul.ini:2: a NUL byte (\0) at column 11: a configuration file is text" "config with a NUL inside a value"
ok "a NUL byte in a configuration file is refused, naming line and column"

# --- render --times beyond the run (old: drew t = 0) ---------------------------
gf render A --times 1e17 -o RT
expect_rc 2 "render --times 1e17"
expect_err "no snapshot of A near t = 1e+17 tau: its 4 snapshots go from t = 0 to 3 tau" "render --times 1e17"
[ ! -e RT ] || fail "render --times 1e17: the output directory was created"
gf render A --times 3.4 -o RT
expect_rc 0 "render --times 3.4 (the last snapshot is at 3, every 1 tau)"
[ -e RT/slice_000003.png ] || fail "render --times 3.4: no picture of the last snapshot"
ok "render refuses a time beyond the run, before it writes anything"

# --- a particle at z = 1e300 (old: "grid too large", no file, no particle) ---
printf 'x,y,z\n0,0,5\n1,0,1e300\n3,0,5\n' >far.csv
gf run -q --set packing.file=far.csv --set run.duration=0.2 -o FAR
expect_rc 2 "run with an imported particle at z = 1e300"
expect_err "far.csv:3: grid too large" "run with an imported particle at z = 1e300"
expect_err "particle id 2 at (1, 0, 1e+300) is the highest" "run with an imported particle at z = 1e300"
[ ! -e FAR ] || fail "run with a particle at z = 1e300: the run directory was created"
ok "a particle too high for the grid is named, with its file and line"

# --- a resume of a directory another run holds, before its first checkpoint
# (old: "no run to resume") ----------------------------------------------------
start run -q --set container.width=12 --set packing.particles=300 --set run.stall_time=0 \
    --set run.checkpoint_interval=0 --set run.duration=5000 -o LK
for ((i = 0; i < 200; i++)); do [ -e LK/snapshots/snap_000001.dump ] && break; sleep 0.1; done
[ -e LK/snapshots/snap_000001.dump ] || fail "run -o LK: no snapshot 1 after 20 s"
gf run -q --resume LK
expect_rc 2 "resume of a directory in use"
expect_err "LK is in use by another granflow run (pid $BGPID, lock LK/.lock)" "resume of a directory in use"
grep -qF "no run to resume" "$T/err" && fail "resume of a directory in use says 'no run to resume'"
kill -KILL "$BGPID"; wait "$BGPID" 2>/dev/null; BGPID=
ok "a resume of a directory in use says so"

# --- a packing.file with a line break (old: an empty run directory left) ------
NLF=$(printf 'a\nb.csv')
printf 'x,y,z\n0,0,5\n3,0,5\n' >"$NLF"
gf run -q --set "packing.file=$NLF" --set run.duration=0.2 -o NL
expect_rc 2 "run with a packing.file holding a line break"
expect_err "packing.file = a\x0Ab.csv contains a line break: config.ini could not hold it" "packing.file with a line break"
[ ! -e NL ] || fail "run with a packing.file holding a line break: the run directory was created"
gf dem -q --set "packing.file=$NLF" -o NLD
expect_rc 2 "dem with a packing.file holding a line break"
[ ! -e NLD ] || fail "dem with a packing.file holding a line break: the directory was created"
ok "a packing.file that config.ini cannot hold is refused before anything is created"

# --- compare of 2-snapshot runs (old: NaN rows, then "gnuplot failed") --------
gf run -q "${TINY[@]}" --set run.duration=1 --set output.snapshot_interval=1 -o C1
gf run -q "${TINY[@]}" --set run.seed=2 --set run.duration=1 --set output.snapshot_interval=1 -o C2
gf compare C1 C2 -o CMP
expect_rc 2 "compare of two 2-snapshot runs"
expect_err "too few snapshots to compare: the window 0.25..1 tau holds 1 of the DEM run's and 1 of the spot run's" \
    "compare of two 2-snapshot runs"
grep -qi nan "$T/out" && fail "compare of two 2-snapshot runs prints NaN"
[ ! -e CMP ] || fail "compare of two 2-snapshot runs: CMP was created"
ok "compare refuses runs with too few snapshots in the window, before writing anything"

# --- an impossible re-insertion zone, refused before the packing is built (old:
# at the first exit) -----------------------------------------------------------
gf run -q --set container.width=12 --set packing.particles=300 --set run.recirculate=on --set run.reinsert=zone \
    --set run.reinsert_rmin=6.8 -o RZ
expect_rc 2 "recirculation into a zone outside the box"
expect_err "run.reinsert_rmin = 6.8 and run.reinsert_rmax = auto (default) leave nothing of the container's cross-section" \
    "recirculation into a zone outside the box"
[ ! -e RZ ] || fail "recirculation into a zone outside the box: the run directory was created"
ok "an impossible re-insertion zone is refused up front"

# --- analyze of an empty directory or a VTK-only run (old: exit 1, "failed") ---
mkdir -p EMPTY
gf analyze EMPTY --no-plots
expect_rc 2 "analyze of an empty directory"
expect_err "EMPTY: no LAMMPS dumps in this directory" "analyze of an empty directory"
gf run -q --set container.width=12 --set packing.particles=300 --set run.duration=1 --set output.format=vtk -o VTK
expect_rc 0 "run with output.format = vtk"
gf analyze VTK --no-plots
expect_rc 2 "analyze of a VTK-only run"
expect_err "VTK/snapshots: only VTK (.vtu) snapshots" "analyze of a VTK-only run"
ok "analyze of a directory with nothing to read: exit 2 (the command line), with what to do"

# --- a checkpoint that cannot be written, refused before the run (old: ran to
# its end, then failed writing it) ----------------------------------------------
(trap '' XFSZ; ulimit -f 40; exec "$GF" run -q --set container.width=12 --set packing.particles=300 \
    --set run.checkpoint_interval=0 --set run.duration=3 -o FS) 2>"$T/err"
RC=$? LAST="run with ulimit -f 40 (checkpoint ~32 kB at the start, ~53 kB when all have left)"
expect_rc 1 "a checkpoint over the file size limit"
expect_err "cannot write checkpoint: File too large: it will take up to 0.05" \
    "a checkpoint over the file size limit"
grep -q '"simulated_time": 0,' FS/summary.json || fail "a checkpoint over the file size limit: the run ran before failing"
grep -q '"status": "failed"' FS/summary.json || fail "a checkpoint over the file size limit: summary.json is not 'failed'"
ok "a checkpoint that could not be written at the end is refused before the run starts"

echo "cli $NAME: $PASS passed, 0 failed"
