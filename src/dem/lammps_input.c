// SPDX-License-Identifier: MIT
// LAMMPS inputs for a DEM run of granflow's container (SPEC 1.8): fill by
// fix pour (or from granflow's packing), settle, open the orifice, drain.
//
// Units lj with d = 1, particle mass 1 (density 6/pi) and g = 1, so LAMMPS
// time is tau = sqrt(d/g). Contacts: pair_style gran/hertz/history (Hertzian
// normal force with history-dependent Coulomb friction, the papers' DEM),
// the same law on the flat side walls and the base (fix wall/gran). The base
// with its hole is the surface of a union region (the half space z > 0 and
// the orifice cylinder or slab below it); a union's surface has no edge, so a
// ring of frozen beads (type 2, 0.05 d, 0.1 d apart) marks the orifice edge.
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/fs.h"
#include "dem/dem_internal.h"
#include "granflow/defs.h"
#include "granflow/dem.h"
#include "geom/container.h"
#include "granflow/packing.h"

#define GF_DEM_PI 3.14159265358979323846
#define GF_DEM_PHI_FILL 0.6     // packing fraction of a poured fill, for its expected height
#define GF_DEM_DENSITY 1.9098593171027440 // 6 / pi: a sphere of diameter 1 has mass 1
#define GF_DEM_BEAD 0.05        // diameter of the rim beads, d
#define GF_DEM_BEAD_STEP 0.1    // their spacing: a sphere of diameter 1 cannot pass between them
#define GF_DEM_DELETE_DEPTH 2.0 // particles are deleted this far below the base (through the hole)
#define GF_DEM_POUR_FRACTION 0.3 // packing fraction of each fix pour batch
#define GF_DEM_POUR_GAP 4.0     // the pour region starts this far above the expected fill, d
#define GF_DEM_CHUNK 1.0        // LAMMPS runs in chunks of this many tau between checks
#define GF_DEM_REINSERT_EVERY 0.1 // run.recirculate: tau between reinsertions (a particle falls < 0.5 d meanwhile)

/// The contact law's arguments, as pair_style and fix wall/gran take them.
static void gf_dem_contact(const gf_dem_defs *dd, char *buf, size_t n)
{
    snprintf(buf, n, "%.10g %.10g %.10g %.10g %.10g 1", dd->kn, dd->kt, dd->gamman, dd->gammat,
             dd->friction);
}

/// LAMMPS seeds are positive 31-bit integers.
static long gf_dem_seed(const gf_dem_defs *dd, unsigned salt)
{
    return 1 + (long)((dd->seed * 2654435761u + salt * 40503u) % 2000000000u);
}

/// Steps of `t` tau, at least 1.
static int64_t gf_dem_steps(const gf_dem_defs *dd, double t)
{
    double s = floor(t / dd->timestep + 0.5);
    return s < 1 ? 1 : (int64_t)s;
}

/// The common head: units, atom style, communication, neighbour lists.
static void gf_dem_head(FILE *f, const gf_config *c, const char *what)
{
    const gf_container box = gf_container_make(c);
    char shape[64] = "";
    if (!gf_container_rectangular(&box)) snprintf(shape, sizeof shape, "%s (bounding box) ", gf_container_name(&box));
    char at[96] = "the centre of";
    gf_container_defs cd;
    gf_config_container_defs(c, &cd);
    if (cd.orifice.x != 0.0 || cd.orifice.y != 0.0) // container.orifice_x, orifice_y
        snprintf(at, sizeof at, "x = %g, y = %g on", cd.orifice.x, cd.orifice.y);
    fprintf(f,
            "# granflow %s: %s\n"
            "# container %s%g x %g d, %s orifice of %g d at %s the base z = 0.\n"
            "# Units lj: d = 1, particle mass 1, g = 1, so times are in tau = sqrt(d/g).\n"
            "# Written by `granflow dem`; see docs/dem.md.\n\n",
            gf_version(), what, shape,
            cd.width, cd.depth,
            cd.orifice.shape == GF_ORIFICE_SLIT ? "slit" : "circular", cd.orifice.diameter, at);
}

