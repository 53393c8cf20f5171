// SPDX-License-Identifier: MIT
// The microscopic mechanism: spot() and relax() (2009 paper Sec. 2; thesis
// Sec. 3.4; SPEC 1.3). These are the hot loops of the whole program.
#include <math.h>
#include <stdint.h>

#include "core/alloc.h"
#include "core/error.h"
#include "spot/sim_internal.h"

// Distance from v to the interval [a, b] (0 inside).
static inline double gf_gap(double v, double a, double b) { return v < a ? a - v : (v > b ? v - b : 0.0); }

// Collects every grid particle within r_e of c into w->inside, visiting only
// the cells that the ball reaches (rows culled against the sphere).
static size_t gf_gather(const gf_sim *sim, gf_work *w, const double c[3])
{
    const gf_grid *g = &sim->grid;
    const gf_pos *restrict p = sim->p;
    uint32_t *restrict inside = w->inside;
    uint8_t *restrict in_ball = w->in_ball;
    const double re2 = sim->re2, rs2 = sim->rs2, h = g->h;
    int lo[3], hi[3];
    gf_grid_range(g, c, sim->re, lo, hi);
    size_t m = 0;
    for (int cz = lo[2]; cz <= hi[2]; cz++) {
        double gz = cz == 0 || cz == g->nz - 1 ? 0.0 : gf_gap(c[2], g->oz + cz * h, g->oz + (cz + 1) * h);
        for (int cy = lo[1]; cy <= hi[1]; cy++) {
            double gy = cy == 0 || cy == g->ny - 1 ? 0.0 : gf_gap(c[1], g->oy + cy * h, g->oy + (cy + 1) * h);
            double rem = re2 - gz * gz - gy * gy;
            if (rem < 0.0) continue;
            double half = sqrt(rem);
            int x0 = gf_grid_axis(c[0] - half, g->ox, g->inv_h, g->nx);
            int x1 = gf_grid_axis(c[0] + half, g->ox, g->inv_h, g->nx);
            size_t row = ((size_t)cz * (size_t)g->ny + (size_t)cy) * (size_t)g->nx;
            for (int cx = x0; cx <= x1; cx++) {
                size_t cell = row + (size_t)cx;
                const uint32_t *s = g->slot + cell * GF_CELL_CAP;
                uint32_t cnt = g->count[cell];
                if (m + cnt > w->scratch_cap) {
                    gf_error_set(GF_ERR_STATE, "more than %zu particle centres within %g d of (%g, %g, %g): the "
                                 "packing overlaps far too much", w->scratch_cap - GF_CELL_CAP, sim->re, c[0], c[1], c[2]);
                    return SIZE_MAX;
                }
                // Branch-free: every candidate is written, and kept by
                // advancing m (~40% are kept: a branch would mispredict).
                for (uint32_t k = 0; k < cnt; k++) {
                    uint32_t i = s[k];
                    double dx = p[i].x - c[0], dy = p[i].y - c[1], dz = p[i].z - c[2];
                    double d2 = dx * dx + dy * dy + dz * dz;
                    inside[m] = i;
                    in_ball[m] = d2 < rs2;
                    m += d2 < re2;
                }
            }
        }
    }
    return m;
}

// Numbers the inside particles (mark = position + 1) so relax() can tell an
// inside neighbour from a shell one with one load, and copies their
// positions (after spot()) next to each other.
static void gf_mark_inside(gf_sim *sim, gf_work *w, size_t m)
{
    const uint32_t *restrict inside = w->inside;
    const gf_pos *restrict p = sim->p;
    gf_pos *restrict ip = w->ip;
    uint32_t *restrict mark = sim->mark;
    for (size_t k = 0; k < m; k++) {
        uint32_t i = inside[k];
        mark[i] = (uint32_t)k + 1;
        ip[k] = p[i];
    }
    w->scratch_used = m;
}

static void gf_clear_marks(gf_sim *sim, gf_work *w)
{
    for (size_t k = 0; k < w->scratch_used; k++) sim->mark[w->inside[k]] = 0;
}

gf_status gf_spot_unmark(gf_sim *sim, gf_work *w)
{
    gf_clear_marks(sim, w);
    return gf_sim_track_moves(sim, w, w->scratch_used, w->in_ball);
}

