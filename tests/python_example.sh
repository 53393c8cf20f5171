#!/usr/bin/env bash
# Runs examples/python/outflow.py on a short drain and checks what it wrote:
# every row of outflow.csv accounts for all particles (exited + remaining),
# the count never falls, some drained, and outflow.png is a PNG.
# Usage: python_example.sh PYTHON SOURCE_DIR OUT_DIR
set -euo pipefail
py=$1 src=$2 out=$3
rm -rf "$out"
PYTHONPATH=$src/python "$py" "$src/examples/python/outflow.py" -o "$out" --until 3 --particles 1500
awk -F, 'NR == 1 { next }
         $2 + $3 != 1500 { print "row " NR ": " $2 " + " $3 " != 1500"; bad = 1 }
         $2 < last { print "row " NR ": exits fell"; bad = 1 }
         { last = $2 }
         END { if (last == 0) { print "nothing drained"; bad = 1 } exit bad }' "$out/outflow.csv"
grep -q 'P   N   G' <<< "$(head -c 8 "$out/outflow.png" | od -An -c)" || { echo "outflow.png is not a PNG"; exit 1; }