static void gf_dem_physics(FILE *f, const gf_config *c, const char *pre, double zlo, double zhi)
{
    gf_dem_defs dd;
    gf_config_dem_defs(c, &dd);
    char law[256];
    gf_dem_contact(&dd, law, sizeof law);
    fprintf(f,
            "comm_modify vel yes\n"
            "neighbor 0.2 bin\n"
            "neigh_modify delay 0\n"
            "# Hertzian contacts with friction: kn kt gamma_n gamma_t mu dampflag (dem.* keys)\n"
            "pair_style gran/hertz/history %s\n"
            "pair_coeff * *\n"
            "timestep %.10g\n"
            "group flow type %d\n"
            "group rim type %d\n"
            "# frozen: the granular pair style then gives the beads infinite mass (the\n"
            "# damping of a flow-rim contact uses the flow particle's mass, not the reduced one)\n"
            "fix freeze_rim rim freeze\n"
            "fix integrate flow nve/sphere\n"
            "fix gravity flow gravity 1.0 vector 0 0 -1\n",
            law, dd.timestep, GF_DEM_TYPE_FLOW, GF_DEM_TYPE_RIM);
    const gf_container box = gf_container_make(c);
    (void)gf_container_lammps_walls(&box, f, pre, law, zlo, zhi); // the container's walls (src/geom/; asked before)
    fprintf(f,
            "compute ke flow ke\n"
            "variable nflow equal count(flow)\n"
            "variable kea equal c_ke/(v_nflow+(v_nflow==0))\n"
            "thermo_style custom step time v_nflow v_kea\n"
            "thermo_modify norm no\n"
            "thermo %lld\n",
            (long long)gf_dem_steps(&dd, 0.1));
}

/// The frozen beads along the orifice edge at z = 0 (only inside the walls),
/// around the orifice centre (container.orifice_x, orifice_y).
static size_t gf_dem_beads(FILE *f, const gf_config *c)
{
    gf_container_defs cd;
    gf_config_container_defs(c, &cd);
    double R = 0.5 * cd.orifice.diameter, hw = 0.5 * cd.width, hd = 0.5 * cd.depth;
    const double ox = cd.orifice.x, oy = cd.orifice.y;
    size_t n = 0;
    if (cd.orifice.shape == GF_ORIFICE_SLIT) {
        long m = (long)floor(cd.depth / GF_DEM_BEAD_STEP);
        for (int side = -1; side <= 1; side += 2)
            for (long k = 0; k <= m; k++) {
                double y = -hd + GF_DEM_BEAD_STEP * (double)k;
                if (fabs(y) > hd) continue;
                if (f) fprintf(f, "create_atoms %d single %.6f %.6f 0 units box\n", GF_DEM_TYPE_RIM, ox + side * R, y);
                n++;
            }
        return n;
    }
    long m = (long)ceil(2.0 * GF_DEM_PI * R / GF_DEM_BEAD_STEP);
    for (long k = 0; k < m; k++) {
        double a = 2.0 * GF_DEM_PI * (double)k / (double)m, x = ox + R * cos(a), y = oy + R * sin(a);
        if (fabs(x) > hw || fabs(y) > hd) continue;
        if (f) fprintf(f, "create_atoms %d single %.6f %.6f 0 units box\n", GF_DEM_TYPE_RIM, x, y);
        n++;
    }
    return n;
}

void gf_dem_restart_line(FILE *f, const gf_dem_plan *plan, double timestep)
{
    if (plan->restart_steps <= 0) return;
    fprintf(f,
            "# a restart file every %g tau, to drain.a.restart and drain.b.restart in turn (one is whole\n"
            "# while the other is written): granflow dem --continue goes on from the newer (docs/dem.md)\n"
            "restart %lld drain.a.restart drain.b.restart\n",
            (double)plan->restart_steps * timestep, (long long)plan->restart_steps);
}

static gf_status gf_dem_open(const char *dir, const char *name, char *path, size_t pn, char *tmp, size_t tn,
                             FILE **f)
{
    if (snprintf(path, pn, "%s/%s", dir, name) >= (int)pn) return gf_error_set(GF_ERR_PARAM, "path too long: %s", dir);
    return gf_atomic_open(path, tmp, tn, f);
}

