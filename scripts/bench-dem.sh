#!/usr/bin/env bash
# bench-dem.sh: LAMMPS wall seconds per simulated tau for the DEM that `granflow dem` writes (default
# config: the papers' silo), with 1 and 2 MPI ranks; one JSON object on stdout, progress on stderr.
set -euo pipefail

# Usage: scripts/bench-dem.sh [GRANFLOW_BINARY] [OUTDIR]   (defaults build/granflow, build/bench-dem)
# Environment: BENCH_DEM_STEPS (measured steps, default 3000 = 0.3 tau), BENCH_DEM_SETTLE (unmeasured
# settle-in steps, default 10000 = 1 tau), BENCH_DEM_SETTLE_RANKS (1 or 2, default 1: two ranks are
# slower than one when another job holds the other core), LMP (default lmp), MPIRUN (default mpirun;
# empty: 1 rank only).
#
# The LAMMPS inputs are derived from the files `granflow dem --set dem.fill_method=generate` writes,
# not written by hand, so the physics is the drainage's:
# - in.settle: in.fill's setup (units, read_data fill.data, the rim beads) up to its first physics line
#   (comm_modify), then in.drain from that line on (pair style and coefficients, walls, gravity,
#   timestep, the base with the open orifice, deletion below it) without dumps and prints, with
#   `thermo 0` and its `run` replaced by `run SETTLE` + `write_restart time.restart`. granflow's
#   generated packing is not in equilibrium (its contacts carry no load): under gravity the column
#   falls and compacts during the first ~1 tau (kinetic energy per particle up to ~0.15), and LAMMPS
#   is ~10% faster in that phase than in the compacted, draining packing, so the settle-in lasts 1 tau.
# - in.time: in.drain with `read_restart time.restart` instead of settled.restart, without dumps and
#   prints, `thermo 0`, `run STEPS` (measured: LAMMPS' "Loop time of X on P procs for N steps").
# The script checks that in.fill's and in.drain's physics blocks are identical and that in.drain's
# part before them is only read_restart + newton off, so nothing of the drainage physics is dropped.

GRANFLOW=${1:-build/granflow}
OUT=${2:-build/bench-dem}
STEPS=${BENCH_DEM_STEPS:-3000}
SETTLE=${BENCH_DEM_SETTLE:-10000}
SETTLE_RANKS=${BENCH_DEM_SETTLE_RANKS:-1}
LMP=${LMP:-lmp}
MPIRUN=${MPIRUN-mpirun}

say() { echo "bench-dem: $*" >&2; }
die() { echo "bench-dem: error: $*" >&2; exit 1; }

[[ $STEPS =~ ^[1-9][0-9]*$ ]] || die "BENCH_DEM_STEPS must be a positive integer (got '$STEPS')"
[[ $SETTLE =~ ^[0-9]+$ ]] || die "BENCH_DEM_SETTLE must be a non-negative integer (got '$SETTLE')"
[[ $SETTLE_RANKS == 1 || $SETTLE_RANKS == 2 ]] || die "BENCH_DEM_SETTLE_RANKS must be 1 or 2 (got '$SETTLE_RANKS')"
command -v "$LMP" >/dev/null 2>&1 ||
    die "LAMMPS ('$LMP') not found: install it (apt-get install lammps, or scripts/deps.sh) or set LMP=/path/to/lmp"
[[ -x $GRANFLOW ]] || die "granflow binary '$GRANFLOW' not found or not executable (build it, or pass its path)"
HAVE_MPI=0
if [[ -n $MPIRUN ]] && command -v "$MPIRUN" >/dev/null 2>&1; then
    HAVE_MPI=1
else
    say "no mpirun ('$MPIRUN' not found or MPIRUN empty): only 1 rank is measured (the 2-rank fields are null)"
fi

mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
say "load average before: $load_before"

# ---- 1. granflow's inputs (default config, granflow's own packing: no pour) ----
say "writing the LAMMPS inputs with $GRANFLOW dem (default config, dem.fill_method=generate) into $OUT"
"$GRANFLOW" dem --set dem.fill_method=generate -o "$OUT" --force >&2
for f in in.fill in.drain fill.data; do [[ -s $OUT/$f ]] || die "granflow dem did not write $OUT/$f"; done

# ---- 2. in.settle and in.time, derived from in.fill and in.drain ----
physics() { sed -n '/^comm_modify/,/^thermo [0-9]/p' "$1"; }
[[ -n $(physics "$OUT/in.fill") ]] || die "no physics block (comm_modify ... thermo) in $OUT/in.fill"
[[ $(physics "$OUT/in.fill") == "$(physics "$OUT/in.drain")" ]] ||
    die "the physics blocks of in.fill and in.drain differ: the timing would not use the drainage's physics"
