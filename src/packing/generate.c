// SPDX-License-Identifier: MIT
// Random initial packing (SPEC 1.2): soft spheres placed at random in a tall
// column, squeezed uniaxially towards the base while Jacobi sweeps push
// overlapping pairs apart, then relaxed until no overlap is left. The method,
// its parameters and the packings it makes are described in docs/packing.md.
#include "granflow/packing.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "core/rng.h"

// Parameters of the method (docs/packing.md says why each has its value).
#ifndef GF_GEN_PHI_START
#define GF_GEN_PHI_START 0.30
#endif
#define GF_GEN_PHI_START_X    // nominal packing fraction of the random start
#ifndef GF_GEN_PHI_SIDE
#define GF_GEN_PHI_SIDE 0.6
#endif
#ifndef GF_GEN_LOAD
#define GF_GEN_LOAD 0.01
#endif
#ifndef GF_GEN_EXPAND
#define GF_GEN_EXPAND 0.05
#endif
#ifndef GF_GEN_EXPMAX
#define GF_GEN_EXPMAX 1.0
#endif
#ifndef GF_GEN_TAPS
#define GF_GEN_TAPS 0
#endif
#define GF_GEN_TAP 0.02
#define GF_GEN_TAP_SWEEPS 20
#ifndef GF_GEN_NOISE
#define GF_GEN_NOISE 0.0
#endif
#ifndef GF_GEN_STALL
#define GF_GEN_STALL 200
#endif
#ifndef GF_GEN_STALL_GAIN
#define GF_GEN_STALL_GAIN 0.002
#endif
#ifndef GF_GEN_PHI_STOP
#define GF_GEN_PHI_STOP 0.625
#endif
#define GF_GEN_PHI_STOP_X    // bulk packing fraction at which squeezing stops
#ifndef GF_GEN_STRAIN
#define GF_GEN_STRAIN 4.0e-3
#endif
#define GF_GEN_STRAIN_X     // largest compressive strain of the column per sweep
#define GF_GEN_LOAD_X         // overlap per particle at which squeezing stalls
#define GF_GEN_EXPAND_X        // final relaxation: strain per unit overlap per particle
#ifndef GF_GEN_ALPHA
#define GF_GEN_ALPHA 0.8
#endif
#define GF_GEN_ALPHA_X         // fraction of an overlap removed per sweep
#define GF_GEN_SKIN 0.3          // Verlet-list skin, d
#define GF_GEN_TOL 0.005         // final largest overlap: centre distance > 1 - TOL
#ifndef GF_GEN_PRE_TOL
#define GF_GEN_PRE_TOL 0.2
#endif
#define GF_GEN_PRE_TOL_X       // largest overlap before squeezing starts
#define GF_GEN_MEASURE 10        // sweeps between two bulk-fraction measurements
#define GF_GEN_MAX_SWEEPS 200000 // safety net against a relaxation that never ends
#define GF_GEN_STREAM 0x7061636b696e67ull // "packing": the RNG stream of this module
#define GF_GEN_MAX_N 2000000000ll         // neighbour indices are 32-bit
// Acceptance checks of the result (SPEC 1.2).
#define GF_GEN_MIN_PAIR 0.99
#define GF_GEN_WALL 0.5

#ifdef GF_GEN_TRACE
static long gf_gen_builds;
#endif
static const double gf_gen_pi = 3.14159265358979323846;

// Working state of one generation. Particles are kept in cell order (re-sorted
// at every neighbour-list build) so that a sweep walks memory almost linearly.
typedef struct gf_gen {
    size_t n;
    double *x, *y, *z;    // centres
    double *ux, *uy, *uz; // per-sweep displacement sums; scratch during a build
    double *rx, *ry, *rz; // centres at the last build, z squeezed with the column
    size_t *start;        // CSR row starts of the half neighbour list, n + 1
    uint32_t *nbr;        // neighbours j of i in cell order (each pair once)
    size_t nbr_cap;
    size_t *cell_start; // counting-sort scratch, ncell_cap + 1
    size_t ncell_cap;
    uint32_t *cell;  // cell of each particle during a build
    double zlo;           // lowest centre height
    double zhi;           // highest centre height (a lid), or +inf
    double width, depth;  // current side walls: +-width/2, +-depth/2 (they close in)
    double width_final, depth_final;
    double squeeze; // product of (1 - strain) since the last build
} gf_gen;

