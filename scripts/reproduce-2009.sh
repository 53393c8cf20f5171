#!/usr/bin/env bash
# Reproduces the variants of the 2009 paper (Rycroft, Wong & Bazant, "Fast
# spot-based multiscale simulations of granular drainage", Figs. 4-12) from
# the configurations in examples/, shorter than the paper, two runs at a time;
# measures them (granflow analyze), draws them (granflow render) and writes
# reproduce/REPORT.md with our numbers beside the paper's.
#
#   scripts/reproduce-2009.sh            (or: make reproduce)
#
# Environment:
#   GRANFLOW=path      the granflow binary (default build/granflow)
#   REPRO_SCALE=s      multiply every run length and time window by s (default
#                      1); below 0.25 the silo is also shrunk (REPRO_SMALL=1),
#                      so REPRO_SCALE=0.05 is a smoke test of a couple of minutes
#   REPRO_SMALL=0|1    force the small silo (20 d wide, 6,000 spheres) on or off
#   REPRO_JOBS=n       runs at a time (default 2)
#   REPRO_OUT=dir      output directory (default reproduce, or with a scale
#                      other than 1 reproduce/runs/scale-S, so that a smoke test
#                      leaves the committed report alone); runs in DIR/runs
#
# Idempotent and resumable: a run whose summary.json says "complete" and whose
# config.ini is the one planned is skipped; an interrupted one (Ctrl-C) is
# resumed from its checkpoint; anything else is run afresh. Analyses, pictures
# and the report are always redone (they take seconds). Progress goes to
# stderr, each run's own output to DIR/runs/NAME.log. Any error stops it.
set -euo pipefail

ROOT=${REPRO_ROOT:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}
GF=${GRANFLOW:-$ROOT/build/granflow}
SCALE=${REPRO_SCALE:-1}
# A scaled run reports into its own directory, so that a smoke test does not
# overwrite the committed reproduce/REPORT.md and pictures.
if [ "$SCALE" = 1 ]; then OUT=${REPRO_OUT:-$ROOT/reproduce}
else OUT=${REPRO_OUT:-$ROOT/reproduce/runs/scale-$SCALE}; fi
RUNS=$OUT/runs
JOBS=${REPRO_JOBS:-2}
EX=$ROOT/examples

say() { printf '[reproduce %s] %s\n' "$(date +%H:%M:%S)" "$*" >&2; }
die() { say "ERROR: $*"; exit 1; }
# s(X): X times the scale, printed without trailing zeros.
s() { awk -v x="$1" -v k="$SCALE" 'BEGIN { printf "%.6g", x * k }'; }

awk -v k="$SCALE" 'BEGIN { exit !(k > 0 && k <= 100) }' ||
  die "REPRO_SCALE=$SCALE: expected a number in (0, 100]"
if [ -z "${REPRO_SMALL:-}" ]; then
  REPRO_SMALL=$(awk -v k="$SCALE" 'BEGIN { print (k < 0.25) ? 1 : 0 }')
fi

# ---- the plan ---------------------------------------------------------------
# Run lengths (tau) at scale 1. The paper runs 200-300 tau; on 2 cores that
# would take many hours, so:
#  - MAIN: event/fixed (Fig. 4) and the boundary layers (Fig. 8) drain the
#    papers' silo for 34 tau: the spots (rising 0.1 d x 28 per tau) reach the
#    Fig. 8 region 50 < z < 70 by about 26 tau;
#  - RELAX: the relaxation variants (Figs. 9-12), 34 tau: the badness region
#    15 < z < 45 flows from about 17 tau;
#  - SURF: the free-surface variants (Figs. 5-7) in a silo filled only to
#    z = 40 d (about 18,000 spheres), 50 tau, so that the spots reach the free
#    surface after 15 tau instead of the 43 tau of the full silo.
T_MAIN=34 T_RELAX=34 T_SURF=50
# Time windows (tau, at scale 1) of each figure's averages.
W4="24 34"   # Fig. 4: flow rate, velocity profiles, packing fraction
W8="26 34"   # Fig. 8: v_z(y) in |x| < 10, 50 < z < 70 (paper 80-180)
W9="18 34"   # Fig. 9: badness in -15 < x < 15, 15 < z < 45 (paper 40-160)
W7="20 50"   # Fig. 7: mean surface angle (the angle is listed at every frame)
PIC4="20 34" # Fig. 4 pictures (paper: t = 20 tau and later)
PIC10=30     # Fig. 10 pictures (paper: t = 120 tau)
PIC5=50      # Figs. 5, 6 pictures (paper: t = 300 tau)
SURF_FILL=40

