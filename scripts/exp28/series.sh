#!/bin/sh
# Issue 28 item 4: the mass/funnel series (docs/stress.md, "Mass flow or
# funnel flow"): cones at 45, 55, 65 and 75 degrees to the horizontal, in
# DEM (scripts/exp28/dem-all.sh made them) and with each flow rule over
# three seeds; prints angle, what, seed, z, axis and wall-band speeds and
# their ratio (scripts/exp28/massflow.py, frames 2-12 tau).
#   scripts/exp28/series.sh [OUT]     (default runs/h28)
set -u
here=$(cd "$(dirname "$0")" && pwd)
out=${1:-runs/h28}
echo "angle,what,seed,z_d,axis_speed,wall_speed,wall_over_axis"
for a in 35 45 55 65 75; do
    if [ -d "$out/cone$a-dem/snapshots" ]; then
        python3 "$here/massflow.py" "$out/cone$a-dem" 2 12 | tail -n +3 | sed "s/^/$a,dem,1,/"
    fi
    for v in diffusive sfr sfr-steady; do
        for seed in 1 2 3; do
            rule=${v%-steady}
            extra=""; [ "$v" = sfr ] && extra="--set spot.sfr_rise=slip"; [ "$v" = sfr-steady ] && extra="--set spot.sfr_rise=steady"
            EXTRA="$extra" "$here/cone.sh" "$a" "$rule" "$out/cone$a-$v-$seed" "$seed" >/dev/null 2>&1 || echo "# $a $v $seed failed"
            python3 "$here/massflow.py" "$out/cone$a-$v-$seed" 2 12 | tail -n +3 | sed "s/^/$a,$v,$seed,/"
        done
    done
done
