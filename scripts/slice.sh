#!/usr/bin/env bash
# Draws the central slice (y > 0) of granflow snapshots as discs coloured by
# initial layer (as in the 2009 paper's Fig. 3), side by side, with gnuplot.
#   scripts/slice.sh OUT.png SNAPSHOT.dump [SNAPSHOT.dump ...]
# (A stop-gap until `granflow render` draws them with cairo.)
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 OUT.png SNAPSHOT.dump..." >&2; exit 2; }
out=$1; shift
command -v gnuplot >/dev/null || { echo "$0: gnuplot is not installed (scripts/deps.sh installs it)" >&2; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
n=0; plots=""
xmax=0; zmax=0
for snap in "$@"; do
  [ -r "$snap" ] || { echo "$0: cannot read $snap" >&2; exit 1; }
  t=$(awk 'NR==2 {print $1; exit}' "$snap")
  # Columns of `ITEM: ATOMS id type x y z`; keep y > 0, colour by layer parity.
  awk -v f="$tmp/$n.dat" '
    /^ITEM: BOX BOUNDS/ {getline; xlo=$1; xhi=$2; getline; getline; zhi=$2; print xhi, zhi > f".box"; next}
    /^ITEM: ATOMS/ {atoms=1; next}
    atoms && $4 > 0 {print $3, $5, ($2 % 2)}' "$snap" > "$tmp/$n.dat"
  read -r bx bz < "$tmp/$n.dat.box"
  xmax=$(awk -v a="$xmax" -v b="$bx" 'BEGIN {print (b > a ? b : a)}')
  zmax=$(awk -v a="$zmax" -v b="$bz" 'BEGIN {print (b > a ? b : a)}')
  echo "$t" > "$tmp/$n.t"
  n=$((n + 1))
done
{
  # About 8 pixels per particle diameter.
  echo "set terminal pngcairo size $(awk -v x="$xmax" -v n="$n" 'BEGIN {printf "%d", n * (16 * x + 90)}'),$(awk -v z="$zmax" 'BEGIN {printf "%d", 8 * z + 110}') font 'sans,11'"
  echo "set output '$out'"
  echo "set multiplot layout 1,$n"
  echo "unset key; set size ratio -1; set xrange [-$xmax:$xmax]; set yrange [0:$zmax]"
  echo "set xlabel 'x / d'; set ylabel 'z / d'"
  echo "set palette maxcolors 2; set palette defined (0 '#d95f02', 1 '#1b6fb5'); unset colorbox"
  echo "set style fill solid 1.0 noborder"
  for ((k = 0; k < n; k++)); do
    echo "set title sprintf('t = %g {/Symbol t}', $(cat "$tmp/$k.t"))"
    echo "plot '$tmp/$k.dat' using 1:2:(0.5):3 with circles lc palette"
  done
  echo "unset multiplot"
} > "$tmp/plot.gp"
gnuplot "$tmp/plot.gp"
echo "wrote $out"
