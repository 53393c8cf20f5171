#!/bin/sh
# Issue 28 item 2: the papers' box with each flow rule, three seeds
# (docs/stress.md, "The box: sfr against the papers' walk").
#   scripts/exp28/box-rules.sh OUT [VARIANT...]   (diffusive sfr sfr-steady sfr-smooth sfr-steady-smooth)
# SEEDS="1 2 3" by default. (-smooth: frictionless walls, stress.wall_friction_angle = 0: Rankine's field)
set -u
gf=${GRANFLOW:-$(dirname "$0")/../../build/granflow}
out=$1; shift
[ $# -gt 0 ] || set -- diffusive sfr sfr-steady
mkdir -p "$out"
for v in "$@"; do
    case $v in
        diffusive) rule="--set spot.flow_rule=diffusive" ;;
        sfr) rule="--set spot.flow_rule=sfr --set spot.sfr_rise=slip" ;;
        sfr-steady) rule="--set spot.flow_rule=sfr --set spot.sfr_rise=steady" ;;
        sfr-smooth) rule="--set spot.flow_rule=sfr --set spot.sfr_rise=slip --set stress.wall_friction_angle=0" ;;
        sfr-steady-smooth) rule="--set spot.flow_rule=sfr --set spot.sfr_rise=steady --set stress.wall_friction_angle=0" ;;
    esac
    for seed in ${SEEDS:-1 2 3}; do
        d=$out/$v-$seed
        # shellcheck disable=SC2086
        "$gf" run --set packing.particles=25000 --set run.duration=30 --set output.snapshot_interval=1 \
            --set run.seed=$seed $rule -o "$d" -q --force &&
        "$gf" analyze outflow "$d" -q --no-plots &&
        "$gf" analyze velocity "$d" -q --no-plots --set velocity.heights=10,20,30,40 || echo "# $v $seed failed"
        python3 - "$d" "$v" "$seed" <<'PY'
import json, sys
s = json.load(open(sys.argv[1] + "/analysis/summary.json"))
keys = [k for k in s if "var" in k.lower() or "flow_rate" == k]
print(sys.argv[2], sys.argv[3], s.get("flow_rate"), [(k, s[k]) for k in sorted(keys) if k != "flow_rate"])
PY
    done
done
