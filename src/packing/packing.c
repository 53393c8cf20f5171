// SPDX-License-Identifier: MIT
// Simple whole-packing measurements (the storage is io/particles.c).
#include "granflow/packing.h"

#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "geom/container.h"

void gf_packing_tag_layers(gf_packing *p, double thickness)
{
    // Clamped: a band index beyond int32 (a hair-thin band, a far particle)
    // would be undefined; config ranges keep real runs far from it.
    for (size_t i = 0; i < p->n; i++) {
        double b = floor(p->z[i] / thickness);
        b = b > 1e9 ? 1e9 : (b < -1e9 ? -1e9 : b);
        p->layer[i] = 1 + (int32_t)(isnan(b) ? 0.0 : b);
    }
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
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    double rmax = 0.0;
    const double *c[3] = {p->x, p->y, p->z};
    for (size_t i = 0; i < p->n; i++) {
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], c[k][i]);
            hi[k] = fmax(hi[k], c[k][i]);
        }
        rmax = fmax(rmax, p->r[i]);
    }
    // Cells of side >= one diameter: every pair closer than that is in
    // neighbouring cells, so the result is exact whenever it is below h.
    // Sparse or far-flung particles get bigger cells, so that there are never
    // many more cells than particles (their count, in doubles, cannot wrap).
    double h = fmax(2.0 * rmax, 1.0), fc[3];
    for (int k = 0; k < 3; k++)
        if (!isfinite(hi[k] - lo[k]) || !isfinite(h)) return NAN; // (no reader lets these through)
    for (;;) {
        for (int k = 0; k < 3; k++) fc[k] = floor((hi[k] - lo[k]) / h) + 1.0;
        if (fc[0] * fc[1] * fc[2] <= 2.0 * (double)p->n + 64.0) break;
        h *= 1.5;
    }
    size_t nc[3], ncell = 1;
    for (int k = 0; k < 3; k++) {
        nc[k] = (size_t)fc[k];
        ncell *= nc[k];
    }
    size_t *head = GF_NEW(size_t, ncell + 1), *order = GF_NEW(size_t, p->n), *cell = GF_NEW(size_t, p->n);
    if (!head || !order || !cell) {
        GF_DELETE(head, ncell + 1);
        GF_DELETE(order, p->n);
        GF_DELETE(cell, p->n);
        return NAN;
    }
    size_t ci[3];
    for (size_t i = 0; i < p->n; i++) {
        for (int k = 0; k < 3; k++) {
            size_t v = (size_t)((c[k][i] - lo[k]) / h);
            ci[k] = v >= nc[k] ? nc[k] - 1 : v;
        }
        cell[i] = (ci[2] * nc[1] + ci[1]) * nc[0] + ci[0];
        head[cell[i] + 1]++;
    }
    for (size_t k = 0; k < ncell; k++) head[k + 1] += head[k];
    for (size_t i = 0; i < p->n; i++) order[head[cell[i]]++] = i;
    for (size_t k = ncell; k > 0; k--) head[k] = head[k - 1];
    head[0] = 0;
    double best2 = INFINITY;
    for (size_t cz = 0; cz < nc[2]; cz++)
        for (size_t cy = 0; cy < nc[1]; cy++)
            for (size_t cx = 0; cx < nc[0]; cx++) {
                size_t a = (cz * nc[1] + cy) * nc[0] + cx;
                for (int dz = -1; dz <= 1; dz++)
                    for (int dy = -1; dy <= 1; dy++)
                        for (int dx = -1; dx <= 1; dx++) {
                            long x = (long)cx + dx, y = (long)cy + dy, z = (long)cz + dz;
                            if (x < 0 || y < 0 || z < 0 || x >= (long)nc[0] || y >= (long)nc[1] ||
                                z >= (long)nc[2])
                                continue;
                            size_t b = ((size_t)z * nc[1] + (size_t)y) * nc[0] + (size_t)x;
                            if (b < a) continue;
                            for (size_t u = head[a]; u < head[a + 1]; u++)
                                for (size_t v = (a == b ? u + 1 : head[b]); v < head[b + 1]; v++) {
                                    size_t i = order[u], j = order[v];
                                    double ddx = p->x[i] - p->x[j], ddy = p->y[i] - p->y[j],
                                           ddz = p->z[i] - p->z[j];
                                    double d2 = ddx * ddx + ddy * ddy + ddz * ddz;
                                    if (d2 < best2) best2 = d2;
                                }
                        }
            }
    GF_DELETE(head, ncell + 1);
    GF_DELETE(order, p->n);
    GF_DELETE(cell, p->n);
    return sqrt(best2);
}

gf_status gf_packing_check(const gf_packing *p, const gf_config *cfg)
{
    gf_container box = gf_container_make(cfg);
    for (size_t i = 0; i < p->n; i++) {
        if (!gf_container_contains(&box, p->x[i], p->y[i], p->z[i], 0.0, 0.0))
            return gf_error_set(GF_ERR_PARAM,
                                "particle id %lld at (%g, %g, %g) is outside the container "
                                "(%s |x| <= %g, |y| <= %g, above the base except over the outlet)",
                                (long long)p->id[i], p->x[i], p->y[i], p->z[i],
                                box.kind == GF_SHAPE_CYLINDER ? "a cylinder within" : "a box", box.xhi, box.yhi);
    }
    return GF_OK;
}

double gf_packing_bulk_fraction(const gf_packing *p, const gf_config *cfg)
{
    double top = 0.0;
    for (size_t i = 0; i < p->n; i++)
        if (p->z[i] > top) top = p->z[i];
    if (cfg->container_shape != GF_SHAPE_CYLINDER) {
        double hw = 0.5 * cfg->container_width, hd = 0.5 * cfg->container_depth;
        return gf_packing_fraction(p, -hw + 2, hw - 2, -hd + 2, hd - 2, 2.0, top - 3.0);
    }
    // A cylinder: the annulus 3 d inside the wall (and outside a column).
    // Curved walls order the first layers: the ring 2-3 d from the wall is
    // denser than the bulk by ~0.05 (docs/geometry.md), so it stays out.
    gf_container c = gf_container_make(cfg);
    double r1 = c.radius - 3.0, r0 = c.r_in > 0.0 ? c.r_in + 3.0 : 0.0, z0 = c.z_top + 2.0, z1 = top - 3.0;
    if (!(r1 > r0 && z1 > z0)) return NAN;
    double vol = 0.0;
    for (size_t i = 0; i < p->n; i++) {
        double rho2 = p->x[i] * p->x[i] + p->y[i] * p->y[i];
        if (rho2 < r0 * r0 || rho2 >= r1 * r1 || p->z[i] < z0 || p->z[i] >= z1) continue;
        vol += 4.0 / 3.0 * 3.14159265358979323846 * p->r[i] * p->r[i] * p->r[i];
    }
    return vol / (3.14159265358979323846 * (r1 * r1 - r0 * r0) * (z1 - z0));
}
