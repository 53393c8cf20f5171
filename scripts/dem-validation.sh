#!/bin/sh
# Regenerates the DEM validation of docs/dem.md ("Validation on silos that are
# not the papers'"): three LAMMPS drains of other containers
# (examples/dem-validation/*.ini), then for each: calibrate (with the
# closed-loop refinement), the spot run of the calibrated parameters, and
# compare. Usage: scripts/dem-validation.sh [GRANFLOW] [OUTDIR]
# (defaults build/granflow, runs/dem-validation; runs/ is not in git).
# CPU-heavy: one LAMMPS at a time, one MPI rank, under nice (7-40 minutes each
# on a shared 2-core machine); a finished drain (snapshots/.done) is kept.
set -eu
GF=${1:-build/granflow}
OUT=${2:-runs/dem-validation}
mkdir -p "$OUT"
for name in narrow-deep slit wide-deep; do
    dir=$OUT/$name
    if [ ! -f "$dir/snapshots/.done" ]; then
        nice "$GF" dem "examples/dem-validation/$name.ini" -o "$dir" --run --force -q
        touch "$dir/snapshots/.done"
    fi
done
for name in narrow-deep slit wide-deep; do
    dir=$OUT/$name
    nice "$GF" calibrate "$dir" -o "$OUT/$name-params.ini" > "$OUT/$name.calibrate.txt"
    nice "$GF" run -q "$OUT/$name-params.ini" -o "$OUT/$name-spot" --force
    nice "$GF" compare "$dir" "$OUT/$name-spot" --no-plots > "$OUT/$name.compare.txt"
    cat "$OUT/$name.compare.txt"
done
