#!/usr/bin/env bash
# A wedge hopper in LAMMPS (container.shape = wedge, src/geom/wedge.c's
# lammps_walls): a tiny granflow dem --run (600 spheres, 3 tau of drainage;
# ~20 s on one core), in which every particle in every snapshot stays inside
# the walls (flat walls, inclined walls, chute) and every particle that
# leaves is last seen falling through the slit; then calibrate (profiles in
# x), a spot run of its parameters, and compare.
# ctest: nosan
NAME=dem_wedge
source "$(dirname "$0")/lib.bash" "$@"

gf dem -q --set container.shape=wedge --set container.width=12 --set container.depth=4 \
    --set container.hopper_angle=60 --set container.orifice_diameter=4 --set container.outlet_length=1 \
    --set packing.particles=600 --set dem.fill_method=generate --set dem.settle_time=2 --set dem.settle_ke=1e-3 \
    --set run.duration=3 --set output.snapshot_interval=0.5 --set dem.mpi_ranks=1 -o dem --run
expect_rc 0 "granflow dem --run of a wedge (600 spheres, 3 tau)"
grep -q 'region drain_vessel union 2 drain_hopper drain_chute' dem/in.drain || fail "in.drain has no wedge region"
[ "$(ls dem/snapshots/*.dump | wc -l)" -eq 7 ] || fail "expected 7 snapshots, got $(ls dem/snapshots | wc -l)"
ok "LAMMPS drained a wedge for 3 tau (7 snapshots)"

# Inside: |y| <= 2 - 1/2, |x| <= 6 - 1/2, 1/2 above each inclined wall (60
# degrees from the slit's edges x = +-2), in the chute |x| <= 2 - 1/2; a
# contact overlaps by a few hundredths.
bad=$(awk 'FNR > 11 { x = $2; y = $3; z = $4; ax = x < 0 ? -x : x; q = ax - 2;
           if ((y < 0 ? -y : y) > 1.55 || ax > 5.55 || (q > 0 && z * 0.5 - q * 0.8660254 < 0.45) || (z < 0 && q > -0.45))
               print FILENAME ": " $0 }' dem/snapshots/*.dump | head -n 3)
[ -z "$bad" ] || fail "a particle beyond the wedge's walls: $bad"
# Leavers: in one snapshot, gone from the next; last seen over the slit, going down.
files=(dem/snapshots/*.dump)
gone=0
for ((k = 0; k + 1 < ${#files[@]}; k++)); do
    out=$(awk 'FNR == NR { if (FNR > 11) next_ids[$1] = 1; next } FNR > 11 && !($1 in next_ids) { print $2, $4 }' \
        "${files[k + 1]}" "${files[k]}")
    [ -z "$out" ] && continue
    while read -r x z; do
        awk -v x="$x" -v z="$z" 'BEGIN { exit !((x < 0 ? -x : x) < 1.6 && z < 0.5) }' ||
            fail "a particle left from (x, z) = ($x, $z), not through the slit"
        gone=$((gone + 1))
    done <<< "$out"
done
[ "$gone" -gt 5 ] || fail "only $gone particles left the wedge in 3 tau"
ok "every particle inside the walls in every snapshot; $gone left, all through the slit"

gf calibrate dem -o params.ini --no-refine
expect_rc 0 "calibrate a wedge's DEM run"
expect_err "wedge hopper 12 x 4 d" "calibrate: the container described"
grep -q 'v_z(x)' out err || fail "calibrate: the wedge's profiles are not in x"
gf run -q params.ini -o spot --set run.duration=3
expect_rc 0 "granflow run params.ini"
gf compare dem spot --no-plots
expect_rc 0 "compare dem spot"
grep -q 'flow rate Q' out || fail "compare: no flow rate row"
ok "calibrate (profiles in x), the spot run and compare on a wedge"
echo "cli $NAME: $PASS passed, 0 failed"
