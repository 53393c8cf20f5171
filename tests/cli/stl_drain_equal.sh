#!/usr/bin/env bash
# CLI test (issue 24 item 5): a container from STL drains as the analytic
# shape it copies. The box and the 60 degree hopper of scripts/make-stl.py
# against container.shape = box and cylinder, 3 seeds each: the mean number
# of particles out in 5 tau (past the first tau) of the mesh within 2 pooled
# standard deviations of the analytic one's, and so the variance Var(z) of
# the velocity profile (v_z(x) in the box, v_z(r) in the hopper: the mesh is
# found to be a solid of revolution) at each of three heights, over the
# window 1..6 tau. Prints the tables of docs/geometry.md ("Drains equal").
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

COMMON=(--set packing.fill_height=14 --set run.duration=6 --set run.threads=1 --set output.snapshot_interval=0.5)
# out DIR: particles out after the first tau.
out() { awk -F, 'NR > 1 && $2 > 1 { n++ } END { print n + 0 }' "$1/exits.csv"; }
HEIGHTS=4,6,8
# var DIR Z: the profile's variance at height Z (d^2) over 1..6 tau.
var() { awk -F, -v z="$2" 'NR > 1 && $1 == z { print $2 }' "$1/analysis/velocity_variance.csv"; }
# within NAME A1 A2 A3 M1 M2 M3: the means of the analytic (A) and mesh (M)
# values within 2 pooled standard deviations; prints the table's row.
within() {
    local name=$1
    shift
    read -r ma sa mm sm pooled <<<"$(echo "$@" | awk '{ for (i = 1; i <= 3; i++) { A += $i; M += $(i + 3) } A /= 3; M /= 3
        for (i = 1; i <= 3; i++) { va += ($i - A)^2; vm += ($(i + 3) - M)^2 } va /= 2; vm /= 2
        printf "%.3g %.2g %.3g %.2g %.3g\n", A, sqrt(va), M, sqrt(vm), sqrt((va + vm) / 2) }')"
    local v=($(printf '%.3g ' "$@"))
    echo "| $name | ${v[0]} ${v[1]} ${v[2]} | $ma +- $sa | ${v[3]} ${v[4]} ${v[5]} | $mm +- $sm | $pooled |"
    awk -v a="$ma" -v m="$mm" -v s="$pooled" 'BEGIN { d = a - m; if (d < 0) d = -d; exit !(d <= 2 * s) }'
}

for pair in "box mbox" "hop mhop"; do
    set -- $pair
    for seed in 1 2 3; do
        "$GF" run -q "$1.ini" "${COMMON[@]}" --set run.seed=$seed -o "$1-$seed" 2>"$1-$seed.err" &
        p=$!
        "$GF" run -q "$2.ini" "${COMMON[@]}" --set run.seed=$seed -o "$2-$seed" 2>"$2-$seed.err" ||
            { cat "$2-$seed.err"; fail "run $2.ini seed $seed"; }
        wait $p || { cat "$1-$seed.err"; fail "run $1.ini seed $seed"; }
    done
    within "$1: particles out" $(for c in "$1" "$2"; do for s in 1 2 3; do out "$c-$s"; done; done) ||
        fail "$2: particles out more than 2 pooled sd from $1's"
    ok "$2 drains as $1 (3 seeds)"
    for c in "$1" "$2"; do
        for s in 1 2 3; do
            "$GF" analyze velocity "$c-$s" -q --no-plots --set velocity.heights=$HEIGHTS --set velocity.window=run \
                --set window.t0=1 --set window.t1=6 2>"$c-$s.aerr" || { cat "$c-$s.aerr"; fail "analyze $c-$s"; }
        done
    done
    if [ "$2" = mhop ]; then # a cylinder's profiles are v_z(r); the mesh of one is found to be a solid of revolution
        for c in hop mhop; do grep -q '^z_d,r_d,' "$c-1/analysis/velocity_profiles.csv" || fail "$c: profiles not radial"; done
    else
        grep -q '^z_d,x_d,' "mbox-1/analysis/velocity_profiles.csv" || fail "mbox: the box mesh's profiles are not v_z(x)"
    fi
    for z in ${HEIGHTS//,/ }; do
        within "$1: Var at z = $z" $(for c in "$1" "$2"; do for s in 1 2 3; do var "$c-$s" "$z"; done; done) ||
            fail "$2: Var(z = $z) more than 2 pooled sd from $1's"
    done
    ok "$2's profiles as wide as $1's at z = $HEIGHTS (3 seeds)"
done
echo "cli $NAME: $PASS passed"
