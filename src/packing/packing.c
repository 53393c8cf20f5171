// SPDX-License-Identifier: MIT
// Simple whole-packing measurements (the storage is io/particles.c).
#include "granflow/packing.h"

#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "geom/celllist.h"
#include "geom/container.h"
#include "granflow/defs.h"
#include "io/packing_frames.h"
#include "packing/blame.h"
#include "packing/layer.h"

int32_t gf_packing_layer_of(double z, double thickness)
{
    // Clamped: a band index beyond int32 (a hair-thin band, a far particle)
    // would be undefined; config ranges keep real runs far from it.
    double b = floor(z / thickness);
    b = b > 1e9 ? 1e9 : (b < -1e9 ? -1e9 : b);
    return 1 + (int32_t)(isnan(b) ? 0.0 : b);
}

void gf_packing_tag_layers(gf_packing *p, double thickness)
{
    for (size_t i = 0; i < p->n; i++) p->layer[i] = gf_packing_layer_of(p->z[i], thickness);
}

double gf_packing_fraction(const gf_packing *p, double x0, double x1, double y0, double y1, double z0,
                           double z1)
{
    double vol = (x1 - x0) * (y1 - y0) * (z1 - z0);
    if (!(vol > 0)) return 0.0;
    double sum = 0.0;
    for (size_t i = 0; i < p->n; i++) {
        if (p->x[i] >= x0 && p->x[i] < x1 && p->y[i] >= y0 && p->y[i] < y1 && p->z[i] >= z0 &&
            p->z[i] < z1)
            sum += 4.0 / 3.0 * 3.14159265358979323846 * p->r[i] * p->r[i] * p->r[i];
    }
    return sum / vol;
}

double gf_packing_min_distance(const gf_packing *p)
{
    if (p->n < 2) return INFINITY;
    double rmax = 0.0;
    for (size_t i = 0; i < p->n; i++) {
        if (!isfinite(p->x[i]) || !isfinite(p->y[i]) || !isfinite(p->z[i])) return NAN; // (no reader lets these through)
        rmax = fmax(rmax, p->r[i]);
    }
    // Cells of side >= one diameter: every pair closer than that is in
    // neighbouring cells, so the result is exact whenever it is below h.
    double h = fmax(2.0 * rmax, 1.0);
    if (!isfinite(h)) return NAN;
    gf_celllist cl = {0};
    if (gf_celllist_fit(&cl, p->x, p->y, p->z, p->n, h) != GF_OK) {
        gf_celllist_free(&cl);
        return NAN;
    }
    double best2 = INFINITY;
    for (int cz = 0; cz < cl.n[2]; cz++)
        for (int cy = 0; cy < cl.n[1]; cy++)
            for (int cx = 0; cx < cl.n[0]; cx++) {
                size_t a = gf_celllist_index(&cl, cx, cy, cz), lo[13], hi[13];
                int ns = gf_celllist_forward(&cl, cx, cy, cz, lo, hi);
                for (size_t u = cl.start[a]; u < cl.start[a + 1]; u++) {
                    size_t i = cl.idx[u];
                    for (int s = -1; s < ns; s++)
                        for (size_t v = s < 0 ? u + 1 : lo[s]; v < (s < 0 ? cl.start[a + 1] : hi[s]); v++) {
                            size_t j = cl.idx[v];
                            double dx = p->x[i] - p->x[j], dy = p->y[i] - p->y[j], dz = p->z[i] - p->z[j];
                            double d2 = dx * dx + dy * dy + dz * dz;
                            if (d2 < best2) best2 = d2;
                        }
                }
            }
    gf_celllist_free(&cl);
    return sqrt(best2);
}

// An imported packing: the lead "FILE:LINE: " of particle `id` and the
// tail " (packing.file, WHERE)"; both empty for a generated one.
static void gf_packing_lead(const gf_config *cfg, int64_t id, char *lead, size_t nlead, char *from, size_t nfrom)
{
    gf_packing_defs pd;
    gf_config_packing_defs(cfg, &pd);
    lead[0] = from[0] = '\0';
    if (!pd.file[0]) return;
    long line = gf_packing_line_of(pd.file, id);
    if (line > 0) snprintf(lead, nlead, "%s:%ld: ", pd.file, line);
    else snprintf(lead, nlead, "%s: ", pd.file);
    char where[GF_PATH_MAX + 32];
    if (gf_config_where(cfg, "packing.file", where, sizeof where) == GF_OK)
        snprintf(from, nfrom, " (packing.file, %s)", where);
}

gf_status gf_packing_blame_highest(const gf_packing *p, const gf_config *cfg, gf_status st)
{
    if (p->n == 0) return st;
    size_t top = 0;
    for (size_t i = 1; i < p->n; i++)
        if (p->z[i] > p->z[top]) top = i;
    char why[1024], lead[GF_PATH_MAX + 32], from[GF_PATH_MAX + 64];
    snprintf(why, sizeof why, "%s", gf_last_error());
    gf_packing_lead(cfg, p->id[top], lead, sizeof lead, from, sizeof from);
    return gf_error_set(st, "%s%s: particle id %lld at (%g, %g, %g) is the highest, and the grid reaches up to it%s",
                        lead, why, (long long)p->id[top], p->x[top], p->y[top], p->z[top], from);
}

gf_status gf_packing_check(const gf_packing *p, const gf_config *cfg)
{
    gf_container box = gf_container_make(cfg);
    for (size_t i = 0; i < p->n; i++) {
        if (gf_container_contains(&box, p->x[i], p->y[i], p->z[i], 0.0, 0.0)) continue;
        // An imported packing: lead with its file and the particle's line there.
        char lead[GF_PATH_MAX + 32], from[GF_PATH_MAX + 64];
        gf_packing_lead(cfg, p->id[i], lead, sizeof lead, from, sizeof from);
        return gf_error_set(GF_ERR_PARAM,
                            "%sparticle id %lld at (%g, %g, %g) is outside the container "
                            "(a %s%s |x| <= %g, |y| <= %g, above the base except over the outlet)%s",
                            lead, (long long)p->id[i], p->x[i], p->y[i], p->z[i], gf_container_name(&box),
                            gf_container_rectangular(&box) ? "" : " within", box.xhi, box.yhi, from);
    }
    return GF_OK;
}

double gf_packing_bulk_fraction(const gf_packing *p, const gf_config *cfg)
{
    double top = 0.0;
    for (size_t i = 0; i < p->n; i++)
        if (p->z[i] > top) top = p->z[i];
    // Away from the walls, where they do not order the layers
    // (gf_container_bulk: 2 d inside flat walls, 3 d inside curved ones).
    gf_container c = gf_container_make(cfg);
    gf_bulk_region b;
    gf_container_bulk(&c, top, &b);
    if (!b.annulus) return gf_packing_fraction(p, b.lo[0], b.hi[0], b.lo[1], b.hi[1], b.lo[2], b.hi[2]);
    double r1 = b.r1, r0 = b.r0, z0 = b.lo[2], z1 = b.hi[2];
    if (!(r1 > r0 && z1 > z0)) return NAN;
    double vol = 0.0;
    for (size_t i = 0; i < p->n; i++) {
        double rho2 = p->x[i] * p->x[i] + p->y[i] * p->y[i];
        if (rho2 < r0 * r0 || rho2 >= r1 * r1 || p->z[i] < z0 || p->z[i] >= z1) continue;
        vol += 4.0 / 3.0 * 3.14159265358979323846 * p->r[i] * p->r[i] * p->r[i];
    }
    return vol / (3.14159265358979323846 * (r1 * r1 - r0 * r0) * (z1 - z0));
}