static void gf_gen_release(gf_gen *g)
{
    size_t n = g->n;
    GF_DELETE(g->x, n);
    GF_DELETE(g->y, n);
    GF_DELETE(g->z, n);
    GF_DELETE(g->ux, n);
    GF_DELETE(g->uy, n);
    GF_DELETE(g->uz, n);
    GF_DELETE(g->rx, n);
    GF_DELETE(g->ry, n);
    GF_DELETE(g->rz, n);
    GF_DELETE(g->start, n + 1);
    GF_DELETE(g->nbr, g->nbr_cap);
    GF_DELETE(g->cell_start, g->ncell_cap + 1);
    GF_DELETE(g->cell, n);
}

static gf_status gf_gen_init(gf_gen *g, size_t n)
{
    g->n = n;
    g->x = GF_NEW(double, n);
    g->y = GF_NEW(double, n);
    g->z = GF_NEW(double, n);
    g->ux = GF_NEW(double, n);
    g->uy = GF_NEW(double, n);
    g->uz = GF_NEW(double, n);
    g->rx = GF_NEW(double, n);
    g->ry = GF_NEW(double, n);
    g->rz = GF_NEW(double, n);
    g->start = GF_NEW(size_t, n + 1);
    g->cell = GF_NEW(uint32_t, n);
    g->nbr_cap = 8 * n;
    g->nbr = GF_NEW(uint32_t, g->nbr_cap);
    if (!g->x || !g->y || !g->z || !g->ux || !g->uy || !g->uz || !g->rx || !g->ry || !g->rz ||
        !g->start || !g->cell || !g->nbr)
        return gf_error_set(GF_ERR_NOMEM, "packing: out of memory for %zu particles", n);
    return GF_OK;
}

