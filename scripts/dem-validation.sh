#!/bin/sh
# Regenerates the DEM references of docs/dem.md ("Validation on other silos"):
# three LAMMPS drains of non-paper containers, then calibrates the spot model
# on each and compares. Usage: scripts/dem-validation.sh [GRANFLOW] [OUTDIR]
# (defaults build/granflow, runs/dem-validation). CPU-heavy (tens of minutes on
# one core per run): runs one LAMMPS at a time under nice, 1 MPI rank.
set -eu
GF=${1:-build/granflow}
OUT=${2:-runs/dem-validation}
mkdir -p "$OUT"
for name in narrow-deep slit wide-deep; do
    cfg=examples/dem-validation/$name.ini
    dir=$OUT/$name
    if [ ! -f "$dir/snapshots/.done" ]; then
        nice "$GF" dem "$cfg" -o "$dir" --run --force
        touch "$dir/snapshots/.done"
    fi
done
for name in narrow-deep slit wide-deep; do
    dir=$OUT/$name
    nice "$GF" calibrate "$dir" -o "$OUT/$name-params.ini"
    nice "$GF" run "$OUT/$name-params.ini" -o "$OUT/$name-spot" --force
    nice "$GF" compare "$dir" "$OUT/$name-spot"
done
