#!/usr/bin/env bash
# CLI test: `granflow pack` writes and converts packings; bad packing files
# (truncated, garbage numbers, missing, particles outside the container) fail
# with the right exit code, name the file (and line or particle id), and leave
# no half-written output behind.
# usage: bash tests/cli/pack_import.sh GRANFLOW_BINARY TESTS_DATA_DIR
NAME=pack_import
source "$(dirname "$0")/lib.bash" "$@"
# no_run_output DIR WHAT: a failed run must not leave result files in DIR.
no_run_output() {
    local f
    for f in summary.json checkpoint.bin config.ini exits.csv; do
        [ ! -e "$1/$f" ] || fail "$2: $1/$f was written although the run failed"
    done
    if [ -d "$1" ]; then
        local files
        files=$(find "$1" -type f | head -n 5)
        [ -z "$files" ] || fail "$2: the failed run left files in $1: $files"
    fi
}
# atoms FILE: "id x y z radius" of every atom of a single-frame LAMMPS dump.
atoms() { awk '/^ITEM: ATOMS/ { a = 1; next } a { print $1, $3, $4, $5, $6 }' "$1"; }

TINY=(--set container.width=12 --set packing.particles=300 --set run.duration=0.3)

# --- pack writes a LAMMPS dump -------------------------------------------------
gf pack -q "${TINY[@]}" -o x.dump
expect_rc 0 "pack -o x.dump"
[ -s x.dump ] || fail "pack -o x.dump: x.dump not written"
[ "$(head -n 1 x.dump)" = "ITEM: TIMESTEP" ] || fail "x.dump: first line is not 'ITEM: TIMESTEP'"
[ "$(sed -n '/^ITEM: NUMBER OF ATOMS/{n;p;}' x.dump)" = 300 ] || fail "x.dump: NUMBER OF ATOMS is not 300"
grep -q '^ITEM: ATOMS id type x y z' x.dump || fail "x.dump: no 'ITEM: ATOMS id type x y z' line"
[ "$(atoms x.dump | wc -l)" -eq 300 ] || fail "x.dump: does not hold 300 atom lines"
[ ! -e x.dump.tmp ] || fail "pack left x.dump.tmp behind"
ok "pack -o x.dump writes a 300-atom LAMMPS dump"

# --- pack converts -------------------------------------------------------------
gf pack -q --set packing.file=x.dump -o y.xyz
expect_rc 0 "pack packing.file=x.dump -o y.xyz"
[ "$(head -n 1 y.xyz | tr -d ' \r')" = 300 ] || fail "y.xyz: first line is not the count 300"
[ "$(wc -l <y.xyz)" -eq 302 ] || fail "y.xyz: expected 302 lines (count, comment, 300 atoms)"
ok "pack converts x.dump to y.xyz"

gf pack -q --set packing.file=y.xyz -o back.dump
expect_rc 0 "pack packing.file=y.xyz -o back.dump"
atoms x.dump >x.atoms
atoms back.dump >back.atoms
cmp -s x.atoms back.atoms || fail "x.dump -> y.xyz -> back.dump changed ids or coordinates"
ok "dump -> xyz -> dump keeps ids and coordinates exactly"

gf pack -q --set packing.file=x.dump -o y.csv
expect_rc 0 "pack packing.file=x.dump -o y.csv"
head -n 1 y.csv | grep -q 'x,y,z' || fail "y.csv: header does not name x,y,z"
[ "$(wc -l <y.csv)" -eq 301 ] || fail "y.csv: expected 301 lines (header, 300 atoms)"
ok "pack converts x.dump to y.csv"

gf pack -q --set "packing.file=$DATA/multiframe.dump" -o last.csv
expect_rc 0 "pack packing.file=multiframe.dump -o last.csv"
[ "$(tail -n +2 last.csv | cut -d, -f1 | tr '\n' ' ')" = "4 2 3 " ] ||
    fail "multiframe.dump: expected the last frame (ids 4 2 3), got: $(tail -n +2 last.csv | cut -d, -f1 | tr '\n' ' ')"
ok "pack imports the last frame of a multi-frame dump"

# --- pack usage errors ------------------------------------------------------
gf pack -q "${TINY[@]}"
expect_rc 2 "pack without -o"
expect_err "-o" "pack without -o"
ok "pack without -o: exit 2"

gf pack -q "${TINY[@]}" -o no_such_dir/sub/x.dump
expect_rc 1 "pack -o no_such_dir/sub/x.dump"
expect_err "no_such_dir/sub/x.dump" "pack -o no_such_dir/sub/x.dump"
ok "pack into a missing directory: exit 1 naming the path"