/// fill.data: granflow's packing as a LAMMPS data file (atom_style sphere).
static gf_status gf_dem_write_data(const gf_config *c, const char *dir, const gf_packing *pk, double zlo,
                                   double zhi)
{
    char path[GF_PATH_MAX + 32], tmp[GF_PATH_MAX + 48];
    FILE *f;
    gf_status st = gf_dem_open(dir, "fill.data", path, sizeof path, tmp, sizeof tmp, &f);
    if (st != GF_OK) return st;
    gf_container_defs cd;
    gf_config_container_defs(c, &cd);
    double hw = 0.5 * cd.width, hd = 0.5 * cd.depth;
    fprintf(f, "LAMMPS data file: granflow packing of %zu spheres\n\n%zu atoms\n2 atom types\n\n", pk->n, pk->n);
    fprintf(f, "%.10g %.10g xlo xhi\n%.10g %.10g ylo yhi\n%.10g %.10g zlo zhi\n\nAtoms # sphere\n\n", -hw, hw, -hd,
            hd, zlo, zhi);
    for (size_t i = 0; i < pk->n; i++)
        fprintf(f, "%zu %d %.10g %.16g %.10g %.10g %.10g\n", i + 1, GF_DEM_TYPE_FLOW, 2.0 * pk->r[i], GF_DEM_DENSITY,
                pk->x[i], pk->y[i], pk->z[i]);
    return gf_atomic_commit(f, tmp, path);
}

