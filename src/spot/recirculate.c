// SPDX-License-Identifier: MIT
// Recirculation (pebble-bed cycling; SPEC 3, issue 14): a particle that exits
// is put back on the free surface with its pass count + 1, as pebbles are
// reloaded at the top of a reactor core (Rycroft et al. 2006, Sec. I).
//
// Where: a target (x, y) uniform over the cross-section (run.reinsert =
// random) or over the annulus rmin <= r < rmax around the axis (zone), as the
// container allows (gf_container_inside_xy). How high: the sphere is dropped
// at (x, y) onto the packing, where it first touches a particle (or the
// floor), then rolls down into a pocket (gf_settle). A plain drop would build
// a top layer at phi ~ 0.3 that the spots never compact (they carry free
// volume up, never away), and the surface would rise pass after pass; rolled
// into pockets the new layer has about the bulk density. Finally it is set
// down where a drop at the pocket first touches, so it overlaps nothing.
//
// The queue is filled as particles exit and emptied at the end of every
// event or fixed step (gf_sim_event), in id order with sim->rng: the result
// is the same in every engine order and on any number of threads.
#include <math.h>

#include "core/alloc.h"
#include "config/where.h"
#include "core/error.h"
#include "spot/sim_internal.h"

bool gf_sim_reinsert_queue(gf_sim *sim, uint32_t i)
{
    if (sim->nreins == sim->reins_cap) {
        size_t cap = sim->reins_cap ? 2 * sim->reins_cap : 64;
        uint32_t *q = gf_realloc(sim->reins, sim->reins_cap * sizeof(uint32_t), cap * sizeof(uint32_t));
        if (!q) return false;
        sim->reins = q;
        sim->reins_cap = cap;
    }
    sim->reins[sim->nreins++] = i;
    return true;
}

// Whether a sphere of radius r may be put back at (x, y) of container `box`.
static bool gf_zone_allowed(const gf_container *box, const gf_engine_defs *ed, double x, double y, double r)
{
    if (!gf_container_inside_xy(box, x, y, r)) return false;
    if (ed->reinsert != GF_REINSERT_ZONE) return true;
    double rho = hypot(x, y), rmax = ed->reinsert_rmax;
    return rho >= ed->reinsert_rmin && (isnan(rmax) || rho < rmax);
}

static bool gf_reinsert_allowed(const gf_sim *sim, double x, double y, double r)
{
    return gf_zone_allowed(&sim->box, &sim->d, x, y, r);
}

gf_status gf_sim_check_config(const gf_config *cfg_in)
{
    if (!cfg_in) return gf_error_set(GF_ERR_PARAM, "gf_sim_check_config: NULL configuration");
    gf_config cfg = *cfg_in;
    gf_status st = gf_config_validate(&cfg);
    if (st != GF_OK) return st;
    gf_engine_defs d;
    gf_config_engine_defs(&cfg, &d);
    if (!d.recirculate || d.reinsert != GF_REINSERT_ZONE) return st;
    // The share of the cross-section where a sphere of radius 1/2 may be put
    // back, on a 256 x 256 lattice over the bounding box: the targets are
    // drawn there by rejection, GF_REINSERT_SAMPLES tries each, so a share
    // that gives fewer than ~50 hits in those tries would fail at some exit
    // (issue 26: an impossible zone was refused at the first exit, after the
    // packing was built).
    const gf_container box = gf_container_make(&cfg);
    double lo[2], hi[2];
    gf_container_bounds_xy(&box, lo, hi);
    const int n = 256;
    long hits = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            hits += gf_zone_allowed(&box, &d, lo[0] + (hi[0] - lo[0]) * (i + 0.5) / n,
                                    lo[1] + (hi[1] - lo[1]) * (j + 0.5) / n, 0.5);
    const double share = (double)hits / ((double)n * n);
    if (share * GF_REINSERT_SAMPLES >= 50.0) return GF_OK;
    gf_config_msg m;
    gf_config_msg_make(&m, &cfg, "run.reinsert_rmin", "run.reinsert_rmax");
    return gf_error_set(GF_ERR_PARAM,
                        "%s%s and %s leave %s of the container's cross-section (%s) for re-inserted particles: "
                        "recirculation could not put them back",
                        m.lead, m.key[0], m.key[1], hits ? "almost nothing" : "nothing",
                        gf_container_profile_radial(&box)
                            ? "a sphere's centre within container.radius - 1/2 of the axis"
                            : "a sphere's centre 1/2 inside the walls, |x| <= "
                              "container.width / 2 - 1/2, |y| <= container.depth / 2 - 1/2");
}