long gf_spot_apply(gf_sim *sim, gf_work *w, const double c[3], const double u0[3])
{
    size_t m = gf_gather(sim, w, c);
    if (m == SIZE_MAX) return -1;
    long moved = 0;
    gf_pos *p = sim->p; // not restrict: gf_sim_exit_check parks through sim->p
    uint32_t *restrict inside = w->inside;
    uint8_t *restrict in_ball = w->in_ball;
    const gf_engine_defs *ed = &sim->d;
    double u[3] = {u0[0], u0[1], u0[2]};
    // Sec. 3 influence weighting: the spot's free volume is shared by the p
    // particles it reaches (at least min_count of them), off low in the silo.
    if (ed->weighting && c[2] >= ed->weighting_zmin) {
        size_t p_ball = 0;
        for (size_t k = 0; k < m; k++) p_ball += in_ball[k];
        double f = ed->weighting_bulk_count / fmax((double)p_ball, ed->weighting_min_count);
        u[0] *= f;
        u[1] *= f;
        u[2] *= f;
    }
    // Mirror images of c in the side walls its ball crosses (Sec. 4, the reflection procedure).
    double mir[GF_WALL_HITS][3];
    int nmir = ed->walls == GF_WALLS_REFLECT ? sim->box.ops->mirrors(&sim->box, c, sim->rs, mir) : 0;
    // SPEC 1.3 spot(c, u, r_s): every particle within r_s of c moves by u
    // (times S(x) = 1 + the mirrored balls that also reach it, Sec. 4).
    // Particles that fall out leave the inside list, which relax() then uses
    // as it is; in_ball stays aligned with it (it marks the moved ones, whose
    // cells and lists are brought up to date after relax(): gf_sim_track_moves).
    size_t keep = 0;
    double weight = 0.0;
    for (size_t k = 0; k < m; k++) {
        uint32_t i = inside[k];
        uint8_t b = in_ball[k];
        if (b) {
            double sx = 1.0;
            for (int k2 = 0; k2 < nmir; k2++) {
                double dx = p[i].x - mir[k2][0], dy = p[i].y - mir[k2][1], dz = p[i].z - mir[k2][2];
                sx += dx * dx + dy * dy + dz * dz < sim->rs2;
            }
            p[i].x += sx * u[0];
            p[i].y += sx * u[1];
            p[i].z += sx * u[2];
            weight += sx;
            moved++;
            if (gf_sim_exit_check(sim, w, i)) continue;
        }
        inside[keep] = i;
        in_ball[keep] = b;
        keep++;
    }
    gf_mark_inside(sim, w, keep);
    w->st->spot_dz += weight * u[2];
    return moved;
}

size_t gf_ball_count(const gf_sim *sim, const double c[3], double r)
{
    const gf_grid *g = &sim->grid;
    const gf_pos *restrict p = sim->p;
    const double r2 = r * r;
    int lo[3], hi[3];
    gf_grid_range(g, c, r, lo, hi);
    size_t n = 0;
    for (int cz = lo[2]; cz <= hi[2]; cz++)
        for (int cy = lo[1]; cy <= hi[1]; cy++)
            for (int cx = lo[0]; cx <= hi[0]; cx++) {
                uint32_t cnt;
                const uint32_t *s = gf_grid_slots(g, cx, cy, cz, &cnt);
                for (uint32_t k = 0; k < cnt; k++) {
                    double dx = p[s[k]].x - c[0], dy = p[s[k]].y - c[1], dz = p[s[k]].z - c[2];
                    n += dx * dx + dy * dy + dz * dz < r2;
                }
            }
    return n;
}

// Pass 1 of relax() for the row of inside entry k: writes to hit[] its
// neighbours closer than contact, less the inside ones earlier in inside[]
// (kj in 1..k: the pair was handled from their side), and returns their
// number. Branch-free: ~1 entry in 8 overlaps, and a branch per entry would
// mispredict (measured: relax ~4% faster). `mono` (all radii equal, contact
// distance^2 = s2) spares the radius loads.
static inline size_t gf_row_overlaps(const gf_pos *restrict p, const uint32_t *restrict mark,
                                     const uint32_t *restrict row, uint32_t cnt, uint32_t k, double xi, double yi,
                                     double zi, double ri, bool mono, double s2, uint32_t *restrict hit)
{
    size_t nh = 0;
    for (uint32_t e = 0; e < cnt; e++) {
        uint32_t j = row[e], kj = mark[j];
        double dx = xi - p[j].x, dy = yi - p[j].y, dz = zi - p[j].z;
        double r2 = dx * dx + dy * dy + dz * dz;
        if (!mono) {
            double s = ri + p[j].r;
            s2 = s * s;
        }
        hit[nh] = j;
        // kj - 1 wraps to UINT32_MAX for a shell neighbour (kj = 0).
        nh += (size_t)((r2 < s2) & (kj - 1u >= k));
    }
    return nh;
}

