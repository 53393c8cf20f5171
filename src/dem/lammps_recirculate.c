// SPDX-License-Identifier: MIT
// The drainage of in.drain with run.recirculate = on (issue 27): no particle
// leaves. LAMMPS runs in chunks of GF_DEM_REINSERT_EVERY tau; after each,
// every particle that fell gf_dem_plan.delete_z below the base (through the
// orifice) is put back, one at a time, at rest and keeping its id, at a
// random point of a slab above the packing's surface (which rises as the
// flowing packing dilates: the slab follows it) that no particle centre
// comes within 2 r_max of (tried again from a new random point until one is
// clear: no overlap). Each one is a line of reinserted.txt, from
// which gf_dem_write_exits (reinserted.c) makes exits.csv.
//
// LAMMPS 2021 (Debian 12's) has no command that picks one atom of a group
// nor an atom map in this atom style, so the loop finds them by coding
// their ids into their heights: the particles below the deletion plane are
// all about to move, so their z becomes delete_z - 1 - s id (s small, one
// per id: no two the same, all within the box), the lowest of them is the
// highest id, decoded with round(); `create_atoms random` draws a point
// inside the region (any shape's: a box, a cylinder, a wedge, an annulus),
// and a sphere region about it counts the centres too close.
#include <math.h>
#include <stdbool.h>
#include <stdio.h>

#include "core/error.h"
#include "dem/dem_internal.h"
#include "geom/container.h"
#include "granflow/defs.h"

#define GF_DEM_REINSERT_GAP 1.0    // the slab starts this far above the settled packing's highest centre, d
#define GF_DEM_REINSERT_SLAB 3.0   // and is this thick, d (a particle falls at most 4 d: it lands at < 3 d/tau)
#define GF_DEM_REINSERT_MARGIN 0.01 // clearance beyond contact of a re-inserted centre from every other, d
#define GF_DEM_REINSERT_TRIES 10000 // points tried for one particle before LAMMPS stops: the slab is full
#define GF_DEM_SURFACE_FILL 0.25   // a layer this full of a dense one is the packing's surface
#define GF_DEM_DILATION 0.15       // the box keeps room for the flowing packing to rise by this much

gf_status gf_dem_recirc_check(const gf_config *c)
{
    gf_engine_defs ed;
    gf_config_engine_defs(c, &ed);
    if (!ed.recirculate) return GF_OK;
    char where[GF_PATH_MAX + 64];
    if (ed.max_passes != 0)
        return gf_error_set(GF_ERR_PARAM,
                            "%srun.max_passes = %lld: granflow dem puts every particle back every time it leaves "
                            "(run.max_passes = 0); a last pass is not supported in the DEM",
                            gf_config_where_lead(c, "run.max_passes", where, sizeof where), (long long)ed.max_passes);
    const gf_container box = gf_container_make(c);
    double r[2];
    box.ops->radii(&box, r);
    if (r[0] > 0.0)
        return gf_error_set(GF_ERR_PARAM,
                            "%srun.recirculate = on around a central column (container.inner_radius): granflow dem "
                            "cannot put particles back there (its reinsertion region would cut the column)",
                            gf_config_where_lead(c, "run.recirculate", where, sizeof where));
    if (gf_container_lammps_pour(&box, NULL, 0.0, 0.0, 1.0) != GF_OK)
        return gf_error_set(GF_ERR_PARAM, "%srun.recirculate = on: no region to put particles back in: %s",
                            gf_config_where_lead(c, "run.recirculate", where, sizeof where), gf_last_error());
    return GF_OK;
}

double gf_dem_recirc_headroom(double top)
{
    return GF_DEM_REINSERT_GAP + GF_DEM_REINSERT_SLAB + 1.0 + GF_DEM_DILATION * top;
}

/// The region rc_in: the pour region, the slab rc_slab and the zone's annulus.
static void gf_dem_recirc_zone(FILE *f, const gf_engine_defs *ed, bool define)
{
    const bool zone = ed->reinsert == GF_REINSERT_ZONE, in = zone && ed->reinsert_rmin > 0.0,
               out = zone && !isnan(ed->reinsert_rmax);
    if (define) {
        if (in) fprintf(f, "region rc_zin cylinder z 0 0 %.10g INF INF side out units box\n", ed->reinsert_rmin);
        if (out) fprintf(f, "region rc_zout cylinder z 0 0 %.10g INF INF units box\n", ed->reinsert_rmax);
        return;
    }
    fprintf(f, "region rc_in intersect %d pour rc_slab%s%s\n", 2 + in + out, in ? " rc_zin" : "", out ? " rc_zout" : "");
}