// A target position uniform over the allowed region (rejection from the
// bounding rectangle). False when none was found.
static bool gf_reinsert_target(gf_sim *sim, double r, double *x, double *y)
{
    double lo[2], hi[2];
    gf_container_bounds_xy(&sim->box, lo, hi);
    for (int t = 0; t < GF_REINSERT_SAMPLES; t++) {
        double u = lo[0] + (hi[0] - lo[0]) * gf_rng_uniform(&sim->rng);
        double v = lo[1] + (hi[1] - lo[1]) * gf_rng_uniform(&sim->rng);
        if (gf_reinsert_allowed(sim, u, v, r)) {
            *x = u;
            *y = v;
            return true;
        }
    }
    return false;
}

// Height at which a sphere of radius r dropped at (x, y) first touches a
// particle or the floor: the highest z_j + sqrt((r + r_j)^2 - rho_j^2) over
// the particles within r + r_j horizontally. Layers are scanned from the top
// and the scan stops when no lower layer can reach higher.
static double gf_rest_height(const gf_sim *sim, double x, double y, double r)
{
    const gf_grid *g = &sim->grid;
    const gf_pos *p = sim->p;
    const double reach = r + sim->rmax;
    int x0 = gf_grid_axis(x - reach, g->ox, g->inv_h, g->nx), x1 = gf_grid_axis(x + reach, g->ox, g->inv_h, g->nx);
    int y0 = gf_grid_axis(y - reach, g->oy, g->inv_h, g->ny), y1 = gf_grid_axis(y + reach, g->oy, g->inv_h, g->ny);
    double best = gf_container_floor_z(&sim->box, x, y, r);
    for (int cz = g->nz - 1; cz >= 0; cz--) {
        // The top layer also holds every particle above the grid (clamped).
        if (cz < g->nz - 1 && g->oz + (cz + 1) * g->h + reach <= best) break;
        for (int cy = y0; cy <= y1; cy++)
            for (int cx = x0; cx <= x1; cx++) {
                uint32_t cnt;
                const uint32_t *s = gf_grid_slots(g, cx, cy, cz, &cnt);
                for (uint32_t k = 0; k < cnt; k++) {
                    const gf_pos *q = &p[s[k]];
                    double dx = q->x - x, dy = q->y - y, c = r + q->r, d2 = dx * dx + dy * dy;
                    if (d2 >= c * c) continue;
                    double z = q->z + sqrt(c * c - d2);
                    if (z > best) best = z;
                }
            }
    }
    return best + GF_REINSERT_GAP;
}

// The particles near (x, y, z) a settling sphere of radius r may touch:
// within `reach` horizontally and from `reach` below to r + rmax above.
static size_t gf_settle_gather(const gf_sim *sim, double x, double y, double z, double reach, uint32_t *out, size_t cap)
{
    const gf_grid *g = &sim->grid;
    double c[3] = {x, y, z - 0.5 * reach};
    int lo[3], hi[3];
    gf_grid_range(g, c, 1.5 * reach, lo, hi);
    size_t m = 0;
    for (int cz = lo[2]; cz <= hi[2]; cz++)
        for (int cy = lo[1]; cy <= hi[1]; cy++)
            for (int cx = lo[0]; cx <= hi[0]; cx++) {
                uint32_t cnt;
                const uint32_t *s = gf_grid_slots(g, cx, cy, cz, &cnt);
                for (uint32_t k = 0; k < cnt && m < cap; k++) out[m++] = s[k];
            }
    return m;
}