// Sorts the particles into a cell grid of side >= 1 + skin, re-orders them by
// cell and builds the half neighbour list (pairs closer than 1 + skin).
static gf_status gf_gen_build(gf_gen *g)
{
    size_t n = g->n;
    double ztop = g->zlo;
    for (size_t i = 0; i < n; i++) ztop = fmax(ztop, g->z[i]);
    const double cut = 1.0 + GF_GEN_SKIN;
    // Cells of side h >= cut; a sparse tall column gets bigger cells so the
    // grid never has many more cells than particles.
    double h = cut;
    size_t nx, ny, nz;
    for (;;) {
        nx = (size_t)fmax(1.0, floor(g->width / h));
        ny = (size_t)fmax(1.0, floor(g->depth / h));
        nz = (size_t)floor((ztop + 0.5) / h) + 1;
        if ((double)nx * (double)ny * (double)nz <= 2.0 * (double)n + 64.0) break;
        h *= 1.25;
    }
    size_t ncell = nx * ny * nz;
    if (ncell > g->ncell_cap) {
        GF_DELETE(g->cell_start, g->ncell_cap + 1);
        g->ncell_cap = ncell + ncell / 2;
        g->cell_start = GF_NEW(size_t, g->ncell_cap + 1);
        if (!g->cell_start) {
            g->ncell_cap = 0;
            return gf_error_set(GF_ERR_NOMEM, "packing: out of memory for %zu cells", ncell);
        }
    }
    size_t *cs = g->cell_start;
    memset(cs, 0, sizeof *cs * (ncell + 1));
    const double fx = (double)nx / g->width, fy = (double)ny / g->depth, fz = 1.0 / h;
    const double hw = 0.5 * g->width, hd = 0.5 * g->depth;
    for (size_t i = 0; i < n; i++) {
        size_t ix = (size_t)((g->x[i] + hw) * fx), iy = (size_t)((g->y[i] + hd) * fy),
               iz = (size_t)(g->z[i] * fz);
        if (ix >= nx) ix = nx - 1;
        if (iy >= ny) iy = ny - 1;
        if (iz >= nz) iz = nz - 1;
        g->cell[i] = (uint32_t)((iz * ny + iy) * nx + ix);
        cs[g->cell[i] + 1]++;
    }
    for (size_t c = 0; c < ncell; c++) cs[c + 1] += cs[c];
    // Counting sort (stable: equal cells keep their order) into the scratch
    // arrays, then swap them in. cs[c] ends as the end of cell c.
    for (size_t i = 0; i < n; i++) {
        size_t k = cs[g->cell[i]]++;
        g->ux[k] = g->x[i];
        g->uy[k] = g->y[i];
        g->uz[k] = g->z[i];
    }
    for (size_t c = ncell; c > 0; c--) cs[c] = cs[c - 1];
    cs[0] = 0;
    double *t;
    t = g->x, g->x = g->ux, g->ux = t;
    t = g->y, g->y = g->uy, g->uy = t;
    t = g->z, g->z = g->uz, g->uz = t;
    memcpy(g->rx, g->x, sizeof *g->x * n);
    memcpy(g->ry, g->y, sizeof *g->y * n);
    memcpy(g->rz, g->z, sizeof *g->z * n);
    g->squeeze = 1.0;

    // Half stencil: the cell itself (j > i) and its 13 "forward" neighbours.
    const double cut2 = cut * cut;
    size_t m = 0;
    for (size_t iz = 0; iz < nz; iz++)
        for (size_t iy = 0; iy < ny; iy++)
            for (size_t ix = 0; ix < nx; ix++) {
                size_t c = (iz * ny + iy) * nx + ix;
                size_t lo[14], hi[14];
                int ns = 0;
                for (int dz = 0; dz <= 1; dz++)
                    for (int dy = (dz ? -1 : 0); dy <= 1; dy++)
                        for (int dx = (dz || dy ? -1 : 1); dx <= 1; dx++) {
                            long jx = (long)ix + dx, jy = (long)iy + dy, jz = (long)iz + dz;
                            if (jx < 0 || jy < 0 || jx >= (long)nx || jy >= (long)ny ||
                                jz >= (long)nz)
                                continue;
                            size_t b = ((size_t)jz * ny + (size_t)jy) * nx + (size_t)jx;
                            if (cs[b] == cs[b + 1]) continue;
                            lo[ns] = cs[b];
                            hi[ns] = cs[b + 1];
                            ns++;
                        }
                for (size_t i = cs[c]; i < cs[c + 1]; i++) {
                    g->start[i] = m;
                    // Room for every candidate of this particle.
                    size_t need = m + (cs[c + 1] - i);
                    for (int s = 0; s < ns; s++) need += hi[s] - lo[s];
                    if (need > g->nbr_cap) {
                        size_t cap = need + need / 2 + 1024;
                        uint32_t *q = gf_realloc(g->nbr, sizeof *q * g->nbr_cap, sizeof *q * cap);
                        if (!q)
                            return gf_error_set(GF_ERR_NOMEM,
                                                "packing: out of memory for the neighbour list");
                        g->nbr = q;
                        g->nbr_cap = cap;
                    }
                    const double xi = g->x[i], yi = g->y[i], zi = g->z[i];
                    for (int s = -1; s < ns; s++) {
                        size_t j0 = s < 0 ? i + 1 : lo[s], j1 = s < 0 ? cs[c + 1] : hi[s];
                        for (size_t j = j0; j < j1; j++) {
                            double dx = xi - g->x[j], dy = yi - g->y[j], dz = zi - g->z[j];
                            if (dx * dx + dy * dy + dz * dz < cut2) g->nbr[m++] = (uint32_t)j;
                        }
                    }
                }
            }
    g->start[n] = m;
#ifdef GF_GEN_TRACE
    gf_gen_builds++;
#endif
    return GF_OK;
}

// max(s, 0) without a branch (compilers turn ?: and fmax into one here):
// clears every bit of a value whose sign bit is set.
static inline double gf_gen_positive(double s)
{
    uint64_t b;
    memcpy(&b, &s, sizeof b);
    b &= (b >> 63) - 1u;
    memcpy(&s, &b, sizeof s);
    return s;
}