grep -qx 'read_data fill.data' "$OUT/in.fill" || die "$OUT/in.fill does not read fill.data (not dem.fill_method=generate?)"
pre_drain=$(sed -n '/^comm_modify/q;/^#/d;/^$/d;p' "$OUT/in.drain")
[[ $pre_drain == $'read_restart settled.restart\nnewton off' ]] ||
    die "unexpected setup in in.drain before comm_modify (granflow's format changed?): $pre_drain"
[[ $(grep -c '^run ' "$OUT/in.drain") == 1 ]] || die "in.drain should have exactly one run command"
# drain_body RUNLINES: in.drain from comm_modify on, without dumps/prints, thermo 0, run -> RUNLINES
drain_body() {
    sed -n '/^comm_modify/,$p' "$OUT/in.drain" |
        sed -E -e '/^(dump|dump_modify|print) /d' -e '/^# snapshots /d' -e 's/^thermo [0-9]+$/thermo 0/' \
            -e "s/^run [0-9]+\$/$1/"
}
{
    echo "# bench-dem.sh settle-in, derived from in.fill (setup up to comm_modify) and in.drain (from"
    echo "# comm_modify on, without dump/print, thermo 0, run -> $SETTLE steps and a restart for in.time)"
    sed -n '/^comm_modify/q;p' "$OUT/in.fill"
    drain_body "run $SETTLE\\nwrite_restart time.restart"
} >"$OUT/in.settle"
{
    echo "# bench-dem.sh timing input: in.drain from the settle-in's restart (time.restart), without"
    echo "# dump/print, thermo 0, run -> $STEPS measured steps"
    sed -n '/^comm_modify/q;p' "$OUT/in.drain" | sed 's/^read_restart settled\.restart$/read_restart time.restart/'
    drain_body "run $STEPS"
} >"$OUT/in.time"

particles=$(awk '$2 == "atoms" { print $1; exit }' "$OUT/fill.data")
beads=$(grep -c '^create_atoms ' "$OUT/in.settle" || true)
dt=$(awk '$1 == "timestep" { print $2; exit }' "$OUT/in.time")
[[ -n $particles && -n $dt ]] || die "cannot read the particle count or the timestep from the inputs"
say "$particles particles (+$beads rim beads), timestep $dt tau: $SETTLE settle-in steps, then $STEPS measured steps"

# ---- 3. LAMMPS runs ----
mpi_cmd=()
if ((HAVE_MPI)); then
    mpi_cmd=("$MPIRUN" -np 2)
    "$MPIRUN" --version 2>&1 | grep -q 'Open MPI' && mpi_cmd=("$MPIRUN" --allow-run-as-root -np 2)
fi
# run_lmp INPUT LABEL WANT_STEPS CMD...: runs CMD -in INPUT in OUT (log OUT/log.LABEL) and sets loop,
# nprocs, neighs, builds, cpu, pairpct, modpct from its last run
run_lmp() {
    local input=$1 label=$2 want=$3
    shift 3
    local log="$OUT/log.$label" t0 t1 line nsteps
    say "running LAMMPS ($label): $* -in $input"
    t0=$(date +%s)
    (cd "$OUT" && OMP_NUM_THREADS=1 "$@" -in "$input" -log "$log" -screen none >"$OUT/out.$label" 2>&1) ||
        die "LAMMPS failed ($label): see $log and $OUT/out.$label"
    t1=$(date +%s)
    line=$(grep 'Loop time of' "$log" | tail -n 1)
    [[ -n $line ]] || die "no 'Loop time of' line in $log"
    # Loop time of X on P procs for N steps with A atoms
    read -r loop nprocs nsteps <<<"$(awk '{ print $4, $6, $9 }' <<<"$line")"
    [[ $nsteps == "$want" ]] || die "$log: the last run has $nsteps steps, not $want"
    neighs=$(awk -F'= *' '/^Ave neighs\/atom/ { v = $2 } END { print v }' "$log")
    builds=$(awk -F'= *' '/^Neighbor list builds/ { v = $2 } END { print v }' "$log")
    cpu=$(awk '/% CPU use with/ { v = $1 } END { sub(/%/, "", v); print v }' "$log")
    pairpct=$(awk '$1 == "Pair" && $2 == "|" { v = $NF } END { print v }' "$log")
    modpct=$(awk '$1 == "Modify" && $2 == "|" { v = $NF } END { print v }' "$log")
    say "  $label: $want steps in $loop s on $nprocs procs ($((t1 - t0)) s with setup); $cpu% CPU, Pair $pairpct%, Modify $modpct%"
}

# the settle-in (not measured)
((SETTLE > 0)) || say "BENCH_DEM_SETTLE=0: no settle-in, timing from the generated packing at rest"
if ((HAVE_MPI && SETTLE_RANKS == 2)); then run_lmp in.settle settle "$SETTLE" "${mpi_cmd[@]}" "$LMP"
else run_lmp in.settle settle "$SETTLE" "$LMP"; fi
[[ -s $OUT/time.restart ]] || die "the settle-in did not write $OUT/time.restart"
sl=$loop slp=$nprocs