// Rolls a sphere of radius r resting at (x, y, z) down into a pocket of the
// surface (sequential deposition with rolling, Visscher & Bolsterli 1972):
// repeatedly lowered a little, then pushed out of every fixed neighbour and
// the walls, until it no longer descends. Leaves (x, y) where it settled.
static void gf_settle(gf_sim *sim, double r, double *x, double *y, double *z)
{
    uint32_t *near = sim->w0.cross; // free between events
    const size_t cap = sim->w0.scratch_cap;
    const double reach = r + sim->rmax + GF_SETTLE_REACH;
    double gx = *x, gy = *y, gz = *z;
    size_t m = gf_settle_gather(sim, gx, gy, gz, reach, near, cap);
    int still = 0;
    for (int it = 0; it < GF_SETTLE_ITERS && still < GF_SETTLE_PATIENCE; it++) {
        double px = *x, py = *y, pz = *z - GF_SETTLE_STEP * r;
        for (int sweep = 0; sweep < GF_SETTLE_SWEEPS; sweep++)
            for (size_t k = 0; k < m; k++) {
                const gf_pos *q = &sim->p[near[k]];
                double dx = px - q->x, dy = py - q->y, dz = pz - q->z, s = r + q->r;
                double d2 = dx * dx + dy * dy + dz * dz;
                if (d2 >= s * s || d2 <= 0.0) continue;
                double d = sqrt(d2), f = (s - d) / d;
                px += f * dx;
                py += f * dy;
                pz += f * dz;
            }
        double wx = 0.0, wy = 0.0, wz = 0.0;
        gf_container_push(&sim->box, px, py, pz, r, 1.0, &wx, &wy, &wz);
        px += wx;
        py += wy;
        pz = fmax(pz + wz, gf_container_floor_z(&sim->box, px, py, r));
        // Still: lowered and pushed back to where it was (a pocket). Perched
        // near the top of one sphere it moves little at first, but it moves.
        double mv = fabs(px - *x) + fabs(py - *y) + fabs(pz - *z);
        still = mv < GF_SETTLE_STILL * r ? still + 1 : 0;
        *x = px;
        *y = py;
        *z = pz;
        if (hypot(px - gx, py - gy) + fabs(pz - gz) > GF_SETTLE_REACH * 0.5) { // moved on: new neighbours
            gx = px;
            gy = py;
            gz = pz;
            m = gf_settle_gather(sim, gx, gy, gz, reach, near, cap);
        }
    }
}

// Sets a sphere of radius r that settled at (x, y, *z) down exactly: lifted
// just clear of every particle below its centre (it moves up by what the
// sweeps left of its overlaps). False when that would overlap one above
// (it slipped under an overhang, or the sweeps did not converge).
static bool gf_set_down(gf_sim *sim, double x, double y, double r, double *z)
{
    // Every particle within reach of the centre, straight from the grid (no
    // scratch buffer that could be too small): pass 0 finds the lift, pass 1
    // checks the lifted position against all of them.
    const gf_grid *g = &sim->grid;
    const double reach = r + sim->rmax + GF_SETTLE_LIFT * r + GF_REINSERT_GAP;
    const double c[3] = {x, y, *z};
    int lo[3], hi[3];
    gf_grid_range(g, c, reach, lo, hi);
    double top = fmax(*z, gf_container_floor_z(&sim->box, x, y, r));
    for (int pass = 0; pass < 2; pass++) {
        for (int cz = lo[2]; cz <= hi[2]; cz++)
            for (int cy = lo[1]; cy <= hi[1]; cy++)
                for (int cx = lo[0]; cx <= hi[0]; cx++) {
                    uint32_t cnt;
                    const uint32_t *s = gf_grid_slots(g, cx, cy, cz, &cnt);
                    for (uint32_t k = 0; k < cnt; k++) {
                        const gf_pos *q = &sim->p[s[k]];
                        double dx = q->x - x, dy = q->y - y, d = r + q->r, d2 = dx * dx + dy * dy;
                        if (pass == 0 && d2 < d * d && q->z <= *z) top = fmax(top, q->z + sqrt(d * d - d2));
                        if (pass == 1 && d2 + (q->z - top) * (q->z - top) < d * d) return false;
                    }
                }
        if (pass == 0) {
            top += GF_REINSERT_GAP;
            if (top - *z > GF_SETTLE_LIFT * r) return false;
        }
    }
    *z = top;
    return true;
}