// One Jacobi sweep, first half: sums for every particle the pushes of its
// overlapping neighbours (each moves by alpha * overlap / 2 along the line of
// centres) into ux, uy, uz. Returns the largest overlap 1 - r.
static double gf_gen_push(gf_gen *g, double *mean)
{
    size_t n = g->n;
    const double *restrict x = g->x, *restrict y = g->y, *restrict z = g->z;
    double *restrict ux = g->ux, *restrict uy = g->uy, *restrict uz = g->uz;
    const size_t *restrict start = g->start;
    const uint32_t *restrict nbr = g->nbr;
    memset(ux, 0, sizeof *ux * n);
    memset(uy, 0, sizeof *uy * n);
    memset(uz, 0, sizeof *uz * n);
    const double half = 0.5 * GF_GEN_ALPHA;
    double worst = 0.0, sum = 0.0;
    for (size_t i = 0; i < n; i++) {
        const double xi = x[i], yi = y[i], zi = z[i];
        double ax = 0.0, ay = 0.0, az = 0.0;
        for (size_t k = start[i]; k < start[i + 1]; k++) {
            size_t j = nbr[k];
            double dx = xi - x[j], dy = yi - y[j], dz = zi - z[j];
            // Branch-free (a mispredicted branch on every other pair costs
            // more than the arithmetic): with s = 1 - r^2 (0 for pairs that do
            // not touch), (1 - r) / r = s/2 + 3s^2/8 + 5s^3/16 + 35s^4/128 + ...
            // The truncated series has relative error < 1e-5 for overlaps
            // below 0.05, only ever pushes less than the exact rule for big
            // ones, and stays finite when two centres coincide.
            double s = 1.0 - (dx * dx + dy * dy + dz * dz);
            s = gf_gen_positive(s);
            worst = s > worst ? s : worst;
            sum += s;
            double f = half * s * (0.5 + s * (0.375 + s * (0.3125 + s * 0.2734375)));
            if (s > 0.5) { // r < 0.71: rare, so this branch is well predicted
                double r = sqrt(1.0 - s);
                if (r < 1e-9) { // coincident centres (walls can clamp two into a corner)
                    dx = 0.0;
                    dy = 0.0;
                    dz = r = 1e-9;
                }
                f = half * (1.0 - r) / r;
            }
            ax += f * dx;
            ay += f * dy;
            az += f * dz;
            ux[j] -= f * dx;
            uy[j] -= f * dy;
            uz[j] -= f * dz;
        }
        ux[i] += ax;
        uy[i] += ay;
        uz[i] += az;
    }
    *mean = 0.5 * sum / (double)n; // sum of s/2 ~ sum of overlaps
    return 1.0 - sqrt(1.0 - fmin(worst, 1.0));
}

// Second half: applies the pushes, squeezes the column by `strain` towards the
// base, puts particles back inside the walls. Returns the largest squared
// non-affine displacement since the last build.
static double gf_gen_move(gf_gen *g, double strain, double noise, gf_rng *rng)
{
    size_t n = g->n;
    const double sz = 1.0 - strain, zlo = g->zlo;
    // The side walls close in with the same strain until they reach their
    // final place (and never move out again).
    double w = g->width, d = g->depth;
    if (strain > 0.0) {
        w = fmax(w * sz, g->width_final);
        d = fmax(d * sz, g->depth_final);
    }
    const double sx = w / g->width, sy = d / g->depth;
    g->width = w;
    g->depth = d;
    const double xhi = 0.5 * w - 0.5, xlo = -xhi, yhi = 0.5 * d - 0.5, ylo = -yhi;
    double worst = 0.0;
    for (size_t i = 0; i < n; i++) {
        double x = g->x[i] + g->ux[i], y = g->y[i] + g->uy[i], z = g->z[i] + g->uz[i];
        if (noise > 0.0) {
            x += noise * (2.0 * gf_rng_uniform(rng) - 1.0);
            y += noise * (2.0 * gf_rng_uniform(rng) - 1.0);
            z += noise * (2.0 * gf_rng_uniform(rng) - 1.0);
        }
        x *= sx;
        y *= sy;
        z = zlo + (z - zlo) * sz;
        x = x > xlo ? x : xlo;
        x = x < xhi ? x : xhi;
        y = y > ylo ? y : ylo;
        y = y < yhi ? y : yhi;
        z = z > zlo ? z : zlo;
        z = z < g->zhi ? z : g->zhi;
        g->x[i] = x;
        g->y[i] = y;
        g->z[i] = z;
        double rx = g->rx[i] * sx, ry = g->ry[i] * sy, rz = zlo + (g->rz[i] - zlo) * sz;
        g->rx[i] = rx;
        g->ry[i] = ry;
        g->rz[i] = rz;
        double dx = x - rx, dy = y - ry, dz = z - rz;
        double d2 = dx * dx + dy * dy + dz * dz;
        worst = d2 > worst ? d2 : worst;
    }
    g->squeeze *= fmin(fmin(sx, sy), sz);
    return worst;
}

