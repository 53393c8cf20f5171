#!/usr/bin/env bash
# granflow dem with run.recirculate = on (issue 27): a real LAMMPS run of 300
# spheres in an 8 x 6 box, 4 tau of drainage with every particle that falls
# through the orifice put back on top (~10 s on one core), then a cylinder
# with zone reinsertion (3 tau). Checks: the count is 300 in every snapshot; no
# particle leaves the box but through the orifice; every re-inserted
# particle is clear of every other one where it is put (its position from
# reinserted.txt against the snapshot of that very step); exits.csv has a
# spot run's header, is sorted, and has one row per reinsertion;
# analyze's flow rate is the exits' rate; calibrate's spot runs recirculate
# too, and compare works; what granflow dem cannot do is refused, naming
# the key.
# ctest: nosan
NAME=dem_recirc
source "$(dirname "$0")/lib.bash" "$@"

BOX=(--set container.width=8 --set container.depth=6 --set container.orifice_diameter=4
    --set packing.particles=300 --set dem.fill_method=generate --set dem.settle_time=2 --set dem.settle_ke=1e-3
    --set dem.mpi_ranks=1)

# ---- refusals: before any file is written ----
gf dem -q "${BOX[@]}" --set run.recirculate=on --set run.max_passes=3 -o bad
expect_rc 2 "dem with run.max_passes"
expect_err "run.max_passes" "dem with run.max_passes"
[ -e bad/in.drain ] && fail "dem with run.max_passes wrote in.drain"
gf dem -q --set container.shape=cylinder --set container.radius=5 --set container.hopper_angle=60 \
    --set container.outlet_diameter=4 --set container.inner_radius=1 \
    --set packing.particles=300 --set dem.fill_method=generate --set run.recirculate=on -o bad
expect_rc 2 "dem recirculating around a column"
expect_err "around a central column (container.inner_radius)" "dem recirculating around a column"
ok "run.max_passes and a central column refused under run.recirculate = on, naming the key"

