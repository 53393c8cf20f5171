#!/usr/bin/env bash
# Same physics, shown: runs one config with the event engine and with the
# domain engine over several seeds, measures each run the papers' way
# (granflow analyze), and prints flow rate, Var(z) slope, b_p, bulk packing
# fraction and mean residence time as mean +- sd over the seeds per engine,
# with the difference in units of its standard deviation
# (sqrt(sd_a^2 + sd_b^2), the spread of one run's difference): |z| < 2 is the
# target (docs/performance.md); and, stricter, in units of the standard
# error of the difference of the means (sqrt(sd_a^2/n_a + sd_b^2/n_b)).
#
#   scripts/compare-engines.sh GRANFLOW OUTDIR SEEDS TAU [CONFIG] [-- EXTRA --set ...]
# e.g. scripts/compare-engines.sh build/granflow runs/cmp 3 40
#      scripts/compare-engines.sh build/granflow runs/cmp-hopper 3 40 examples/hopper-60.ini
# Extra arguments after -- go to both engines' runs (e.g. --set packing.particles=20000);
# DOMAINS_SET adds --set arguments to the domain engine's runs only
# (e.g. DOMAINS_SET="--set parallel.window=0.05").
# ANALYZE_SET adds arguments to `granflow analyze` (its regions and heights
# are the papers' silo's; a smaller container needs its own, e.g.
# ANALYZE_SET="--set velocity.heights=10,14,18 --set diffusion.z0=18").
# REANALYZE=1 measures existing runs again (after changing ANALYZE_SET).
# ENGINES="event" or "domains" runs one side only (two invocations with
# different ENGINES share the machine's cores and the same OUTDIR); the
# table is printed once both sides have every seed.
# In a recirculating run (passes_max > 1) two more rows: the mean transit
# time of every exit (surface to outlet, or start to outlet on the first
# pass) and of the passes after the first (re-inserted pebbles only), the
# residence time of the steady recirculating core. The last row, exits per
# spot move over the whole run, is the sharpest test of the flow (free of
# the insertions' Poisson noise).
set -euo pipefail
gf=$1 out=$2 seeds=$3 tau=$4
shift 4
config=()
if [ $# -gt 0 ] && [ "$1" != "--" ]; then config=("$1"); shift; fi
[ $# -gt 0 ] && [ "$1" = "--" ] && shift
extra=("$@")
read -r -a dset <<<"${DOMAINS_SET:-}"
read -r -a aset <<<"${ANALYZE_SET:-}"
read -r -a engines <<<"${ENGINES:-event domains}"
mkdir -p "$out"
for engine in "${engines[@]}"; do
  for s in $(seq 1 "$seeds"); do
    d="$out/$engine-$s"
    if [ -f "$d/analysis/summary.json" ]; then
      [ "${REANALYZE:-0}" = 1 ] && "$gf" analyze "$d" "${aset[@]}" >/dev/null
      continue
    fi
    case $engine in
      event) eng=(--set run.mode=event) ;;
      domains) eng=(--set run.mode=fixed --set run.order=domains "${dset[@]}") ;;
      *) echo "compare-engines.sh: unknown engine '$engine' in ENGINES (event, domains)" >&2; exit 2 ;;
    esac
    "$gf" run "${config[@]}" --force --quiet "${eng[@]}" --set run.seed="$s" --set run.duration="$tau" \
      --set run.checkpoint_interval=0 "${extra[@]}" -o "$d" >/dev/null
    "$gf" analyze "$d" "${aset[@]}" >/dev/null
  done
done
for engine in event domains; do
  for s in $(seq 1 "$seeds"); do
    [ -f "$out/$engine-$s/analysis/summary.json" ] || { echo "compare-engines.sh: $out/$engine-$s not measured yet: no table" >&2; exit 0; }
  done
done
python3 - "$out" "$seeds" <<'PY'
import csv, json, math, sys
out, n = sys.argv[1], int(sys.argv[2])
keys = [("flow_rate", "flow rate (1/tau)"), ("velocity_variance_slope", "Var(z) slope (d)"),
        ("diffusion_length", "b_p (d)"), ("bulk_packing_fraction", "bulk packing fraction"),
        ("rtd_mean", "mean residence time (tau)")]
def summary(engine, s):
    return json.load(open(f"{out}/{engine}-{s}/analysis/summary.json"))
def later_passes(engine, s):
    # Mean transit of the passes after the first, from rtd_pass.csv (count-weighted).
    tot = num = 0.0
    with open(f"{out}/{engine}-{s}/analysis/rtd_pass.csv") as f:
        for row in csv.DictReader(f):
            if int(row["pass"]) > 1 and int(row["count"]) > 0:
                tot += float(row["mean_tau"]) * int(row["count"])
                num += int(row["count"])
    return tot / num if num else None
def per_move(engine, s):
    # Particles out per spot move over the whole run (x 1e4), from the run's
    # own summary.json: the drainage per move, free of the insertions' noise.
    r = json.load(open(f"{out}/{engine}-{s}/summary.json"))
    return 1e4 * r["particles_exited"] / r["spot_moves"] if r.get("spot_moves") else None
def value(engine, key, s):
    if key == "later_passes": return later_passes(engine, s)
    if key == "per_move": return per_move(engine, s)
    return summary(engine, s).get(key)
def values(engine, key):
    v = [value(engine, key, s) for s in range(1, n + 1)]
    return [x for x in v if isinstance(x, (int, float)) and math.isfinite(x)]
def stats(v):
    if not v: return float("nan"), float("nan"), 0
    m = sum(v) / len(v)
    sd = math.sqrt(sum((x - m) ** 2 for x in v) / (len(v) - 1)) if len(v) > 1 else float("nan")
    return m, sd, len(v)
if any((summary(e, s).get("passes_max") or 0) > 1 for e in ("event", "domains") for s in range(1, n + 1)):
    keys += [("transit_mean", "mean transit time, every exit (tau)"),
             ("later_passes", "mean transit time, passes after the first (tau)")]
keys += [("per_move", "exits per spot move, whole run (1e-4)")]
print(f"| quantity | event engine ({n} seeds) | domain engine ({n} seeds) | difference / sd | difference / se |")
print("|---|---|---|---|---|")
for k, name in keys:
    a, b = stats(values("event", k)), stats(values("domains", k))
    sd = math.sqrt(a[1] ** 2 + b[1] ** 2)
    se = math.sqrt(a[1] ** 2 / a[2] + b[1] ** 2 / b[2]) if a[2] and b[2] else float("nan")
    z = (b[0] - a[0]) / sd if sd > 0 else float("nan")
    zse = (b[0] - a[0]) / se if se > 0 else float("nan")
    nn = "" if a[2] == n and b[2] == n else f" (measured in {a[2]} and {b[2]} runs)"
    print(f"| {name}{nn} | {a[0]:.4g} +- {a[1]:.2g} | {b[0]:.4g} +- {b[1]:.2g} | {z:+.2f} | {zse:+.2f} |")
PY