gf_status gf_dem_write_inputs(const gf_config *cfg_in, const char *dir, const gf_packing_opts *opts,
                              gf_dem_plan *plan_out)
{
    gf_config cv = *cfg_in;
    gf_config *c = &cv;
    gf_status st = gf_config_validate(c);
    if (st != GF_OK) return st;
    if (!dir || !*dir) return gf_error_set(GF_ERR_PARAM, "gf_dem_write_inputs: no directory");
    gf_dem_plan plan = {0};
    const gf_container box = gf_container_make(c);
    // Whether LAMMPS can hold the walls at all (a mesh's triangles: no).
    if ((st = gf_container_lammps_walls(&box, NULL, NULL, NULL, 0.0, 0.0)) != GF_OK) {
        char where[GF_PATH_MAX + 32], why[1024];
        snprintf(why, sizeof why, "%s", gf_last_error());
        if (gf_config_where(c, "container.shape", where, sizeof where) != GF_OK) snprintf(where, sizeof where, "?");
        return gf_error_set(st, "%s: %s", where, why);
    }
    if ((st = gf_dem_recirc_check(c)) != GF_OK) return st;
    gf_dem_defs dd;
    gf_config_dem_defs(c, &dd);
    gf_engine_defs ed;
    gf_config_engine_defs(c, &ed);
    if (dd.fill == GF_DEM_POUR && (st = gf_container_lammps_pour(&box, NULL, 0.0, 0.0, 0.0)) != GF_OK)
        return st;
    // The column's cross-section, above any funnel.
    double area = box.ops->section_area(&box, box.z_col), vp = GF_DEM_PI / 6.0;
    gf_packing pk = {0};
    if (dd.fill == GF_DEM_GENERATE) {
        if ((st = gf_packing_for_config(c, opts, &pk, NULL)) != GF_OK) return st;
        plan.particles = (int64_t)pk.n;
    } else if (dd.fill_height > 0) {
        plan.particles = (int64_t)floor(GF_DEM_PHI_FILL * area * dd.fill_height / vp + 0.5);
    } else {
        plan.particles = dd.particles;
    }
    plan.fill_height = (double)plan.particles * vp / (GF_DEM_PHI_FILL * area);
    // A funnel holds less than the column over it: the fill ends at most its height higher.
    plan.fill_height += box.z_col;
    plan.delete_z = fmin(gf_config_exit_plane(c), 0.0) - GF_DEM_DELETE_DEPTH;
    plan.box_zlo = plan.delete_z - 2.0;
    plan.snapshot_steps = gf_dem_steps(&dd, dd.snapshot_interval);
    plan.drain_steps = gf_dem_steps(&dd, dd.duration);
    plan.rim_beads = gf_dem_beads(NULL, c);
    plan.reinsert_steps = ed.recirculate ? gf_dem_steps(&dd, GF_DEM_REINSERT_EVERY) : 0;
    if (dd.restart_interval > 0) {
        plan.restart_steps = gf_dem_steps(&dd, dd.restart_interval);
        // Recirculating, at the end of a chunk (before its reinsertions, which a continued drain redoes).
        if (plan.reinsert_steps > 0)
            plan.restart_steps = (plan.restart_steps + plan.reinsert_steps - 1) / plan.reinsert_steps * plan.reinsert_steps;
    }

    // Pour: batches of GF_DEM_POUR_FRACTION filling a region of height hp
    // above the fill; each batch falls hp before the next (fix pour's rule).
    double hp = 0.0, z_ins = 0.0;
    if (dd.fill == GF_DEM_POUR) {
        double need = (double)plan.particles * vp / (GF_DEM_POUR_FRACTION * area); // height holding them all
        hp = fmin(fmax(need / 4.0, 5.0), 40.0);
        z_ins = plan.fill_height + GF_DEM_POUR_GAP;
        double batches = ceil(need / hp);
        plan.pour_time = batches * sqrt(2.0 * hp) + sqrt(2.0 * (z_ins + hp));
        plan.box_zhi = z_ins + hp + 2.0;
    } else {
        double top = 0.0;
        for (size_t i = 0; i < pk.n; i++) top = fmax(top, pk.z[i] + pk.r[i]);
        // Recirculation puts particles back in a slab above the top: room for it.
        plan.box_zhi = top + 2.0 + (ed.recirculate ? gf_dem_recirc_headroom(top) : 0.0);
    }
    double rmax = 0.5; // fix pour's diameter one 1.0
    for (size_t i = 0; i < pk.n; i++) rmax = i ? fmax(rmax, pk.r[i]) : pk.r[i];

    if ((st = gf_config_check_writable(c)) != GF_OK) goto done; // config.ini goes in last: check it first
    if ((st = gf_fs_mkdirs(dir)) != GF_OK) goto done;
    char sub[GF_PATH_MAX + 32];
    snprintf(sub, sizeof sub, "%s/snapshots", dir);
    if ((st = gf_fs_mkdirs(sub)) != GF_OK) goto done;
    if (dd.fill == GF_DEM_GENERATE &&
        (st = gf_dem_write_data(c, dir, &pk, plan.box_zlo, plan.box_zhi)) != GF_OK)
        goto done;

    // ---- in.fill ----
    char path[GF_PATH_MAX + 32], tmp[GF_PATH_MAX + 48], law[256];
    gf_dem_contact(&dd, law, sizeof law);
    FILE *f;
    if ((st = gf_dem_open(dir, "in.fill", path, sizeof path, tmp, sizeof tmp, &f)) != GF_OK) goto done;
    gf_container_defs cd;
    gf_config_container_defs(c, &cd);
    double hw = 0.5 * cd.width, hd = 0.5 * cd.depth;
    gf_dem_head(f, c, "DEM fill and settle (run first; then in.drain)");
    fprintf(f, "units lj\natom_style sphere\ndimension 3\nboundary f f f\nnewton off\n");
    if (dd.fill == GF_DEM_GENERATE) {
        fprintf(f, "# granflow's packing of %lld spheres (fill.data), to be settled under gravity\nread_data fill.data\n",
                (long long)plan.particles);
    } else {
        fprintf(f, "region box block %.10g %.10g %.10g %.10g %.10g %.10g units box\ncreate_box 2 box\n", -hw, hw, -hd,
                hd, plan.box_zlo, plan.box_zhi);
    }
    fprintf(f, "# %zu frozen beads mark the orifice edge (see in.drain)\n", plan.rim_beads);
    gf_dem_beads(f, c);
    fprintf(f, "set type %d diameter %g\nset type %d density %.16g\n", GF_DEM_TYPE_RIM, GF_DEM_BEAD, GF_DEM_TYPE_RIM,
            GF_DEM_DENSITY);
    gf_dem_physics(f, c, "fill", plan.box_zlo, plan.box_zhi);
    fprintf(f, "# the base is closed while the container fills\n"
               "fix base flow wall/gran hertz/history %s zplane %.10g NULL\n",
            law, box.gate_z);
    int64_t chunk = gf_dem_steps(&dd, GF_DEM_CHUNK);
    if (dd.fill == GF_DEM_POUR) {
        long maxk = (long)ceil(2.0 * plan.pour_time / GF_DEM_CHUNK) + 20;
        fprintf(f, "# pour %lld particles from the region %.4g < z < %.4g (batches of packing fraction %g)\n",
                (long long)plan.particles, z_ins, z_ins + hp, GF_DEM_POUR_FRACTION);
        gf_container_lammps_pour(&box, f, 0.55, z_ins, z_ins + hp);
        fprintf(f,
                "fix pour flow pour %lld %d %ld region pour vol %g 200 diam one 1.0 dens %.16g %.16g vel 0 0 0 0 0\n"
                "print \"granflow-phase fill %lld %.6g\"\n"
                "variable pourk loop %ld\n"
                "label pour_loop\n"
                "run %lld\n"
                "if \"${nflow} >= %lld\" then \"jump SELF pour_done\"\n"
                "next pourk\n"
                "jump SELF pour_loop\n"
                "label pour_done\n"
                "unfix pour\n",
                (long long)plan.particles, GF_DEM_TYPE_FLOW,
                gf_dem_seed(&dd, 1), GF_DEM_POUR_FRACTION, GF_DEM_DENSITY, GF_DEM_DENSITY, (long long)plan.particles,
                plan.pour_time, maxk, (long long)chunk, (long long)plan.particles);
    } else {
        fprintf(f, "velocity flow set 0 0 0\n");
    }
    long maxs = (long)ceil(dd.settle_time / GF_DEM_CHUNK);
    if (maxs < 1) maxs = 1;
    fprintf(f,
            "# settle: at most %g tau, until the kinetic energy per particle is below %g\n"
            "print \"granflow-phase settle %lld %.6g\"\n"
            "variable settlek loop %ld\n"
            "label settle_loop\n"
            "run %lld\n"
            "if \"${kea} < %.10g\" then \"jump SELF settle_done\"\n"
            "next settlek\n"
            "jump SELF settle_loop\n"
            "label settle_done\n"
            "print \"granflow-phase settled ${nflow} ${kea}\"\n"
            "write_dump flow custom packing.dump id type x y z radius modify sort id\n"
            "write_restart settled.restart\n",
            dd.settle_time, dd.settle_ke, (long long)plan.particles, dd.settle_time, maxs,
            (long long)chunk, dd.settle_ke);
    if ((st = gf_atomic_commit(f, tmp, path)) != GF_OK) goto done;

    // ---- in.drain ----
    if ((st = gf_dem_open(dir, "in.drain", path, sizeof path, tmp, sizeof tmp, &f)) != GF_OK) goto done;
    gf_dem_head(f, c, "DEM drainage (after in.fill)");
    fprintf(f, "read_restart settled.restart\nnewton off\n");
    gf_dem_physics(f, c, "drain", plan.box_zlo, plan.box_zhi);
    fprintf(f, "reset_timestep 0\n");
    gf_container_lammps_base(&box, f, law, plan.box_zlo);
    if (ed.recirculate) {
        gf_dem_recirc_drain(f, c, &plan, rmax, gf_dem_seed(&dd, 3));
    } else {
        fprintf(f,
                "# particles that fell %g d below the base through the hole leave\n"
                "region gone block INF INF INF INF INF %.10g units box\n"
                "fix gone flow evaporate %lld %lld gone %ld\n"
                "# snapshots every %g tau, in the format granflow reads (ITEM: TIME in tau)\n"
                "dump snap flow custom %lld snapshots/snap_*.dump id x y z radius\n"
                "dump_modify snap pad 9 sort id time yes\n",
                GF_DEM_DELETE_DEPTH, plan.delete_z, (long long)gf_dem_steps(&dd, 0.01),
                (long long)(plan.particles + 1), gf_dem_seed(&dd, 2), dd.snapshot_interval,
                (long long)plan.snapshot_steps);
        gf_dem_restart_line(f, &plan, dd.timestep);
        fprintf(f,
                "print \"granflow-phase drain ${nflow} %.6g\"\n"
                "run %lld\n"
                "print \"granflow-phase done ${nflow} 0\"\n",
                dd.duration, (long long)plan.drain_steps);
    }
    if ((st = gf_atomic_commit(f, tmp, path)) != GF_OK) goto done;
    // An earlier drain's restart files and continuation do not fit this in.drain: gone, so that
    // granflow dem --continue cannot go on from them.
    static const char *const stale[] = {"drain.a.restart", "drain.b.restart", "in.continue", "log.continue"};
    for (size_t k = 0; k < sizeof stale / sizeof stale[0]; k++) {
        snprintf(path, sizeof path, "%s/%s", dir, stale[k]);
        if (unlink(path) != 0 && errno != ENOENT) {
            st = gf_error_set(GF_ERR_IO, "%s: cannot remove the earlier drain's: %s", path, strerror(errno));
            goto done;
        }
    }

    // config.ini: the container and keys, for calibrate/compare/analyze.
    snprintf(path, sizeof path, "%s/config.ini", dir);
    st = gf_config_save(c, path);
done:
    gf_packing_free(&pk);
    if (st == GF_OK && plan_out) *plan_out = plan;
    return st;
}