# Geometry: the papers' silo, or (smoke test) a small one 20 d wide, filled
# to about 30 d, with every analysis region scaled with it.
GEOM=() PACK_MAIN=() PACK_SURF=(--set packing.fill_height=$SURF_FILL) AN_GEOM=()
if [ "$REPRO_SMALL" = 1 ]; then
  GEOM=(--set container.width=20)
  PACK_MAIN=(--set packing.particles=6000)
  PACK_SURF=(--set packing.fill_height=10)
  AN_GEOM=(--set velocity.y_xhalf=4 --set velocity.y_z0=12.5 --set velocity.y_z1=17.5
           --set velocity.heights=2.5,5,7.5,10,12.5,15 --set gr.x0=-6 --set gr.x1=6
           --set gr.z0=3.75 --set gr.z1=11.25 --set density.z0=12.5 --set density.z1=17.5
           --set surface.dx=1)
fi
SNAP=$(awk -v k="$SCALE" 'BEGIN { printf "%.6g", 2 * (k < 1 ? k : 1) }')

# name | example | length | packing | what it stands for
PLAN="base|fig4-event|$T_MAIN|main|event-driven, full relaxation, d_w = 1 (Figs. 4, 8, 9)
fixed-random|fig4-fixed-random|$T_MAIN|main|fixed timestep, random order
fixed-newest|fig4-fixed-newest|$T_MAIN|main|fixed timestep, newest first
dw0.5|fig8-dw0.5|$T_MAIN|main|d_w = 0.5
dw0|fig8-dw0|$T_MAIN|main|d_w = 0
dw-1.5|fig8-dw-1.5|$T_MAIN|main|d_w = -1.5
reflect|fig8-reflect|$T_MAIN|main|reflection
none|fig9-none|$T_RELAX|main|no relaxation
random-k10|fig9-random-k10|$T_RELAX|main|method 1, k = 10
random-k100|fig9-random-k100|$T_RELAX|main|method 1, k = 100
random-k1000|fig9-random-k1000|$T_RELAX|main|method 1, k = 1000
counter-k10|fig9-counter-k10|$T_RELAX|main|method 2, k = 10
global-k1|fig9-global-k1|$T_RELAX|main|method 3, k = 1
global-k10|fig9-global-k10|$T_RELAX|main|method 3, k = 10
global-k100|fig9-global-k100|$T_RELAX|main|method 3, k = 100
surf-beta0|fig7-beta0|$T_SURF|surf|beta = 0
surf-beta1|fig7-beta1|$T_SURF|surf|beta = 1
surf-beta1w|fig7-beta1-weighting|$T_SURF|surf|beta = 1 + weighting
surf-beta3w|fig7-beta3-weighting|$T_SURF|surf|beta = 3 + weighting"
# fig8-dw1 and fig9-full are fig4-event (checked below): the run "base".

plan_field() { # NAME FIELD -> the field (1-based) of NAME's plan line
  printf '%s\n' "$PLAN" | awk -F'|' -v n="$1" -v f="$2" '$1 == n { print $f }'
}
run_sets() { # NAME -> the --set options of the run, one a line
  local name=$1 len pk
  len=$(plan_field "$name" 3); pk=$(plan_field "$name" 4)
  printf '%s\n' "${GEOM[@]}" --set "packing.file=$RUNS/pack-$pk.dump" \
    --set "run.duration=$(s "$len")" --set "output.snapshot_interval=$SNAP"
}
effective() { # INI SETS... -> the effective configuration without comments
  "$GF" config "$@" | grep -v '^[#;]' | grep -v '^$'
}