// The list still holds every pair closer than 1 while squeeze * (1 + skin)
// - 2 * (largest non-affine displacement) > 1 (the squeeze shortens every
// pair vector by at most the factor `squeeze`).
static gf_status gf_gen_keep_list(gf_gen *g, double disp2)
{
    if (fmin(g->squeeze, 1.0) * (1.0 + GF_GEN_SKIN) - 2.0 * sqrt(disp2) > 1.0 + 1e-9) return GF_OK;
    return gf_gen_build(g);
}

// Packing fraction of the bulk: away from the side walls, the base and the
// top. Falls back to the whole column when that region holds few particles.
static double gf_gen_bulk_fraction(const gf_gen *g)
{
    size_t n = g->n;
    double ztop = g->zlo;
    for (size_t i = 0; i < n; i++) ztop = fmax(ztop, g->z[i]);
    double bx = 0.5 * g->width_final - 2.0, by = 0.5 * g->depth_final - 1.5, z0 = 2.0,
           z1 = ztop - 3.0;
    double vol = 4.0 * bx * by * (z1 - z0);
    size_t count = 0;
    if (bx > 0 && by > 0 && z1 > z0) {
        for (size_t i = 0; i < n; i++)
            count += fabs(g->x[i]) < bx && fabs(g->y[i]) < by && g->z[i] >= z0 && g->z[i] < z1;
    }
    if (count >= 100) return (double)count * gf_gen_pi / 6.0 / vol;
    return (double)n * gf_gen_pi / 6.0 / (g->width_final * g->depth_final * (ztop + 0.5));
}