gf_status gf_relax_apply(gf_sim *sim, gf_work *w, const double c[3])
{
    (void)c; // inside/shell membership was fixed by the gather (marks)
    const size_t m = w->scratch_used;
    gf_pos *p = sim->p; // not restrict: gf_sim_exit_check parks through sim->p
    const gf_pos *restrict ip = w->ip;
    const uint32_t *restrict mark = sim->mark;
    const uint32_t *restrict inside = w->inside;
    uint8_t *restrict moved = w->in_ball;
    double (*restrict disp)[3] = w->disp;
    const double alpha = sim->alpha, half = 0.5 * sim->alpha;
    for (size_t k = 0; k < m; k++) disp[k][0] = disp[k][1] = disp[k][2] = 0.0;
    // SPEC 1.3 relax(c, r_e): pairs closer than contact push apart, by alpha
    // delta / 2 each when both are inside r_e, by alpha delta for the inside
    // one when the other is in the fixed shell; walls push by alpha (r - gap).
    // A pair of inside particles is seen once, from its earlier member.
    const uint32_t *restrict nl = sim->nl;
    uint32_t *restrict cnts = w->cross; // free until gf_sim_track_moves
    // Row lengths first: a loop of independent loads fetches the rows, cold
    // in memory (spots move in random order all over the silo), in parallel
    // rather than one at a time in the loop below.
    const unsigned shift = sim->nl_shift;
    for (size_t k = 0; k < m; k++) cnts[k] = nl[(size_t)inside[k] << shift];
    const bool mono = sim->contact2 > 0.0;
    const double s2 = sim->contact2;
    for (size_t k = 0; k < m; k++) {
        const uint32_t *row = nl + ((size_t)inside[k] << shift) + 1;
        const uint32_t cnt = cnts[k];
        const double xi = ip[k].x, yi = ip[k].y, zi = ip[k].z, ri = ip[k].r;
        // Pass 1: the overlapping neighbours this row is to push.
        uint32_t hit[GF_NL_CAP_MAX];
        size_t nh = mono ? gf_row_overlaps(p, mark, row, cnt, (uint32_t)k, xi, yi, zi, ri, true, s2, hit)
                         : gf_row_overlaps(p, mark, row, cnt, (uint32_t)k, xi, yi, zi, ri, false, 0.0, hit);
        // Pass 2: their pushes, in row (index) order.
        double ax = 0.0, ay = 0.0, az = 0.0;
        for (size_t h = 0; h < nh; h++) {
            uint32_t j = hit[h];
            uint32_t kj = mark[j];
            double dx = xi - p[j].x, dy = yi - p[j].y, dz = zi - p[j].z;
            double s = ri + p[j].r;
            double r = sqrt(dx * dx + dy * dy + dz * dz);
            if (!(r > 0.0)) continue; // coincident centres: no direction to push along
            double f = (kj ? half : alpha) * (s - r) / r;
            double fx = f * dx, fy = f * dy, fz = f * dz;
            ax += fx;
            ay += fy;
            az += fz;
            if (kj) {
                disp[kj - 1][0] -= fx;
                disp[kj - 1][1] -= fy;
                disp[kj - 1][2] -= fz;
            }
        }
        gf_container_push(&sim->box, xi, yi, zi, ri, alpha, &ax, &ay, &az);
        disp[k][0] += ax;
        disp[k][1] += ay;
        disp[k][2] += az;
    }
    // All displacements are applied together, after every pair was seen.
    gf_clear_marks(sim, w);
    double dz_sum = 0.0;
    for (size_t k = 0; k < m; k++) {
        if (disp[k][0] == 0.0 && disp[k][1] == 0.0 && disp[k][2] == 0.0) continue;
        uint32_t i = inside[k];
        dz_sum += disp[k][2];
        p[i].x += disp[k][0];
        p[i].y += disp[k][1];
        p[i].z += disp[k][2];
        moved[k] = 1;
        if (gf_sim_exit_check(sim, w, i)) moved[k] = 0;
    }
    w->st->relax_dz += dz_sum;
    return gf_sim_track_moves(sim, w, m, moved);
}

