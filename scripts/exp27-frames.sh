#!/bin/sh
# Issue 27 experiment 3 (docs/dem.md): does the frame interval change what
# calibration measures? For each DEM drain NAME of scripts/dem-validation.sh,
# links every K-th snapshot (K = 1, 2, 4: frames every 0.5, 1, 2 tau) into
# OUT/NAME-kK, then `calibrate --no-refine` (OUT/NAME-kK.cal.txt) and
# `analyze velocity` (OUT/NAME-kK-an/velocity_variance.csv).
# Usage: scripts/exp27-frames.sh [GRANFLOW] [DEMDIR] [OUT]
set -eu
GF=$(realpath "${1:-build/granflow}")
DEM=$(realpath "${2:-runs/dem-validation}")
OUT=${3:-runs/frames27}
mkdir -p "$OUT"
for name in slit narrow-deep; do
    for k in 1 2 4; do
        d=$OUT/$name-k$k
        rm -rf "$d"
        mkdir -p "$d/snapshots"
        cp "$DEM/$name/config.ini" "$d/"
        i=0
        for f in $(ls "$DEM/$name/snapshots/"*.dump | sort); do
            [ $((i % k)) = 0 ] && ln -s "$f" "$d/snapshots/"
            i=$((i + 1))
        done
        nice "$GF" calibrate "$d" --no-refine -o "$d-params.ini" > "$d.cal.txt"
        nice "$GF" analyze velocity "$d" -o "$d-an" --no-plots -q > /dev/null
    done
done