# ---- the box ----
gf dem -q "${BOX[@]}" --set run.recirculate=on --set run.duration=4 --set output.snapshot_interval=0.1 -o rc --run
expect_rc 0 "granflow dem --run with run.recirculate = on"
grep -q '^recirculate *= *on' rc/config.ini || fail "rc/config.ini does not say run.recirculate = on"
grep -q 'evaporate' rc/in.drain && fail "a recirculating in.drain still deletes particles"
snaps=(rc/snapshots/*.dump)
[ "${#snaps[@]}" -eq 41 ] || fail "expected 41 snapshots, got ${#snaps[@]}"
counts=$(for f in "${snaps[@]}"; do sed -n 6p "$f"; done | sort -u | tr '\n' ' ')
[ "$counts" = "300 " ] || fail "the particle count changes between snapshots: $counts"
ok "300 particles in each of the 41 snapshots"

# Inside the box (|x| < 4, |y| < 3 for a centre, up to a contact's overlap),
# and below the base (z < 1/2) only over the orifice of radius 2.
bad=$(awk 'FNR > 11 { x = $2; y = $3; z = $4; r = sqrt(x * x + y * y);
           if ((x < 0 ? -x : x) > 3.55 || (y < 0 ? -y : y) > 2.55 || (z < 0.45 && r > 2.05))
               print FILENAME ": " $0 }' "${snaps[@]}" | head -n 3)
[ -z "$bad" ] || fail "a particle outside the box: $bad"
kea=$(awk '$1 ~ /^[0-9]+$/ && NF == 4 && $4 > m { m = $4 } END { print m + 0 }' rc/log.drain)
awk -v k="$kea" 'BEGIN { exit !(k < 1) }' || fail "the kinetic energy per particle reached $kea (a re-inserted particle overlapping?)"
ok "no particle leaves but through the orifice; kinetic energy per particle at most $kea"

# Each reinsertion against the snapshot of the same step (written just
# before the particles are put back; one every 0.1 tau here): no centre of
# the others, nor of the particles put back with it, within 1 d (2 r).
nre=$(grep -vc '^#' rc/reinserted.txt)
[ "$nre" -gt 10 ] || fail "only $nre reinsertions in 4 tau"
check=$(awk '
    FILENAME ~ /reinserted/ { if ($0 ~ /^#/) next; k = int($2 * 10 + 0.5); n[k]++; id[k, n[k]] = $1
                              px[k, n[k]] = $7; py[k, n[k]] = $8; pz[k, n[k]] = $9; moved[k, $1] = 1; next }
    FNR == 2 { k = int($1 * 10 + 0.5); seen[k] = 1 }
    FNR > 11 && (k in n) && !((k, $1) in moved) {
        for (j = 1; j <= n[k]; j++) {
            d = sqrt(($2 - px[k, j])^2 + ($3 - py[k, j])^2 + ($4 - pz[k, j])^2)
            if (m == "" || d < m) m = d
        }
    }
    END {
        for (k in n) {
            if (!(k in seen)) { print "no snapshot at t = " k / 10; exit }
            for (i = 1; i <= n[k]; i++) for (j = i + 1; j <= n[k]; j++) {
                d = sqrt((px[k, i] - px[k, j])^2 + (py[k, i] - py[k, j])^2 + (pz[k, i] - pz[k, j])^2)
                if (d < m) m = d
            }
        }
        print m
    }' rc/reinserted.txt "${snaps[@]}")
awk -v m="$check" 'BEGIN { exit !(m + 0 >= 1.0) }' || fail "a re-inserted particle overlaps another: closest centre $check d"
ok "$nre reinsertions, each at least $check d from every other centre (1 d = contact)"

head -1 rc/exits.csv | grep -qx 'id,time,x,y,pass,entry_time,entry_r' || fail "exits.csv header: $(head -1 rc/exits.csv)"
rows=$(($(wc -l < rc/exits.csv) - 1))
[ "$rows" -eq "$nre" ] || fail "exits.csv has $rows rows for $nre reinsertions"
sort -t, -k2,2g -k1,1n <(tail -n +2 rc/exits.csv) | cmp -s - <(tail -n +2 rc/exits.csv) || fail "exits.csv is not sorted by time"
awk -F, 'NR > 1 && ($2 < 0 || $2 > 4 || $5 < 1) { bad = 1 } END { exit bad }' rc/exits.csv ||
    fail "exits.csv: a time outside 0..4 tau or a pass below 1"
ok "exits.csv: a spot run's header, sorted, one row per reinsertion ($rows)"

gf analyze rc --no-plots -o an
expect_rc 0 "analyze a recirculating DEM run"
grep -q 'read off the snapshots' err && fail "analyze read the exits off the snapshots, not exits.csv"
read -r t0 t1 q n < <(sed -n 's/.*"window_t0": \([^,]*\),*/\1/p; s/.*"window_t1": \([^,]*\),*/\1/p; s/.*"flow_rate": \([^,]*\),*/\1/p; s/.*"particles_exited": \([^,]*\),*/\1/p' \
    an/summary.json | tr '\n' ' ')
[ "$n" = "$rows" ] || fail "analyze: particles_exited = $n, exits.csv has $rows"
# The flow rate is the least-squares slope of (time, k) over the exits in the steady window.
fit=$(awk -F, -v t0="$t0" -v t1="$t1" 'NR > 1 { k++; if ($2 >= t0 && $2 <= t1) { m++; sx += $2; sy += k; sxx += $2 * $2; sxy += $2 * k } }
      END { print (m * sxy - sx * sy) / (m * sxx - sx * sx), m / (t1 - t0) }' rc/exits.csv)
read -r slope perT <<< "$fit"
awk -v q="$q" -v s="$slope" -v p="$perT" 'BEGIN { d = q - s; if (d < 0) d = -d; r = q / p;
    exit !(d <= 1e-6 * s && r > 0.7 && r < 1.43) }' ||
    fail "analyze: flow rate $q, the exits' slope $slope, exits / window $perT (window $t0..$t1)"
ok "analyze: flow rate $q = the exits' rate (slope $slope; $n exits / window = $perT)"

gf calibrate rc -o params.ini
expect_rc 0 "calibrate a recirculating DEM run"
grep -q '^recirculate *= *on' params.ini || fail "params.ini does not recirculate"
gf run -q params.ini -o spot
expect_rc 0 "granflow run params.ini"
re=$(sed -n 's/.*"particles_reinserted": \([0-9]*\).*/\1/p' spot/summary.json)
[ "${re:-0}" -gt 0 ] || fail "the calibrated spot run put no particle back"
gf compare rc spot --no-plots
expect_rc 0 "compare rc spot"
grep -q 'flow rate Q' out || fail "compare: no flow rate row"
ok "calibrate (its spot runs recirculate: $re put back), the spot run, compare"

# Without exits.csv (a killed granflow) the exits cannot be read off the
# snapshots of a recirculating run: an error, not a short outflow.
mv rc/exits.csv rc/exits.keep
gf analyze rc --no-plots -o an2
expect_rc 3 "analyze a recirculating DEM run without exits.csv"
expect_err "run.recirculate = on but no exits.csv" "analyze a recirculating DEM run without exits.csv"
mv rc/exits.keep rc/exits.csv
ok "a recirculating DEM run without exits.csv: exit 3 saying why"

# --drain-only again: exits.csv and reinserted.txt are the new drain's.
echo "999999 0 0 0 -3 -1 0 0 9" >> rc/reinserted.txt
gf dem -q "${BOX[@]}" --set run.recirculate=on -o rc --drain-only
expect_rc 0 "dem --drain-only of a recirculating run"
grep -q '^999999,' rc/exits.csv && fail "--drain-only kept the previous drain's reinsertions"
[ "$(($(wc -l < rc/exits.csv) - 1))" -eq "$(grep -vc '^#' rc/reinserted.txt)" ] ||
    fail "--drain-only: exits.csv does not have one row per reinsertion"
ok "--drain-only starts the records afresh"

# ---- a cylinder over a funnel, put back in a zone r < 2 ----
gf dem -q --set container.shape=cylinder --set container.radius=4 --set container.hopper_angle=60 \
    --set container.outlet_diameter=3 --set container.outlet_length=1 --set packing.particles=300 \
    --set dem.fill_method=generate --set dem.settle_time=2 --set dem.settle_ke=1e-3 --set dem.mpi_ranks=1 \
    --set run.recirculate=on --set run.reinsert=zone --set run.reinsert_rmax=2 --set run.duration=3 \
    --set output.snapshot_interval=0.5 -o cyl --run
expect_rc 0 "granflow dem --run of a recirculating cylinder"
counts=$(for f in cyl/snapshots/*.dump; do sed -n 6p "$f"; done | sort -u | tr '\n' ' ')
[ "$counts" = "300 " ] || fail "cylinder: the particle count changes between snapshots: $counts"
bad=$(awk 'FNR > 11 && sqrt($2 * $2 + $3 * $3) > 3.55 { print FILENAME ": " $0 }' cyl/snapshots/*.dump | head -n 3)
[ -z "$bad" ] || fail "cylinder: a particle beyond the wall: $bad"
far=$(awk '!/^#/ && sqrt($7 * $7 + $8 * $8) >= 2 { print }' cyl/reinserted.txt | head -n 1)
[ -z "$far" ] || fail "cylinder: a particle put back outside the zone r < 2: $far"
[ "$(grep -vc '^#' cyl/reinserted.txt)" -gt 3 ] || fail "cylinder: hardly any reinsertion"
ok "cylinder: 300 in every snapshot, inside the wall, put back only at r < 2"
echo "cli $NAME: $PASS passed, 0 failed"
