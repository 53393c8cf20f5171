#!/bin/sh
# Issue 28 items 3-4: the DEM references of docs/stress.md, one after the
# other (one LAMMPS rank each), into OUT (default runs/h28).
#   scripts/exp28/dem-all.sh [OUT]
set -u
here=$(cd "$(dirname "$0")/../.." && pwd)
gf=${GRANFLOW:-$here/build/granflow}
out=${1:-runs/h28}
mkdir -p "$out"
run() { name=$1; shift; [ -f "$out/$name/snapshots/.done" ] && return 0
        echo "== $name $(date -u +%H:%M:%S)"; "$@" > "$out/$name.log" 2>&1 \
        && touch "$out/$name/snapshots/.done"; echo "== $name rc=$? $(date -u +%H:%M:%S)"; }
# Item 3: the cones at 60 and 30 degrees (80 tau, recirculating), the wedge.
for c in hopper-60:dem60 hopper-30:dem30 wedge-60:demw; do
    run "${c#*:}" "$gf" dem "$here/examples/dem-validation/${c%%:*}.ini" --set run.recirculate=on \
        --set run.duration=80 --set output.snapshot_interval=0.5 --set dem.mpi_ranks=1 \
        -o "$out/${c#*:}" --run
done
# Item 4: the mass/funnel series.
for a in 35 45 55 65 75; do
    GRANFLOW=$gf run "cone$a-dem" "$here/scripts/exp28/cone.sh" "$a" dem "$out/cone$a-dem"
done
