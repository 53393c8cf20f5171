#!/bin/sh
# Issue 28 item 4: the cone series' wall / axis speed at mid-cone against
# the cone's angle, DEM and the three walks (docs/images/massflow-series.png).
#   scripts/exp28/plot-series.sh SERIES.csv OUT.png
set -eu
csv=$1 out=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Mid-cone rows (the second of each run's three heights), averaged over seeds.
awk -F, -v dir="$tmp" 'NR > 1 && $1 !~ /^#/ { k = $1 "," $2 "," $3; n[k]++; if (n[k] == 2) { s[$1 "," $2] += $7; c[$1 "," $2]++ } }
    END { for (k in s) { split(k, a, ","); print a[1], s[k] / c[k] > (dir "/" a[2] ".dat") } }' "$csv"
for f in "$tmp"/*.dat; do sort -n "$f" -o "$f"; done
gnuplot <<GP
set terminal pngcairo size 800,520 font "sans,11"
set output "$out"
set xlabel "cone angle to the horizontal (degrees)"
set ylabel "wall band / axis speed at mid-cone"
set key left top
set grid
set yrange [-0.05:0.8]
set arrow from 35,0.3 to 75,0.3 nohead dt 2 lc rgb "gray"
set label "funnel / mass (0.3)" at 66,0.27 tc rgb "gray"
plot "$tmp/dem.dat" w lp lw 2 pt 7 t "DEM (LAMMPS)", \
     "$tmp/diffusive.dat" w lp pt 5 t "diffusive (papers' walk)", \
     "$tmp/sfr.dat" w lp pt 9 t "sfr, slip rise", \
     "$tmp/sfr-steady.dat" w lp pt 11 t "sfr, steady rise"
GP
