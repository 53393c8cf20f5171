// SPDX-License-Identifier: MIT
// The microscopic mechanism: spot() and relax() (2009 paper Sec. 2; thesis
// Sec. 3.4; SPEC 1.3). These are the hot loops of the whole program.
#include <math.h>

#include "core/error.h"
#include "spot/sim_internal.h"

// Distance from v to the interval [a, b] (0 inside).
static inline double gf_gap(double v, double a, double b) { return v < a ? a - v : (v > b ? v - b : 0.0); }

// Collects every grid particle within r_e of c into sim->inside, visiting only
// the cells that the ball reaches (rows culled against the sphere).
static size_t gf_gather(gf_sim *sim, const double c[3])
{
    const gf_grid *g = &sim->grid;
    const gf_pos *restrict p = sim->p;
    uint32_t *restrict inside = sim->inside;
    uint8_t *restrict in_ball = sim->in_ball;
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
                for (uint32_t k = 0; k < cnt; k++) {
                    uint32_t i = s[k];
                    double dx = p[i].x - c[0], dy = p[i].y - c[1], dz = p[i].z - c[2];
                    double d2 = dx * dx + dy * dy + dz * dz;
                    if (d2 < re2) {
                        inside[m] = i;
                        in_ball[m] = d2 < rs2;
                        m++;
                    }
                }
            }
        }
    }
    return m;
}

// Numbers the inside particles (mark = position + 1) so relax() can tell an
// inside neighbour from a shell one with one load.
static void gf_mark_inside(gf_sim *sim, size_t m)
{
    for (size_t k = 0; k < m; k++) sim->mark[sim->inside[k]] = (uint32_t)k + 1;
    sim->scratch_used = m;
}

void gf_spot_unmark(gf_sim *sim)
{
    for (size_t k = 0; k < sim->scratch_used; k++) sim->mark[sim->inside[k]] = 0;
}

long gf_spot_apply(gf_sim *sim, const double c[3], const double u[3])
{
    size_t m = gf_gather(sim, c);
    long moved = 0;
    gf_pos *restrict p = sim->p;
    // SPEC 1.3 spot(c, u, r_s): every particle within r_s of c moves by u.
    for (size_t k = 0; k < m; k++) {
        if (!sim->in_ball[k]) continue;
        uint32_t i = sim->inside[k];
        p[i].x += u[0];
        p[i].y += u[1];
        p[i].z += u[2];
        moved++;
    }
    // Bookkeeping after all moves: exits, cells, rebuild schedule. Exited
    // particles leave the inside list, which relax() then uses as it is.
    size_t keep = 0;
    for (size_t k = 0; k < m; k++) {
        uint32_t i = sim->inside[k];
        if (sim->in_ball[k] && gf_sim_after_move(sim, i) != GF_OK) return -1;
        if (sim->alive[i]) sim->inside[keep++] = i;
    }
    gf_mark_inside(sim, keep);
    sim->st.spot_dz += (double)moved * u[2];
    return moved;
}

gf_status gf_relax_apply(gf_sim *sim, const double c[3])
{
    (void)c; // inside/shell membership was fixed by the gather (marks)
    const size_t m = sim->scratch_used;
    const gf_pos *restrict p = sim->p;
    const uint32_t *restrict start = sim->nl_start, *restrict nl = sim->nl;
    const uint32_t *restrict mark = sim->mark;
    const uint32_t *restrict inside = sim->inside;
    double (*restrict disp)[3] = sim->disp;
    const double alpha = sim->alpha, half = 0.5 * sim->alpha;
    for (size_t k = 0; k < m; k++) disp[k][0] = disp[k][1] = disp[k][2] = 0.0;
    // SPEC 1.3 relax(c, r_e): pairs closer than contact push apart, by alpha
    // delta / 2 each when both are inside r_e, by alpha delta for the inside
    // one when the other is in the fixed shell; walls push by alpha (r - gap).
    // A pair of inside particles is seen once, from its earlier member.
    for (size_t k = 0; k < m; k++) {
        uint32_t i = inside[k];
        const double xi = p[i].x, yi = p[i].y, zi = p[i].z, ri = p[i].r;
        double ax = 0.0, ay = 0.0, az = 0.0;
        for (uint32_t e = start[i], end = start[i + 1]; e < end; e++) {
            uint32_t j = nl[e];
            uint32_t kj = mark[j];
            if (kj != 0 && kj <= k) continue; // inside, and handled already from j's side
            double dx = xi - p[j].x, dy = yi - p[j].y, dz = zi - p[j].z;
            double s = ri + p[j].r;
            double r2 = dx * dx + dy * dy + dz * dz;
            if (r2 >= s * s || r2 <= 0.0) continue;
            double r = sqrt(r2);
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
    gf_spot_unmark(sim);
    double dz_sum = 0.0;
    for (size_t k = 0; k < m; k++) {
        if (disp[k][0] == 0.0 && disp[k][1] == 0.0 && disp[k][2] == 0.0) continue;
        uint32_t i = inside[k];
        dz_sum += disp[k][2];
        sim->p[i].x += disp[k][0];
        sim->p[i].y += disp[k][1];
        sim->p[i].z += disp[k][2];
    }
    sim->st.relax_dz += dz_sum;
    for (size_t k = 0; k < m; k++) {
        if (disp[k][0] == 0.0 && disp[k][1] == 0.0 && disp[k][2] == 0.0) continue;
        gf_status st = gf_sim_after_move(sim, inside[k]);
        if (st != GF_OK) return st;
    }
    return GF_OK;
}

gf_status gf_relax_at(gf_sim *sim, const double c[3])
{
    gf_mark_inside(sim, gf_gather(sim, c));
    return gf_relax_apply(sim, c);
}