run_lmp in.time time.1rank "$STEPS" "$LMP"
l1=$loop n1=$neighs b1=$builds c1=$cpu pp1=$pairpct mp1=$modpct
l2=null c2=null pp2=null mp2=null
if ((HAVE_MPI)); then
    run_lmp in.time time.2ranks "$STEPS" "${mpi_cmd[@]}" "$LMP"
    [[ $nprocs == 2 ]] || die "mpirun -np 2 ran LAMMPS on $nprocs procs (is lmp built without MPI?)"
    l2=$loop c2=$cpu pp2=$pairpct mp2=$modpct
fi

# the thermo lines (step time nflow kea) at the start and the end of the measured 1-rank run
read -r nflow0 kea0 nflow1 kea1 <<<"$(awk '$1 == "Step" { getline; a = $3 " " $4; last = "" }
    $1 == "Loop" { print a, last } { last = $3 " " $4 }' "$OUT/log.time.1rank")"

load_after=$(cut -d' ' -f1-3 /proc/loadavg)
say "load average after: $load_after"

# ---- 4. JSON ----
cpu_model=$(awk -F': *' '/^model name/ { print $2; exit }' /proc/cpuinfo | tr -d '\042\134')
lmp_version=$(awk '/^LAMMPS \(/ { sub(/^LAMMPS \(/, ""); sub(/\).*/, ""); print; exit }' "$OUT/log.time.1rank" | tr -d '\042\134')
awk -v particles="$particles" -v beads="$beads" -v dt="$dt" -v steps="$STEPS" -v settle="$SETTLE" \
    -v l1="$l1" -v l2="$l2" -v n1="$n1" -v b1="$b1" -v c1="$c1" -v c2="$c2" \
    -v pp1="$pp1" -v mp1="$mp1" -v pp2="$pp2" -v mp2="$mp2" -v sl="$sl" -v slp="$slp" \
    -v nflow0="$nflow0" -v kea0="$kea0" -v nflow1="$nflow1" -v kea1="$kea1" \
    -v nproc="$(nproc)" -v cpu_model="$cpu_model" -v lmp_version="$lmp_version" \
    -v load_before="$load_before" -v load_after="$load_after" -v outdir="$OUT" 'function num(x) { return x == "" ? "null" : x }
function per_tau(l) { return l == "null" ? "null" : sprintf("%.6g", l / (steps * dt)) }
function per_s(l) { return l == "null" ? "null" : sprintf("%.6g", steps / l) }
BEGIN {
    printf "{\"particles\": %d, \"rim_beads\": %d, \"timestep_tau\": %s, \"settle_steps\": %d, \"steps\": %d, ", particles, beads, dt, settle, steps
    printf "\"measured_tau\": %.6g, \"settle_tau\": %.6g, ", steps * dt, settle * dt
    printf "\"settle_loop_seconds\": %s, \"settle_ranks\": %s, ", num(sl), num(slp)
    printf "\"flow_particles_start\": %s, \"flow_particles_end\": %s, ", num(nflow0), num(nflow1)
    printf "\"ke_per_particle_start\": %s, \"ke_per_particle_end\": %s, ", num(kea0), num(kea1)
    printf "\"lammps_seconds_per_tau_1rank\": %s, \"lammps_seconds_per_tau_2ranks\": %s, ", per_tau(l1), per_tau(l2)
    printf "\"lammps_steps_per_second_1rank\": %s, \"lammps_steps_per_second_2ranks\": %s, ", per_s(l1), per_s(l2)
    printf "\"lammps_loop_seconds_1rank\": %s, \"lammps_loop_seconds_2ranks\": %s, ", l1, l2
    printf "\"speedup_2ranks\": %s, ", l2 == "null" ? "null" : sprintf("%.3g", l1 / l2)
    printf "\"cpu_use_percent_1rank\": %s, \"cpu_use_percent_2ranks\": %s, ", num(c1), num(c2)
    printf "\"pair_percent_1rank\": %s, \"modify_percent_1rank\": %s, ", num(pp1), num(mp1)
    printf "\"pair_percent_2ranks\": %s, \"modify_percent_2ranks\": %s, ", num(pp2), num(mp2)
    printf "\"ave_neighs_per_atom\": %s, \"neighbor_list_builds_1rank\": %s, ", num(n1), num(b1)
    printf "\"nproc\": %d, \"cpu_model\": \"%s\", \"lammps_version\": \"%s\", ", nproc, cpu_model, lmp_version
    printf "\"loadavg_before\": \"%s\", \"loadavg_after\": \"%s\", \"outdir\": \"%s\"}\n", load_before, load_after, outdir
}'
