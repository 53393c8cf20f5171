#!/usr/bin/env bash
# CLI test (issue 24 item 5): a container from STL drains as the analytic
# shape it copies. The box and the 60 degree hopper of scripts/make-stl.py
# against container.shape = box and cylinder, 3 seeds each: the mean number
# of particles out in 5 tau (past the first tau) of the mesh within 2 pooled
# standard deviations of the analytic one's. Prints the table of
# docs/geometry.md ("Shown equal").
# ctest: nosan
# usage: bash tests/cli/stl_drain_equal.sh GRANFLOW_BINARY TESTS_DATA_DIR
NAME=stl_drain_equal
source "$(dirname "$0")/lib.bash" "$@"
SRC=$DATA/../..

python3 "$SRC/scripts/make-stl.py" box box.stl --width 12 --depth 8 --height 40 --orifice 5 >/dev/null 2>&1 ||
    fail "make-stl.py box failed"
python3 "$SRC/scripts/make-stl.py" hopper hopper.stl --radius 7 --angle 60 --outlet 5 --pipe 2 --height 40 --binary \
    >/dev/null 2>&1 || fail "make-stl.py hopper failed"
printf '[container]\nwidth = 12\ndepth = 8\norifice_diameter = 5\n' > box.ini
printf '[container]\nshape = mesh\nmesh = box.stl\norifice_diameter = 5\n' > mbox.ini
printf '[container]\nshape = cylinder\nradius = 7\nhopper_angle = 60\noutlet_diameter = 5\noutlet_length = 2\n' > hop.ini
printf '[container]\nshape = mesh\nmesh = hopper.stl\norifice_diameter = 5\nexit_z = -2\n' > mhop.ini

COMMON=(--set packing.fill_height=14 --set run.duration=6 --set run.threads=1 --set output.snapshot_interval=6)
# out DIR: particles out after the first tau.
out() { awk -F, 'NR > 1 && $2 > 1 { n++ } END { print n + 0 }' "$1/exits.csv"; }

for pair in "box mbox" "hop mhop"; do
    set -- $pair
    for seed in 1 2 3; do
        "$GF" run -q "$1.ini" "${COMMON[@]}" --set run.seed=$seed -o "$1-$seed" 2>"$1-$seed.err" &
        p=$!
        "$GF" run -q "$2.ini" "${COMMON[@]}" --set run.seed=$seed -o "$2-$seed" 2>"$2-$seed.err" ||
            { cat "$2-$seed.err"; fail "run $2.ini seed $seed"; }
        wait $p || { cat "$1-$seed.err"; fail "run $1.ini seed $seed"; }
    done
    read -r ma sa mm sm pooled <<<"$(for seed in 1 2 3; do echo "$(out "$1-$seed") $(out "$2-$seed")"; done |
        awk '{ a[NR] = $1; m[NR] = $2; A += $1; M += $2 }
             END { A /= NR; M /= NR; for (i = 1; i <= NR; i++) { va += (a[i] - A)^2; vm += (m[i] - M)^2 }
                   va /= NR - 1; vm /= NR - 1; printf "%.1f %.1f %.1f %.1f %.2f\n", A, sqrt(va), M, sqrt(vm), sqrt((va + vm) / 2) }')"
    echo "$1: analytic $(for s in 1 2 3; do printf '%s ' "$(out "$1-$s")"; done)mean $ma sd $sa;" \
         "mesh $(for s in 1 2 3; do printf '%s ' "$(out "$2-$s")"; done)mean $mm sd $sm; pooled sd $pooled"
    awk -v a="$ma" -v m="$mm" -v s="$pooled" 'BEGIN { d = a - m; if (d < 0) d = -d; exit !(d <= 2 * s) }' ||
        fail "$2: mean $mm out vs $ma for the analytic shape: more than 2 pooled sd ($pooled) apart"
    ok "$2 drains as $1 (3 seeds)"
done
echo "cli $NAME: $PASS passed"