gf_status gf_relax_at(gf_sim *sim, gf_work *w, const double c[3])
{
    size_t m = gf_gather(sim, w, c);
    if (m == SIZE_MAX) return GF_ERR_STATE;
    for (size_t k = 0; k < m; k++) w->in_ball[k] = 0; // nothing moved yet
    gf_mark_inside(sim, w, m);
    return gf_relax_apply(sim, w, c);
}

gf_status gf_relax_global(gf_sim *sim)
{
    // Method 3 of the 2009 paper Sec. 5: relax() with no shell, over every
    // particle; each pair seen once (j > i), pushes alpha delta / 2 each.
    const size_t n = sim->n;
    double (*d)[3] = gf_alloc(sizeof(double[3]) * (n ? n : 1));
    if (!d) return gf_error_set(GF_ERR_NOMEM, "out of memory for a global relaxation");
    const gf_pos *p = sim->p;
    const double alpha = sim->alpha, half = 0.5 * sim->alpha;
    for (size_t i = 0; i < n; i++) {
        if (!sim->alive[i]) continue;
        const uint32_t *row = sim->nl + (i << sim->nl_shift);
        for (uint32_t e = 1; e <= row[0]; e++) {
            uint32_t j = row[e];
            if (j <= i) continue;
            double dx = p[i].x - p[j].x, dy = p[i].y - p[j].y, dz = p[i].z - p[j].z;
            double s = p[i].r + p[j].r, r2 = dx * dx + dy * dy + dz * dz;
            if (!(r2 < s * s) || !(r2 > 0.0)) continue;
            double r = sqrt(r2), f = half * (s - r) / r;
            d[i][0] += f * dx;
            d[i][1] += f * dy;
            d[i][2] += f * dz;
            d[j][0] -= f * dx;
            d[j][1] -= f * dy;
            d[j][2] -= f * dz;
        }
        gf_container_push(&sim->box, p[i].x, p[i].y, p[i].z, p[i].r, alpha, &d[i][0], &d[i][1], &d[i][2]);
    }
    gf_status st = GF_OK;
    double dz_sum = 0.0;
    size_t nmoved = 0;
    uint32_t *moved = GF_NEW(uint32_t, n ? n : 1);
    if (!moved) st = gf_error_set(GF_ERR_NOMEM, "out of memory for a global relaxation");
    for (size_t i = 0; st == GF_OK && i < n; i++) {
        if (!sim->alive[i] || (d[i][0] == 0.0 && d[i][1] == 0.0 && d[i][2] == 0.0)) continue;
        sim->p[i].x += d[i][0];
        sim->p[i].y += d[i][1];
        sim->p[i].z += d[i][2];
        dz_sum += d[i][2];
        if (!gf_sim_exit_check(sim, &sim->w0, (uint32_t)i)) moved[nmoved++] = (uint32_t)i;
    }
    sim->st.relax_dz += dz_sum;
    // Cells first, then the lists of those past their skin (as gf_sim_track_moves).
    for (size_t k = 0; st == GF_OK && k < nmoved; k++) {
        uint32_t i = moved[k];
        uint32_t c = gf_grid_cell(&sim->grid, p[i].x, p[i].y, p[i].z);
        if (c != sim->grid.cell_of[i]) {
            gf_grid_remove(&sim->grid, i);
            st = gf_grid_insert(&sim->grid, i, c);
        }
    }
    for (size_t k = 0; st == GF_OK && k < nmoved; k++) {
        uint32_t i = moved[k];
        const gf_pos *q = &p[i];
        const gf_ref *a = &sim->p0[i];
        double dx = q->x - a->x, dy = q->y - a->y, dz = q->z - a->z, lim = a->h - GF_SKIN_SLACK;
        if (dx * dx + dy * dy + dz * dz > lim * lim) st = gf_nlist_refresh(sim, i);
    }
    if (moved) GF_DELETE(moved, n ? n : 1);
    gf_free(d, sizeof(double[3]) * (n ? n : 1));
    sim->st.global_relaxations++;
    return st;
}