// Runs the whole method on g (positions are placed here). Returns the status.
static gf_status gf_gen_run(gf_gen *g, uint64_t seed)
{
    size_t n = g->n;
    // Random start: uniform in the footprint, the column as tall as a packing
    // of fraction PHI_START would be. Overlaps are allowed.
    double c = cbrt(GF_GEN_PHI_SIDE / GF_GEN_PHI_START);
    g->width = c * g->width_final;
    g->depth = c * g->depth_final;
    double height = (double)n * gf_gen_pi / 6.0 / (g->width * g->depth * GF_GEN_PHI_START);
    if (height < 1.0) height = 1.0;
#ifdef GF_GEN_LID
    g->zhi = g->zlo + height;
#else
    g->zhi = INFINITY;
#endif
    const double xhi = 0.5 * g->width - 0.5, yhi = 0.5 * g->depth - 0.5;
    gf_rng rng;
    gf_rng_seed(&rng, seed, GF_GEN_STREAM);
    for (size_t i = 0; i < n; i++) {
        g->x[i] = xhi * (2.0 * gf_rng_uniform(&rng) - 1.0);
        g->y[i] = yhi * (2.0 * gf_rng_uniform(&rng) - 1.0);
        g->z[i] = g->zlo + height * gf_rng_uniform(&rng);
    }
    gf_status st = gf_gen_build(g);
    if (st != GF_OK) return st;

    long sweeps = 0;
    double total, floor_squeeze;
    // 1. Take the worst random overlaps out before squeezing.
    double mean = 0.0;
    while (gf_gen_push(g, &mean) > GF_GEN_PRE_TOL && sweeps < GF_GEN_MAX_SWEEPS) {
        sweeps++;
        if ((st = gf_gen_keep_list(g, gf_gen_move(g, 0.0, 0.0, &rng))) != GF_OK) return st;
    }
    for (int cycle = 0; cycle <= GF_GEN_TAPS; cycle++) {
    if (cycle > 0) {
        for (int t = 0; t < GF_GEN_TAP_SWEEPS; t++, sweeps++) {
            gf_gen_push(g, &mean);
            if ((st = gf_gen_keep_list(g, gf_gen_move(g, -GF_GEN_TAP / GF_GEN_TAP_SWEEPS, 0.0, &rng))) != GF_OK) return st;
        }
    }
    // 2. Squeeze the column until the bulk reaches PHI_STOP (or the column
    // has been squeezed well past what that needs: a very shallow bed). The
    // strain rate falls as the overlap per particle approaches LOAD, so the
    // squeeze never outruns the relaxation near jamming.
    total = 1.0, floor_squeeze = 0.5 * GF_GEN_PHI_START / GF_GEN_PHI_STOP;
    double phi_last = 0.0;
    total = 1.0;
    for (long k = 0; total > floor_squeeze && sweeps < GF_GEN_MAX_SWEEPS; k++, sweeps++) {
        if (g->width == g->width_final && g->depth == g->depth_final) {
            if (k % GF_GEN_MEASURE == 0) {
                double phi = gf_gen_bulk_fraction(g);
                if (phi >= GF_GEN_PHI_STOP) break;
                if (k % GF_GEN_STALL == 0) {
                    // Jammed: the bulk no longer gets denser.
                    if (phi < phi_last + GF_GEN_STALL_GAIN) break;
                    phi_last = phi;
                }
            }
        }
        double w = gf_gen_push(g, &mean);
        double strain = GF_GEN_STRAIN * fmax(-GF_GEN_EXPMAX, 1.0 - mean / GF_GEN_LOAD);
#ifdef GF_GEN_TRACE
        if (k % 100000 == 0) GF_GEN_TRACE("squeeze k %ld worst %.4f mean %.5f strain %.5f phi %.4f", k, w, mean, strain, gf_gen_bulk_fraction(g));
#endif
        (void)w;
        if ((st = gf_gen_keep_list(g, gf_gen_move(g, strain, GF_GEN_NOISE, &rng))) != GF_OK) return st;
        total *= 1.0 - strain;
    }
#ifdef GF_GEN_TRACE
    GF_GEN_TRACE("cycle %d: sweeps %ld phi %.4f", cycle, sweeps, gf_gen_bulk_fraction(g));
#endif
    }
#ifdef GF_GEN_TRACE
    GF_GEN_TRACE("after squeeze: sweeps %ld phi %.4f", sweeps, gf_gen_bulk_fraction(g));
#endif
    // 3. Relax until the largest overlap is below TOL, letting the column
    // expand in proportion to what overlap is left.
    for (;;) {
        double worst = gf_gen_push(g, &mean);
#ifdef GF_GEN_TRACE
        if (sweeps % 100 == 0) GF_GEN_TRACE("relax %ld worst %.4f mean %.5f phi %.4f", sweeps, worst, mean, gf_gen_bulk_fraction(g));
#endif
        if (worst < GF_GEN_TOL) break;
        if (++sweeps >= GF_GEN_MAX_SWEEPS)
            return gf_error_set(GF_ERR_STATE,
                                "packing: relaxation did not converge (largest overlap %.3g after "
                                "%ld sweeps)",
                                worst, sweeps);
        if ((st = gf_gen_keep_list(g, gf_gen_move(g, -GF_GEN_EXPAND * mean, 0.0, &rng))) != GF_OK) return st;
    }
#ifdef GF_GEN_TRACE
    GF_GEN_TRACE("done: sweeps %ld phi %.4f", sweeps, gf_gen_bulk_fraction(g));
#endif
    return GF_OK;
}

typedef struct gf_gen_key {
    double z;
    size_t i;
} gf_gen_key;

static int gf_gen_key_cmp(const void *a, const void *b)
{
    const gf_gen_key *p = a, *q = b;
    if (p->z != q->z) return p->z < q->z ? -1 : 1;
    return (p->i > q->i) - (p->i < q->i);
}

// Copies the particles with z <= zmax into `out`, sorted by height, ids 1..n.
static gf_status gf_gen_emit(const gf_gen *g, double zmax, const gf_config *cfg, gf_packing *out)
{
    size_t n = g->n, m = 0;
    gf_gen_key *key = GF_NEW(gf_gen_key, n);
    if (!key) return gf_error_set(GF_ERR_NOMEM, "packing: out of memory for %zu particles", n);
    for (size_t i = 0; i < n; i++)
        if (g->z[i] <= zmax) key[m++] = (gf_gen_key){g->z[i], i};
    qsort(key, m, sizeof *key, gf_gen_key_cmp);
    out->n = 0;
    gf_status st = gf_packing_reserve(out, m);
    if (st == GF_OK) {
        for (size_t k = 0; k < m; k++) {
            size_t i = key[k].i;
            out->id[k] = (int64_t)k + 1;
            out->x[k] = g->x[i];
            out->y[k] = g->y[i];
            out->z[k] = g->z[i];
            out->r[k] = 0.5;
        }
        out->n = m;
        gf_packing_tag_layers(out, cfg->packing_layer_thickness);
    }
    GF_DELETE(key, n);
    return st;
}