failed() { # NAME EXIT LOG
  if [ "$2" = 130 ]; then say "$1: interrupted, checkpoint written (rerun to resume it)"
  else say "$1: FAILED (exit $2), see $3"; fi
}
# ---- one run (called in parallel as: reproduce-2009.sh --one NAME) --------------
run_one() {
  local name=$1 ex dir log sets want t0 rc
  ex=$EX/$(plan_field "$name" 2).ini dir=$RUNS/$name log=$RUNS/$name.log
  mapfile -t sets < <(run_sets "$name")
  want=$(effective "$ex" "${sets[@]}")
  if [ -f "$dir/summary.json" ] && [ -f "$dir/config.ini" ] &&
     [ "$(grep -v '^[#;]' "$dir/config.ini" | grep -v '^$')" = "$want" ]; then
    if grep -q '"status": *"complete"' "$dir/summary.json"; then
      say "$name: complete, skipped"
      return 0
    fi
    if [ -f "$dir/checkpoint.bin" ]; then
      say "$name: resuming from its checkpoint (log $log)"
      t0=$SECONDS
      "$GF" run --resume "$dir" -q >>"$log" 2>&1 || { rc=$?; failed "$name" $rc "$log"; return 1; }
      say "$name: done in $((SECONDS - t0)) s"
      return 0
    fi
  fi
  say "$name: running $(plan_field "$name" 3) x $SCALE tau ($(plan_field "$name" 5)), log $log"
  t0=$SECONDS
  "$GF" run "$ex" "${sets[@]}" -o "$dir" --force -q >"$log" 2>&1 || { rc=$?; failed "$name" $rc "$log"; return 1; }
  say "$name: done in $((SECONDS - t0)) s"
}

if [ "${1:-}" = "--one" ]; then
  # exit 255 makes xargs stop starting new runs after a failure
  run_one "$2" || exit 255
  exit 0
fi

# ---- checks -----------------------------------------------------------------
[ -x "$GF" ] || die "no granflow binary at $GF (run make build, or set GRANFLOW)"
GF=$(cd "$(dirname "$GF")" && pwd)/$(basename "$GF")
command -v python3 >/dev/null || die "python3 is needed to write the report"
command -v gnuplot >/dev/null || die "gnuplot is needed for the plots (scripts/deps.sh installs it)"
mkdir -p "$RUNS"
for ex in "$EX"/fig*.ini; do
  "$GF" config "$ex" >/dev/null 2>"$RUNS/config-check.err" ||
    die "$ex does not load: $(cat "$RUNS/config-check.err")"
done
same() { # two examples that must give the same run
  [ "$(effective "$EX/$1.ini" --set run.duration=1)" = "$(effective "$EX/$2.ini" --set run.duration=1)" ] ||
    die "examples/$1.ini and examples/$2.ini should describe the same run"
}
same fig4-event fig8-dw1; same fig4-event fig9-full; same fig4-event fig7-beta0
say "scale $SCALE ($([ "$REPRO_SMALL" = 1 ] && echo 'small silo' || echo "the papers' silo")), $JOBS runs at a time, output in $OUT"
start=$SECONDS

# ---- packings: one per geometry, shared by every run of it ------------------
pack() { # KIND SETS...
  local kind=$1; shift
  local f=$RUNS/pack-$kind.dump want
  want=$(printf '%s ' "${GEOM[@]}" "$@")
  if [ -f "$f" ] && [ "$(cat "$f.sets" 2>/dev/null)" = "$want" ]; then return 0; fi
  say "building the $kind packing"
  "$GF" pack "${GEOM[@]}" "$@" -o "$f" >"$RUNS/pack-$kind.log" 2>&1 ||
    die "granflow pack failed, see $RUNS/pack-$kind.log"
  printf '%s' "$want" >"$f.sets"
}
pack main "${PACK_MAIN[@]}"
pack surf "${PACK_SURF[@]}"