void gf_dem_recirc_drain(FILE *f, const gf_config *c, const gf_dem_plan *plan, double rmax, long seed)
{
    gf_engine_defs ed;
    gf_config_engine_defs(c, &ed);
    gf_dem_defs dd;
    gf_config_dem_defs(c, &dd);
    const gf_container box = gf_container_make(c);
    const double zdel = plan->delete_z, park = zdel - 1.0;
    // One height per id below `park`, the largest id less than 1 d lower (ids
    // run 1 .. flowing particles + rim beads; 4 times that is room to spare).
    const double s = 0.25 / (double)(plan->particles + (int64_t)plan->rim_beads + 1);
    const double ball = 2.0 * rmax + GF_DEM_REINSERT_MARGIN, inset = rmax + 0.05;
    const int64_t chunk = plan->reinsert_steps, full = plan->drain_steps / chunk, rest = plan->drain_steps % chunk;
    // A layer 1 d thick under the slab holding more than this many centres is
    // packing, not particles falling through (GF_DEM_SURFACE_FILL of a dense
    // layer at phi = 0.6; falling ones are a few): the slab moves up 0.5 d.
    const double vp = 3.14159265358979323846 / 6.0 * 8.0 * rmax * rmax * rmax;
    const long dense = (long)ceil(GF_DEM_SURFACE_FILL * 0.6 * box.ops->section_area(&box, box.z_col) / vp);
    const double top = plan->box_zhi - 1.0; // the slab stays 1 d inside the box's top
    fprintf(f,
            "# run.recirculate = on: no particle leaves. Every %g tau the particles that fell below\n"
            "# z = %g (through the orifice) are put back one at a time, at rest and with their ids, at\n"
            "# a random point of the region rc_in (a slab %g d thick from %g d above the highest centre of\n"
            "# the settled packing, moved up 0.5 d at a time while the 1 d below it holds more than %ld\n"
            "# centres: the packing's dilated surface; %g d from the walls%s) with no particle centre\n"
            "# within %g d; each is a line of reinserted.txt (id, time, where it fell: x y z vz, where it\n"
            "# was put: x y z), from which granflow dem writes exits.csv. Their heights are kept in vx\n"
            "# (zeroed anyway) and their ids coded into their heights (z = %g - %.6g id) to pick them\n"
            "# one by one (docs/dem.md, long references by recirculation).\n"
            "region gone block INF INF INF INF INF %.10g units box\n"
            "variable rc_lo equal $(bound(flow,zmax)+%g)\n",
            (double)chunk * dd.timestep, zdel, GF_DEM_REINSERT_SLAB, GF_DEM_REINSERT_GAP, dense, inset,
            ed.reinsert == GF_REINSERT_ZONE ? ", in the run.reinsert zone" : "", ball, park, s, zdel,
            GF_DEM_REINSERT_GAP);
    gf_container_lammps_pour(&box, f, inset, plan->box_zlo, plan->box_zhi);
    gf_dem_recirc_zone(f, &ed, true);
    fprintf(f,
            "variable rc_code atom %.10g-%.17g*id\n"
            "variable rc_z atom z\n"
            "variable rc_seed equal floor(random(1,900000000,%ld))\n"
            "variable rc_n equal 0\n"
            "variable rc_pre string yes\n"
            "print \"# granflow reinsertions, exit plane z = %.10g\" file reinserted.txt screen no\n"
            "print \"# id time x y z vz x_new y_new z_new\" append reinserted.txt screen no\n"
            "# snapshots every %g tau, in the format granflow reads (ITEM: TIME in tau)\n"
            "dump snap flow custom %lld snapshots/snap_*.dump id x y z radius\n"
            "dump_modify snap pad 9 sort id time yes\n",
            park, s, seed, gf_config_exit_plane(c), dd.snapshot_interval, (long long)plan->snapshot_steps);
    gf_dem_restart_line(f, plan, dd.timestep);
    fprintf(f,
            "print \"granflow-phase drain ${nflow} %.6g\"\n"
            "variable rc_k loop %lld\n"
            "label rc_loop\n"
            "run %lld pre ${rc_pre} post no\n"
            "variable rc_pre string no\n"
            "label rc_block\n"
            "if \"$(count(flow,gone)) == 0\" then \"jump SELF rc_next\"\n"
            "label rc_rise\n"
            "region rc_layer block INF INF INF INF $(v_rc_lo-1) ${rc_lo} units box\n"
            "variable rc_dense equal $(count(flow,rc_layer))\n"
            "region rc_layer delete\n"
            "if \"${rc_dense} > %ld\" then \"variable rc_lo equal $(v_rc_lo+0.5)\" \"jump SELF rc_rise\"\n"
            "if \"${rc_lo} >= %.10g\" then \"print 'ERROR: granflow: no room above the packing (its surface at "
            "${rc_lo}) to put particles back: the LAMMPS box ends at %.10g'\" \"quit 1\"\n"
            "region rc_slab block INF INF INF INF ${rc_lo} $((v_rc_lo+%g<%.10g)*(v_rc_lo+%g)+(v_rc_lo+%g>=%.10g)*%.10g) "
            "units box\n",
            dd.duration, (long long)full, (long long)chunk, dense, top, plan->box_zhi, GF_DEM_REINSERT_SLAB, top,
            GF_DEM_REINSERT_SLAB, GF_DEM_REINSERT_SLAB, top, top);
    gf_dem_recirc_zone(f, &ed, false);
    fprintf(f,
            "group rc_low region gone\n"
            "group rc_gone intersect rc_low flow\n"
            "set group rc_gone vx v_rc_z\n"
            "set group rc_gone z v_rc_code\n"
            "group rc_gone delete\n"
            "group rc_low delete\n"
            "label rc_pick\n"
            "if \"$(count(flow,gone)) == 0\" then \"jump SELF rc_done\"\n"
            "variable rc_id equal $(round((%.10g-bound(flow,zmin))/%.17g))\n"
            "variable rc_t equal 0\n"
            "label rc_try\n"
            "variable rc_t equal $(v_rc_t+1)\n"
            "if \"${rc_t} > %d\" then \"print 'ERROR: granflow: no room to put particle ${rc_id} back after %d tries: "
            "the slab above the packing is full'\" \"quit 1\"\n"
            "create_atoms %d random 1 $(v_rc_seed) rc_in\n"
            "group rc_mark subtract all flow rim\n"
            "variable rc_px equal $(xcm(rc_mark,x):%%.12g)\n"
            "variable rc_py equal $(xcm(rc_mark,y):%%.12g)\n"
            "variable rc_pz equal $(xcm(rc_mark,z):%%.12g)\n"
            "delete_atoms group rc_mark compress no\n"
            "group rc_mark delete\n"
            "region rc_ball sphere ${rc_px} ${rc_py} ${rc_pz} %.10g units box\n"
            "variable rc_hit equal $(count(flow,rc_ball))\n"
            "region rc_ball delete\n"
            "if \"${rc_hit} > 0\" then \"jump SELF rc_try\"\n"
            "group rc_one id ${rc_id}\n"
            "print \"${rc_id} $(time:%%.10g) $(xcm(rc_one,x):%%.8g) $(xcm(rc_one,y):%%.8g) $(vcm(rc_one,x):%%.8g) "
            "$(vcm(rc_one,z):%%.8g) ${rc_px} ${rc_py} ${rc_pz}\" append reinserted.txt screen no\n"
            "group rc_one delete\n"
            "set atom ${rc_id} x ${rc_px} y ${rc_py} z ${rc_pz} vx 0 vy 0 vz 0 omega 0 0 0\n"
            "variable rc_n equal $(v_rc_n+1)\n"
            "variable rc_pre string yes\n"
            "jump SELF rc_pick\n"
            "label rc_done\n"
            "region rc_in delete\n"
            "region rc_slab delete\n"
            "label rc_next\n"
            "next rc_k\n"
            "jump SELF rc_loop\n",
            park, s, GF_DEM_REINSERT_TRIES, GF_DEM_REINSERT_TRIES, GF_DEM_TYPE_FLOW, ball);
    if (rest > 0) fprintf(f, "run %lld pre ${rc_pre} post no\n", (long long)rest);
    fprintf(f, "print \"granflow-phase done ${nflow} 0\"\n"
               "print \"granflow-recirculated ${rc_n}\"\n");
}
