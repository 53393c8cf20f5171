#!/usr/bin/env bash
# Same physics, shown: runs one config with the event engine and with the
# domain engine over several seeds, measures each run the papers' way
# (granflow analyze), and prints flow rate, Var(z) slope, b_p, bulk packing
# fraction and mean residence time as mean +- sd over the seeds per engine,
# with the difference in units of its standard deviation
# (sqrt(sd_a^2 + sd_b^2)): |z| < 2 is the target (docs/performance.md).
#
#   scripts/compare-engines.sh GRANFLOW OUTDIR SEEDS TAU [CONFIG] [-- EXTRA --set ...]
# e.g. scripts/compare-engines.sh build/granflow runs/cmp 3 40
#      scripts/compare-engines.sh build/granflow runs/cmp-hopper 3 40 examples/hopper-60.ini
# Extra arguments after -- go to both engines' runs (e.g. --set packing.particles=20000);
# DOMAINS_SET adds --set arguments to the domain engine's runs only
# (e.g. DOMAINS_SET="--set parallel.window=0.05").
set -euo pipefail
gf=$1 out=$2 seeds=$3 tau=$4
shift 4
config=()
if [ $# -gt 0 ] && [ "$1" != "--" ]; then config=("$1"); shift; fi
[ $# -gt 0 ] && [ "$1" = "--" ] && shift
extra=("$@")
read -r -a dset <<<"${DOMAINS_SET:-}"
mkdir -p "$out"
for engine in event domains; do
  for s in $(seq 1 "$seeds"); do
    d="$out/$engine-$s"
    [ -f "$d/analysis/summary.json" ] && continue
    if [ "$engine" = event ]; then eng=(--set run.mode=event); else eng=(--set run.mode=fixed --set run.order=domains "${dset[@]}"); fi
    "$gf" run "${config[@]}" --force --quiet "${eng[@]}" --set run.seed="$s" --set run.duration="$tau" \
      --set run.checkpoint_interval=0 "${extra[@]}" -o "$d" >/dev/null
    "$gf" analyze "$d" >/dev/null
  done
done
python3 - "$out" "$seeds" <<'PY'
import json, math, sys
out, n = sys.argv[1], int(sys.argv[2])
keys = [("flow_rate", "flow rate (1/tau)"), ("velocity_variance_slope", "Var(z) slope (d)"),
        ("diffusion_length", "b_p (d)"), ("bulk_packing_fraction", "bulk packing fraction"),
        ("rtd_mean", "mean residence time (tau)")]
def stats(engine, key):
    v = [json.load(open(f"{out}/{engine}-{s}/analysis/summary.json")).get(key) for s in range(1, n + 1)]
    v = [x for x in v if isinstance(x, (int, float))]
    m = sum(v) / len(v)
    sd = math.sqrt(sum((x - m) ** 2 for x in v) / (len(v) - 1)) if len(v) > 1 else float("nan")
    return m, sd, len(v)
print(f"| quantity | event engine ({n} seeds) | domain engine ({n} seeds) | difference / sd |")
print("|---|---|---|---|")
for k, name in keys:
    a, b = stats("event", k), stats("domains", k)
    sd = math.sqrt(a[1] ** 2 + b[1] ** 2)
    z = (b[0] - a[0]) / sd if sd > 0 else float("nan")
    print(f"| {name} | {a[0]:.4g} +- {a[1]:.2g} | {b[0]:.4g} +- {b[1]:.2g} | {z:+.2f} |")
PY