// Puts particle i back: dropped at a target, rolled into a pocket, and set
// down exactly where a drop at the pocket first touches (no overlap).
static gf_status gf_reinsert_one(gf_sim *sim, uint32_t i)
{
    const double r = sim->p[i].r;
    double x = 0.0, y = 0.0, z = 0.0;
    for (int t = 0; t < GF_SETTLE_TARGETS; t++) {
        if (!gf_reinsert_target(sim, r, &x, &y))
            return gf_error_set(GF_ERR_PARAM, "recirculation: no room for a sphere of radius %g in the re-insertion "
                                              "zone (run.reinsert_rmin, run.reinsert_rmax)", r);
        z = gf_rest_height(sim, x, y, r);
        double sx = x, sy = y, sz = z;
        gf_settle(sim, r, &sx, &sy, &sz);
        if (gf_reinsert_allowed(sim, sx, sy, r) && gf_set_down(sim, sx, sy, r, &sz)) {
            x = sx;
            y = sy;
            z = sz;
            break;
        } // rolled out of the zone, or did not settle: another target; after the last, the drop
    }
    const gf_grid *g = &sim->grid;
    if (z > g->oz + g->nz * g->h)
        return gf_error_set(GF_ERR_STATE,
                            "recirculation: the free surface has risen to z = %.3g, above the room the run keeps "
                            "(%.3g): the top of the packing loosens pass after pass. Use the 2009 paper's "
                            "free-surface walk (spot.bias_exponent = 3, spot.weighting = on; docs/pebble-bed.md)",
                            z, g->oz + g->nz * g->h);
    sim->p[i] = (gf_pos){x, y, z, r};
    sim->alive[i] = 1;
    sim->n_alive++;
    gf_hist *h = &sim->hist[i];
    h->pass++;
    h->t_entry = sim->t;
    h->r_entry = hypot(x, y);
    gf_status st = gf_grid_insert(&sim->grid, i, gf_grid_cell(&sim->grid, x, y, z));
    if (st != GF_OK) return st;
    sim->st.particles_reinserted++;
    if (sim->use_nlist) return gf_nlist_refresh(sim, i); // p0 = position, rows redone
    sim->p0[i].x = (float)x;
    sim->p0[i].y = (float)y;
    sim->p0[i].z = (float)z;
    return GF_OK;
}

gf_status gf_sim_reinsert(gf_sim *sim)
{
    // Id order (insertion sort: a step queues a handful).
    uint32_t *q = sim->reins;
    for (size_t a = 1; a < sim->nreins; a++) {
        uint32_t v = q[a];
        size_t b = a;
        while (b > 0 && sim->id[q[b - 1]] > sim->id[v]) {
            q[b] = q[b - 1];
            b--;
        }
        q[b] = v;
    }
    gf_status st = GF_OK;
    for (size_t k = 0; k < sim->nreins && st == GF_OK; k++) st = gf_reinsert_one(sim, q[k]);
    sim->nreins = 0;
    return st;
}