# ---- the runs, $JOBS at a time, longest first -----------------------------------
names=$(printf '%s\n' "$PLAN" | awk -F'|' '{ print $3 "|" $1 }' | sort -t'|' -k1,1nr -s | cut -d'|' -f2)
say "$(printf '%s\n' "$names" | wc -l) runs; per-run lines below (runs already complete are skipped)"
export GRANFLOW="$GF" REPRO_OUT="$OUT" REPRO_SCALE="$SCALE" REPRO_SMALL
printf '%s\n' "$names" | xargs -P "$JOBS" -I{} "${BASH_SOURCE[0]}" --one {} ||
  die "a run failed (its log is named above); fix it and rerun: finished runs are kept"
say "all runs done ($((SECONDS - start)) s so far)"

# ---- analyses ---------------------------------------------------------------
analyze() { # NAME OUTSUB WINDOW MEASURE... 
  local name=$1 sub=$2 win=$3; shift 3
  local a b m
  read -r a b <<<"$win"
  for m in "$@"; do
    "$GF" analyze "$m" "$RUNS/$name" -o "$RUNS/$name/$sub" -q "${AN_GEOM[@]}" \
      --set "window.t0=$(s "$a")" --set "window.t1=$(s "$b")" >>"$RUNS/analyze.log" 2>&1 ||
      die "granflow analyze $m $RUNS/$name failed, see $RUNS/analyze.log"
  done
}
say "measuring"
: >"$RUNS/analyze.log"
for n in base fixed-random fixed-newest; do analyze "$n" an-fig4 "$W4" outflow velocity voronoi density; done
for n in base dw0.5 dw0 dw-1.5 reflect; do analyze "$n" an-fig8 "$W8" outflow velocity; done
for n in base none random-k10 random-k100 random-k1000 counter-k10 global-k1 global-k10 global-k100; do
  analyze "$n" an-fig9 "$W9" badness gr
done
for n in surf-beta0 surf-beta1 surf-beta1w surf-beta3w; do analyze "$n" an-fig7 "$W7" surface voronoi; done

# ---- pictures -----------------------------------------------------------------
render() { # NAME COLOUR TIME OUTFILE [PX per d: 4 for the tall silo, 6 for the shallow one]
  local got
  got=$("$GF" render "$RUNS/$1" --colour "$2" --times "$(s "$3")" --scale "${5:-4}" -o "$RUNS/$1/render-repro" 2>>"$RUNS/render.log") ||
    die "granflow render $RUNS/$1 failed, see $RUNS/render.log"
  cp "$(printf '%s\n' "$got" | tail -1)" "$OUT/$4"
}
say "drawing"
: >"$RUNS/render.log"
for n in base fixed-random fixed-newest; do
  for t in $PIC4; do render "$n" phi "$t" "fig4-$n-t$t.png"; done
done
for n in surf-beta0 surf-beta1 surf-beta1w surf-beta3w; do
  render "$n" layer "$PIC5" "fig5-$n.png" 6
  render "$n" phi-raw "$PIC5" "fig6-$n.png" 6
done
for n in base random-k100 random-k1000 none; do render "$n" layer "$PIC10" "fig10-$n.png"; done

# ---- the report -------------------------------------------------------------------
say "writing $OUT/REPORT.md"
REPRO_PLAN="$PLAN" REPRO_W4="$W4" REPRO_W8="$W8" REPRO_W9="$W9" REPRO_W7="$W7" \
REPRO_T="$T_MAIN $T_RELAX $T_SURF" REPRO_PIC="$PIC4|$PIC5|$PIC10" REPRO_SURF_FILL=$SURF_FILL \
REPRO_TOTAL=$((SECONDS - start)) REPRO_JOBS="$JOBS" \
  python3 "$ROOT/scripts/reproduce_report.py" "$OUT" || die "the report failed"
say "done in $((SECONDS - start)) s: $OUT/REPORT.md"