# --- truncated dump ---------------------------------------------------------
size=$(wc -c <x.dump)
head -c $((size / 2)) x.dump >trunc.dump
gf run -q "${TINY[@]}" --set packing.file=trunc.dump -o run_trunc
expect_rc 3 "run with a truncated packing.file"
expect_err "trunc.dump" "run with a truncated packing.file"
grep -qE 'trunc\.dump:[0-9]+' err || fail "run with a truncated packing.file: no trunc.dump:LINE in stderr"
no_run_output run_trunc "run with a truncated packing.file"
ok "run with a truncated dump: exit 3, trunc.dump:LINE, no run files written"

gf pack -q --set packing.file=trunc.dump -o from_trunc.xyz
expect_rc 3 "pack with a truncated packing.file"
expect_err "trunc.dump" "pack with a truncated packing.file"
[ ! -e from_trunc.xyz ] || fail "pack with a truncated packing.file wrote from_trunc.xyz"
ok "pack with a truncated dump: exit 3, no output file"

head -n 3 x.dump >header_only.dump
gf pack -q --set packing.file=header_only.dump -o from_header.xyz
expect_rc 3 "pack with a dump cut inside its header"
expect_err "header_only.dump" "pack with a dump cut inside its header"
ok "dump cut inside its header: exit 3 naming the file"

: >empty.dump
gf pack -q --set packing.file=empty.dump -o from_empty.xyz
expect_rc 3 "pack with an empty dump"
expect_err "empty.dump" "pack with an empty dump"
ok "empty dump: exit 3 naming the file"

# --- garbage numbers --------------------------------------------------------
# Line 20 is the 11th atom (9 header lines); its x becomes "1.2.3".
awk 'NR == 20 { $3 = "1.2.3" } { print }' x.dump >garbage.dump
gf run -q "${TINY[@]}" --set packing.file=garbage.dump -o run_garbage
expect_rc 3 "run with a garbage number in packing.file"
expect_err "garbage.dump:20" "run with a garbage number in packing.file"
expect_err "1.2.3" "run with a garbage number in packing.file"
no_run_output run_garbage "run with a garbage number in packing.file"
ok "dump with a garbage number: exit 3 with garbage.dump:20 and the text"

awk 'NR == 20 { $5 = "nan" } { print }' x.dump >nan.dump
gf pack -q --set packing.file=nan.dump -o from_nan.xyz
expect_rc 3 "pack with z = nan"
expect_err "nan.dump:20" "pack with z = nan"
[ ! -e from_nan.xyz ] || fail "pack with z = nan wrote from_nan.xyz"
ok "dump with z = nan: exit 3 with nan.dump:20"

awk -F, -v OFS=, 'NR == 31 { $3 = "zz" } { print }' y.csv >garbage.csv
gf pack -q --set packing.file=garbage.csv -o from_garbage.dump
expect_rc 3 "pack with a garbage number in a CSV"
expect_err "garbage.csv:31" "pack with a garbage number in a CSV"
ok "CSV with a garbage number: exit 3 with garbage.csv:31"

awk 'NR == 52 { $1 = 42 } { print }' x.dump >dup.dump
gf pack -q --set packing.file=dup.dump -o from_dup.xyz
expect_rc 3 "pack with a duplicate id"
expect_err "dup.dump:52" "pack with a duplicate id"
expect_err "42" "pack with a duplicate id"
ok "dump with a duplicate id: exit 3 with dup.dump:52 and the id"

# --- missing packing file -----------------------------------------------------
gf run -q "${TINY[@]}" --set packing.file=no_such_packing.dump -o run_missing
[ "$RC" -ne 0 ] || fail "run with a missing packing.file succeeded"
expect_err "no_such_packing.dump" "run with a missing packing.file"
no_run_output run_missing "run with a missing packing.file"
ok "run with a missing packing file: exit $RC naming it"

gf pack -q --set packing.file=no_such_packing.dump -o from_missing.xyz
[ "$RC" -ne 0 ] || fail "pack with a missing packing.file succeeded"
expect_err "no_such_packing.dump" "pack with a missing packing.file"
ok "pack with a missing packing file: exit $RC naming it"