// Final acceptance check: the promises of SPEC 1.2 hold, or this is a bug.
static gf_status gf_gen_check(const gf_packing *p, double width, double depth)
{
    double hw = 0.5 * width - GF_GEN_WALL, hd = 0.5 * depth - GF_GEN_WALL;
    for (size_t i = 0; i < p->n; i++) {
        if (!(fabs(p->x[i]) <= hw && fabs(p->y[i]) <= hd && p->z[i] >= GF_GEN_WALL))
            return gf_error_set(GF_ERR_STATE,
                                "packing: particle %zu at (%g, %g, %g) is closer than %g to a wall",
                                i + 1, p->x[i], p->y[i], p->z[i], GF_GEN_WALL);
    }
    double dmin = gf_packing_min_distance(p);
    if (isnan(dmin)) return gf_error_set(GF_ERR_NOMEM, "packing: out of memory checking distances");
    if (dmin < GF_GEN_MIN_PAIR)
        return gf_error_set(GF_ERR_STATE, "packing: two centres are %g apart (< %g)", dmin,
                            GF_GEN_MIN_PAIR);
    return GF_OK;
}

gf_status gf_packing_generate(const gf_config *cfg, gf_packing *out)
{
    if (!cfg || !out) return gf_error_set(GF_ERR_PARAM, "packing: NULL argument");
    out->n = 0;
    double width = cfg->container_width, depth = cfg->container_depth;
    double fill = cfg->packing_fill_height;
    if (!(width >= 1.0 && depth >= 1.0 && isfinite(width) && isfinite(depth)))
        return gf_error_set(GF_ERR_PARAM,
                            "packing: container %g x %g cannot hold a sphere of diameter 1", width,
                            depth);
    if (!(cfg->packing_layer_thickness > 0.0 && isfinite(cfg->packing_layer_thickness)))
        return gf_error_set(GF_ERR_PARAM, "packing: layer thickness must be > 0 (got %g)",
                            cfg->packing_layer_thickness);
    if (isnan(fill) || !isfinite(fill))
        return gf_error_set(GF_ERR_PARAM, "packing: fill height must be finite");
    double count;
    if (fill > 0.0) {
        if (fill < 1.0)
            return gf_error_set(GF_ERR_PARAM,
                                "packing: fill height %g is below one particle diameter", fill);
        // More than can fit below the fill height at any fraction <= 0.66
        // over the whole footprint, plus two layers: the column always
        // overshoots and is cut down to size.
        count = ceil(0.66 * width * depth * (fill + 2.0) / (gf_gen_pi / 6.0));
    } else {
        if (cfg->packing_particles < 1)
            return gf_error_set(GF_ERR_PARAM, "packing: number of particles must be >= 1 (got %lld)",
                                (long long)cfg->packing_particles);
        count = (double)cfg->packing_particles;
    }
    if (count > (double)GF_GEN_MAX_N)
        return gf_error_set(GF_ERR_PARAM, "packing: %.0f particles is more than the limit %lld",
                            count, (long long)GF_GEN_MAX_N);

    gf_gen g = {0};
    g.width = g.width_final = width;
    g.depth = g.depth_final = depth;
    g.zlo = 0.5;
    gf_status st = gf_gen_init(&g, (size_t)count);
    if (st == GF_OK) st = gf_gen_run(&g, cfg->run_seed);
    double zmax = INFINITY;
    if (st == GF_OK && fill > 0.0) {
        zmax = fill - 0.5;
        double ztop = 0.0;
        for (size_t i = 0; i < g.n; i++) ztop = fmax(ztop, g.z[i]);
        if (ztop < zmax + 1.0)
            st = gf_error_set(GF_ERR_STATE, "packing: the column reached only %g, short of %g", ztop,
                              zmax);
    }
    if (st == GF_OK) st = gf_gen_emit(&g, zmax, cfg, out);
    gf_gen_release(&g);
    if (st == GF_OK) st = gf_gen_check(out, width, depth);
    if (st != GF_OK) out->n = 0;
    return st;
}