# --- particles outside the container ---------------------------------------
# Particle 42 moved beyond the wall at x = +6 of the 12-wide container.
awk '/^ITEM: ATOMS/ { a = 1; print; next } a && $1 == 42 { $3 = 9.5 } { print }' x.dump >outside.dump
gf run -q "${TINY[@]}" --set packing.file=outside.dump -o run_outside
expect_rc 2 "run with particle 42 at x = 9.5 (wall at 6)"
expect_err "id 42" "run with particle 42 at x = 9.5"
line42=$(awk '/^ITEM: ATOMS/ { a = 1; next } a && $1 == 42 { print NR; exit }' outside.dump)
expect_err "outside.dump:$line42: particle id 42 at (9.5," "run with particle 42 at x = 9.5"
expect_err "(packing.file, --set)" "run with particle 42 at x = 9.5"
no_run_output run_outside "run with particle 42 at x = 9.5"
# The same in a CSV without an id column (id i is row i) set in a config file.
awk '/^ITEM: ATOMS/ { a = 1; print "x,y,z"; next } a { print $3 "," $4 "," $5 }' outside.dump >outside.csv
printf '[packing]\nfile = outside.csv\n' >outside.ini
gf pack -q outside.ini "${TINY[@]}" -o never.dump
expect_rc 2 "pack outside.ini (packing.file = outside.csv, row 42 at x = 9.5)"
expect_err "outside.csv:43: particle id 42 at (9.5," "pack outside.ini (outside.csv)"
expect_err "(packing.file, outside.ini:2)" "pack outside.ini (outside.csv)"
[ ! -e never.dump ] || fail "pack outside.ini: wrote never.dump despite the error"
ok "particle beyond the wall: exit 2 naming the packing file, the particle's line and id 42"

# packing.types needs a dump's type column: the error says where it was set.
printf '[packing]\nfile = outside.csv\n\ntypes = 1\n' >types_csv.ini
gf pack -q types_csv.ini "${TINY[@]}" -o never.dump
expect_rc 2 "pack types_csv.ini (packing.types with a CSV)"
expect_err "types_csv.ini:4: packing.types = 1 needs a LAMMPS dump with a type column, not outside.csv" \
    "pack types_csv.ini (packing.types with a CSV)"
ok "packing.types with a CSV: exit 2 naming the file and line that set it"

# A particle with |x| > 4.5 is not over the orifice (diameter 8); put it below the base.
low=$(awk '/^ITEM: ATOMS/ { a = 1; next } a && ($3 > 4.5 || $3 < -4.5) { print $1; exit }' x.dump)
[ -n "$low" ] || fail "x.dump: no particle with |x| > 4.5 to move below the base"
awk -v id="$low" '/^ITEM: ATOMS/ { a = 1; print; next } a && $1 == id { $5 = -3 } { print }' x.dump >below.dump
# A DEM packing holds particles below the base (falling through the orifice,
# or a floor): they count as already exited, are dropped, and the run says so
# (docs/dem.md).
gf run "${TINY[@]}" --set packing.file=below.dump -o run_below
expect_rc 0 "run with particle $low below the base (z = -3, not over the orifice)"
expect_err "1 below the base counted as exited" "run with particle $low below the base"
ok "particle below the base: dropped, counted as exited, said so"

# tests/data/id_type_xyz.dump has id 12 at x = 24.5: fine for the default width 50, not for 12.
gf run -q "${TINY[@]}" --set "packing.file=$DATA/id_type_xyz.dump" -o run_data
expect_rc 2 "run with id_type_xyz.dump in a 12-wide container"
expect_err "id 12" "run with id_type_xyz.dump in a 12-wide container"
ok "data file with id 12 outside a 12-wide container: exit 2 naming id 12"

# --- a failed --force run must not damage the run already in the directory ---
gf run -q "${TINY[@]}" --set output.snapshot_interval=0.1 -o run_old
expect_rc 0 "run into run_old"
ls run_old/snapshots >old_snapshots.txt
[ -s old_snapshots.txt ] || fail "run into run_old wrote no snapshots"
gf run -q "${TINY[@]}" --set packing.file=trunc.dump --force -o run_old
expect_rc 3 "run --force over run_old with a truncated packing.file"
ls run_old/snapshots >old_snapshots_after.txt
cmp -s old_snapshots.txt old_snapshots_after.txt ||
    fail "run --force with a bad packing.file failed (exit 3) but deleted the existing run's" \
        "snapshots (before: $(tr '\n' ' ' <old_snapshots.txt| sed 's/ $//'); after: $(tr '\n' ' ' <old_snapshots_after.txt)) and" \
        "left its checkpoint.bin and summary.json without them"
ok "a failed --force run leaves the existing run intact"

echo "cli $NAME: $PASS passed, 0 failed"
exit 0
