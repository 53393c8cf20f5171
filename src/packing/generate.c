// SPDX-License-Identifier: MIT
// Random initial packing (SPEC 1.2): a quench of soft spheres. Centres are
// thrown at random into the container closed by a lid at the height that a
// packing of fraction PHI_BOX would fill (heavy overlaps allowed); Jacobi
// sweeps push overlapping pairs apart until the over-compressed packing has
// settled; then the lid goes and the column expands, each slab of it in
// proportion to the overlap left there, until no pair is closer than
// 1 - TOL. docs/packing.md describes the method, why its parameters have
// their values, and what it makes.
#include "granflow/packing.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/cpu.h"
#include "core/error.h"
#include "core/limits.h"
#include "core/rng.h"
#include "geom/celllist.h"
#include "geom/container.h"
#include "granflow/defs.h"
#include "packing/bidisperse.h"

// Parameters of the method (docs/packing.md says why each has its value).
#define GF_GEN_PHI_BOX 0.64       // nominal packing fraction of the closed start box
#define GF_GEN_ALPHA 0.8          // fraction of an overlap removed per sweep
#define GF_GEN_SKIN 0.3           // Verlet-list skin, d
#define GF_GEN_SETTLE_EVERY 50    // sweeps between two looks at the settling under the lid
#define GF_GEN_SETTLE_GAIN 0.98   // lid off once the overlap falls by < 2 % per look
#define GF_GEN_SETTLE_MAX 20000   // ... or after this many sweeps at the latest
#define GF_GEN_EXPAND 0.01        // slab strain per sweep per unit overlap per particle
#define GF_GEN_SLAB 4.0           // thickness of the slabs of the stretch profile, d
#define GF_GEN_BOUNCE 0.5         // pushed a through a wall, a particle ends a/2 inside
#define GF_GEN_TOL 0.005          // final largest overlap: centre distance > 1 - TOL
#define GF_GEN_SNAP 1e-3          // at the end, closer than this to a wall = on it
#define GF_GEN_MAX_SWEEPS 200000  // safety net against a relaxation that never ends
#define GF_GEN_STREAM 0x7061636b696e67ull // "packing": the RNG stream of this module
// Particles between two looks at the stop flag inside a pass over them
// (a pass over 5e7 spheres takes tens of seconds; 65,536 of them, ~1 ms).
#define GF_GEN_POLL ((size_t)1 << 16)
// Bytes per particle at the generator's peak: its nine coordinate arrays,
// the neighbour list (8 slots) and its row starts, the cell grid, and the
// packing it emits with its sort keys, ~200; checked against what the
// process may have before any of it is allocated.
#define GF_GEN_BYTES_PER_PARTICLE 200.0
// Largest footprint width x depth, d^2: 10^4 times the papers' 50 x 8 silo,
// and small enough that every coordinate and cell count stays exact.
#define GF_GEN_MAX_FOOTPRINT 4e6
// Acceptance checks of the result (SPEC 1.2).
#define GF_GEN_MIN_PAIR 0.99
#define GF_GEN_WALL 0.5

// A throwaway measuring program may define this to watch the progress; the
// library itself never prints.
#ifndef GF_GEN_TRACE
#define GF_GEN_TRACE(...) ((void)0)
#endif

static const double gf_gen_pi = 3.14159265358979323846;

// Working state of one generation. Particles are kept in cell order (re-sorted
// at every neighbour-list build) so that a sweep walks memory almost linearly.
typedef struct gf_gen {
    size_t n;
    double *x, *y, *z;    // centres
    double *ux, *uy, *uz; // per-sweep displacement sums; scratch during a build
    double *rx, *ry, *rz; // centres at the last build, z stretched with the column
    size_t *start;        // CSR row starts of the half neighbour list, n + 1
    uint32_t *nbr;        // neighbours j of i in cell order (each pair once)
    size_t nbr_cap;
    gf_celllist cells;    // the particles by cell at the last build
    double width, depth;  // side walls at +-width/2, +-depth/2 (a cylinder: its bounding box)
    bool shaped;          // not a box: the container's walls bound the centres too
    gf_container box;     // ... these walls, at z + zoff
    double zoff;          // height of the generation's z = 0 in the container (the floor 0.5 below zlo)
    double zlo, zhi;      // lowest and highest allowed centre height (zhi: the lid)
    double ztop;          // highest centre
    // Stretch profile of the column: overlap sums per horizontal slab of
    // thickness GF_GEN_SLAB (measured by the push), and the strain of each.
    double *slab_sum, *slab_strain;
    size_t *slab_count;
    size_t nslab, slab_cap;
    volatile sig_atomic_t *stop; // polled every sweep and every GF_GEN_POLL particles of a pass (may be NULL)
} gf_gen;

// Whether a stop was asked; the passes over the particles look every GF_GEN_POLL.
static inline bool gf_gen_halted(const gf_gen *g) { return g->stop && *g->stop; }

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
    gf_celllist_free(&g->cells);
    GF_DELETE(g->slab_sum, g->slab_cap);
    GF_DELETE(g->slab_strain, g->slab_cap);
    GF_DELETE(g->slab_count, g->slab_cap);
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
    g->nbr_cap = 8 * n;
    g->nbr = GF_NEW(uint32_t, g->nbr_cap);
    if (!g->x || !g->y || !g->z || !g->ux || !g->uy || !g->uz || !g->rx || !g->ry || !g->rz ||
        !g->start || !g->nbr)
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
    g->ztop = ztop;
    const double cut = 1.0 + GF_GEN_SKIN;
    // Cells of side h >= cut; a sparse tall column gets bigger cells so the
    // grid never has many more cells than particles.
    // Counted in doubles, so a huge container cannot overflow them.
    double h = cut, fnx, fny, fnz;
    for (;;) {
        fnx = fmax(1.0, floor(g->width / h));
        fny = fmax(1.0, floor(g->depth / h));
        fnz = floor(fmax(0.0, ztop + 0.5) / h) + 1.0;
        if (fnx * fny * fnz <= 2.0 * (double)n + 64.0) break;
        h *= 1.25;
    }
    size_t nx = (size_t)fnx, ny = (size_t)fny, nz = (size_t)fnz;
    // Cells of width / nx by depth / ny by h over the column (the floor 0.5 below z = 0.5).
    const double corner[3] = {-0.5 * g->width, -0.5 * g->depth, 0.0};
    const double inv[3] = {(double)nx / g->width, (double)ny / g->depth, 1.0 / h};
    const int nc[3] = {(int)nx, (int)ny, (int)nz};
    gf_celllist *cl = &g->cells;
    gf_status st = gf_celllist_grid(cl, corner, inv, nc);
    if (st == GF_OK) st = gf_celllist_bin(cl, g->x, g->y, g->z, n);
    if (st != GF_OK) return st;
    if (gf_gen_halted(g)) return GF_ERR_INTERRUPTED; // the caller sets the message
    // The particles re-ordered by cell into the scratch arrays, then swapped
    // in: from here on cell c holds the particles start[c] .. start[c + 1] - 1.
    for (size_t k = 0; k < n; k++) {
        size_t i = cl->idx[k];
        g->ux[k] = g->x[i];
        g->uy[k] = g->y[i];
        g->uz[k] = g->z[i];
    }
    const size_t *cs = cl->start;
    double *t;
    t = g->x, g->x = g->ux, g->ux = t;
    t = g->y, g->y = g->uy, g->uy = t;
    t = g->z, g->z = g->uz, g->uz = t;
    memcpy(g->rx, g->x, sizeof *g->x * n);
    memcpy(g->ry, g->y, sizeof *g->y * n);
    memcpy(g->rz, g->z, sizeof *g->z * n);

    // Half stencil: the cell itself (j > i) and its 13 "forward" neighbours.
    const double cut2 = cut * cut;
    size_t m = 0;
    for (size_t iz = 0; iz < nz; iz++)
        for (size_t iy = 0; iy < ny; iy++) {
            if (gf_gen_halted(g)) return GF_ERR_INTERRUPTED; // each row of cells: a few thousand particles at most
            for (size_t ix = 0; ix < nx; ix++) {
                size_t c = (iz * ny + iy) * nx + ix;
                size_t lo[13], hi[13];
                int ns = gf_celllist_forward(cl, (int)ix, (int)iy, (int)iz, lo, hi);
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
        }
    g->start[n] = m;
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
// centres) into ux, uy, uz, and the overlaps per slab of the column. Returns
// the largest overlap 1 - r; *mean = total overlap / particles.
static double gf_gen_push(gf_gen *g, double *mean)
{
    size_t n = g->n, nslab = g->nslab;
    double *restrict slab_sum = g->slab_sum;
    size_t *restrict slab_count = g->slab_count;
    memset(slab_sum, 0, sizeof *slab_sum * nslab);
    memset(slab_count, 0, sizeof *slab_count * nslab);
    const double zlo = g->zlo;
    const double *restrict x = g->x, *restrict y = g->y, *restrict z = g->z;
    double *restrict ux = g->ux, *restrict uy = g->uy, *restrict uz = g->uz;
    const size_t *restrict start = g->start;
    const uint32_t *restrict nbr = g->nbr;
    memset(ux, 0, sizeof *ux * n);
    memset(uy, 0, sizeof *uy * n);
    memset(uz, 0, sizeof *uz * n);
    const double half = 0.5 * GF_GEN_ALPHA;
    double worst = 0.0, sum = 0.0;
    // In blocks of GF_GEN_POLL particles with a look at the stop flag between
    // them (the caller sees it too and drops this half-done sweep); the same
    // order of operations as one loop, so the same packing.
    for (size_t i0 = 0; i0 < n && !gf_gen_halted(g); i0 += GF_GEN_POLL)
    for (size_t i = i0, i1 = i0 + GF_GEN_POLL < n ? i0 + GF_GEN_POLL : n; i < i1; i++) {
        const double xi = x[i], yi = y[i], zi = z[i];
        double ax = 0.0, ay = 0.0, az = 0.0, si = 0.0;
        for (size_t k = start[i]; k < start[i + 1]; k++) {
            size_t j = nbr[k];
            double dx = xi - x[j], dy = yi - y[j], dz = zi - z[j];
            // Branch-free (a mispredicted branch on every other pair costs
            // more than the arithmetic): with s = 1 - r^2 (0 for pairs that do
            // not touch), (1 - r) / r = s/2 + 3s^2/8 + 5s^3/16 + 35s^4/128 + ...
            // The truncated series is within 5e-5 (relative) of the exact
            // rule for overlaps up to 0.05 and pushes less for bigger ones;
            // below r = 0.71 (s > 0.5) the exact rule takes over.
            double s = 1.0 - (dx * dx + dy * dy + dz * dz);
            s = gf_gen_positive(s);
            worst = s > worst ? s : worst;
            si += s;
            double f = half * s * (0.5 + s * (0.375 + s * (0.3125 + s * 0.2734375)));
            if (s > 0.5) { // r < 0.71: rare, so this branch is well predicted
                double r = sqrt(1.0 - s);
                if (r < 1e-9) { // coincident centres: part them vertically
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
        sum += si;
        size_t b = (size_t)((zi - zlo) * (1.0 / GF_GEN_SLAB));
        b = b < nslab ? b : nslab - 1;
        slab_sum[b] += si;
        slab_count[b]++;
    }
    *mean = 0.5 * sum / (double)n; // sum of s/2 ~ sum of overlaps
    return 1.0 - sqrt(1.0 - fmin(worst, 1.0));
}

// Puts a coordinate pushed through a wall back inside, half as far from the
// wall as it went through it (an exact clamp would line particles up on the
// wall plane, where overlapping pairs of them could only push each other
// sideways and a crowded layer on the base would never get unstuck).
static inline double gf_gen_wall(double v, double lo, double hi)
{
    v = v >= lo ? v : lo + GF_GEN_BOUNCE * (lo - v);
    v = v <= hi ? v : hi - GF_GEN_BOUNCE * (v - hi);
    v = v >= lo ? v : lo; // (fmin/fmax would be library calls here)
    return v <= hi ? v : hi;
}

// The walls of a shaped container (funnel, pipe, column, curved wall): a
// centre closer than 1/2 to one is put back as gf_gen_wall does, half as
// far inside as it went through.
static void gf_gen_shape_wall(const gf_gen *g, double *x, double *y, double *z)
{
    const gf_container *c = &g->box;
    double p[3] = {*x, *y, *z + g->zoff};
    if (gf_container_clear(c, p[0], p[1], p[2], 0.5)) return; // the bulk
    gf_wall_hit hit[GF_WALL_HITS];
    int n = gf_container_walls(c, p, 0.5, hit);
    for (int k = 0; k < n; k++) {
        double f = (1.0 + GF_GEN_BOUNCE) * (0.5 - hit[k].gap);
        p[0] += f * hit[k].n[0];
        p[1] += f * hit[k].n[1];
        p[2] += f * hit[k].n[2];
    }
    *x = p[0];
    *y = p[1];
    *z = p[2] - g->zoff;
}

// Height (generation coordinates) below which the container holds volume v.
static double gf_gen_height_for(const gf_gen *g, double v)
{
    const double dz = 0.01;
    double h = 0.0, acc = 0.0;
    while (acc < v) {
        acc += dz * g->box.ops->section_area(&g->box, h + 0.5 * dz + g->zoff);
        h += dz;
    }
    return h;
}

// The column stretch: z -> z + u(z), u piecewise linear over the slabs with
// slope slab_strain (>= 0), u(zlo) = 0. It only ever lengthens pair vectors.
static inline double gf_gen_lift(const double *restrict lift, const double *restrict strain,
                                 size_t nslab, double zlo, double z)
{
    double t = (z - zlo) * (1.0 / GF_GEN_SLAB);
    size_t b = (size_t)t;
    b = b < nslab ? b : nslab - 1;
    return z + lift[b] + strain[b] * GF_GEN_SLAB * (t - (double)b);
}

// Second half: applies the pushes, stretches the column by `gain` times the
// overlap per particle of each slab (0: no stretch), puts particles back
// inside the walls, the base and the lid. Returns the largest squared
// displacement since the last build that is not due to the stretch.
static double gf_gen_move(gf_gen *g, double gain)
{
    size_t n = g->n, nslab = g->nslab;
    const double zlo = g->zlo, zhi = g->zhi;
    const double xhi = 0.5 * g->width - 0.5, xlo = -xhi, yhi = 0.5 * g->depth - 0.5, ylo = -yhi;
    double *restrict x = g->x, *restrict y = g->y, *restrict z = g->z, *restrict rz = g->rz;
    const double *restrict ux = g->ux, *restrict uy = g->uy, *restrict uz = g->uz;
    const double *restrict rx = g->rx, *restrict ry = g->ry;
    // lift[b]: how far the bottom of slab b rises (reuses slab_sum).
    double *restrict strain = g->slab_strain, *restrict lift = g->slab_sum;
    double up = 0.0;
    for (size_t b = 0; b < nslab; b++) {
        double e = g->slab_count[b] ? gain * 0.5 * lift[b] / (double)g->slab_count[b] : 0.0;
        strain[b] = e;
        lift[b] = up;
        up += e * GF_GEN_SLAB;
    }
    // The top slab reaches to infinity: above the measured ones nothing stretches.
    strain[nslab - 1] = 0.0;
    double worst = 0.0, ztop = zlo;
    const bool shaped = g->shaped;
    for (size_t i0 = 0; i0 < n && !gf_gen_halted(g); i0 += GF_GEN_POLL) // as gf_gen_push
    for (size_t i = i0, i1 = i0 + GF_GEN_POLL < n ? i0 + GF_GEN_POLL : n; i < i1; i++) {
        double xi = x[i] + ux[i], yi = y[i] + uy[i], zi = z[i] + uz[i];
        xi = gf_gen_wall(xi, xlo, xhi);
        yi = gf_gen_wall(yi, ylo, yhi);
        zi = gf_gen_wall(zi, zlo, zhi);
        if (shaped) gf_gen_shape_wall(g, &xi, &yi, &zi);
        double r = rz[i];
        if (gain > 0.0) {
            zi = gf_gen_lift(lift, strain, nslab, zlo, zi);
            r = gf_gen_lift(lift, strain, nslab, zlo, r);
            rz[i] = r;
        }
        x[i] = xi;
        y[i] = yi;
        z[i] = zi;
        ztop = zi > ztop ? zi : ztop;
        double dx = xi - rx[i], dy = yi - ry[i], dz = zi - r;
        double d2 = dx * dx + dy * dy + dz * dz;
        worst = d2 > worst ? d2 : worst;
    }
    g->ztop = ztop;
    return worst;
}

// Sizes the slab arrays for the column up to ztop (one spare slab on top,
// which never stretches).
static gf_status gf_gen_slabs(gf_gen *g)
{
    size_t need = (size_t)((g->ztop - g->zlo) / GF_GEN_SLAB) + 2;
    if (need > g->slab_cap) {
        size_t cap = need + need / 2 + 4;
        double *a = GF_NEW(double, cap), *b = GF_NEW(double, cap);
        size_t *c = GF_NEW(size_t, cap);
        if (!a || !b || !c) {
            GF_DELETE(a, cap);
            GF_DELETE(b, cap);
            GF_DELETE(c, cap);
            return gf_error_set(GF_ERR_NOMEM, "packing: out of memory for %zu slabs", cap);
        }
        GF_DELETE(g->slab_sum, g->slab_cap);
        GF_DELETE(g->slab_strain, g->slab_cap);
        GF_DELETE(g->slab_count, g->slab_cap);
        g->slab_sum = a;
        g->slab_strain = b;
        g->slab_count = c;
        g->slab_cap = cap;
    }
    g->nslab = need;
    return GF_OK;
}

// Rebuilds the neighbour list unless it still holds every pair closer than 1,
// and sizes the slabs. A stretch only lengthens pair vectors, so a pair
// outside the list (longer than 1 + skin at the build) is still longer than
// 1 while no particle has moved more than skin/2 on top of the stretch.
static gf_status gf_gen_keep_list(gf_gen *g, double disp2)
{
    double half_skin = 0.5 * GF_GEN_SKIN * (1.0 - 1e-9);
    if (disp2 >= half_skin * half_skin) {
        gf_status st = gf_gen_build(g);
        if (st != GF_OK) return st;
    }
    return gf_gen_slabs(g);
}

static gf_status gf_gen_stopped(const gf_gen *g, long sweeps)
{
    if (!gf_gen_halted(g)) return GF_OK;
    if (sweeps < 0) return gf_error_set(GF_ERR_INTERRUPTED, "packing: interrupted before the first relaxation sweep");
    return gf_error_set(GF_ERR_INTERRUPTED, "packing: interrupted after %ld relaxation sweeps", sweeps);
}

// Runs the whole method on g. Returns the status.
static gf_status gf_gen_run(gf_gen *g, uint64_t seed)
{
    size_t n = g->n;
    // 1. Random centres in the container closed at the height that a packing
    // of fraction PHI_BOX would fill. Overlaps are allowed (and many).
    double height = g->shaped ? gf_gen_height_for(g, (double)n * gf_gen_pi / 6.0 / GF_GEN_PHI_BOX)
                              : (double)n * gf_gen_pi / 6.0 / (g->width * g->depth * GF_GEN_PHI_BOX);
    g->zlo = 0.5;
    g->zhi = fmax(g->zlo, height - 0.5);
    const double xhi = 0.5 * g->width - 0.5, yhi = 0.5 * g->depth - 0.5;
    gf_rng rng;
    gf_rng_seed(&rng, seed, GF_GEN_STREAM);
    for (size_t i = 0; i < n; i++) {
        if (i % GF_GEN_POLL == 0 && gf_gen_halted(g)) return gf_gen_stopped(g, -1);
        for (long tries = 0;; tries++) { // a shaped container: drawn in its bounding box until inside
            g->x[i] = xhi * (2.0 * gf_rng_uniform(&rng) - 1.0);
            g->y[i] = yhi * (2.0 * gf_rng_uniform(&rng) - 1.0);
            g->z[i] = g->zlo + (g->zhi - g->zlo) * gf_rng_uniform(&rng);
            if (!g->shaped || gf_container_contains(&g->box, g->x[i], g->y[i], g->z[i] + g->zoff, 0.5, 0.0))
                break;
            if (tries > 100000) return gf_error_set(GF_ERR_PARAM, "packing: no room for a sphere in the container");
        }
    }
    gf_status st = gf_gen_build(g);
    if (st == GF_ERR_INTERRUPTED) return gf_gen_stopped(g, -1);
    if (st == GF_OK) st = gf_gen_slabs(g);
    if (st != GF_OK) return st;

    // 2. Relax under the lid until the over-compressed packing has settled:
    // the overlap left no longer falls by much.
    long sweeps = 0;
    double mean = 0.0, last = INFINITY;
    for (; sweeps < GF_GEN_SETTLE_MAX; sweeps++) {
        if ((st = gf_gen_stopped(g, sweeps)) != GF_OK) return st;
        double worst = gf_gen_push(g, &mean);
        if ((st = gf_gen_stopped(g, sweeps)) != GF_OK) return st; // a sweep cut short
        if (sweeps % GF_GEN_SETTLE_EVERY == 0) {
            GF_GEN_TRACE("lid: sweep %ld worst %.4f mean %.5f", sweeps, worst, mean);
            if (worst < GF_GEN_TOL || mean > GF_GEN_SETTLE_GAIN * last) break;
            last = mean;
        }
        if ((st = gf_gen_keep_list(g, gf_gen_move(g, 0.0))) != GF_OK)
            return st == GF_ERR_INTERRUPTED ? gf_gen_stopped(g, sweeps) : st;
    }

    // 3. Lift the lid and let the column expand. The sweeps alone would let
    // the compression out from the top down, in a time growing with the
    // square of the height; stretching every slab in proportion to the
    // overlap left in it does that part at once, the sweeps the rest.
    g->zhi = INFINITY;
    for (;;) {
        if ((st = gf_gen_stopped(g, sweeps)) != GF_OK) return st;
        double worst = gf_gen_push(g, &mean);
        if ((st = gf_gen_stopped(g, sweeps)) != GF_OK) return st; // a sweep cut short
        if (sweeps % 200 == 0)
            GF_GEN_TRACE("open: sweep %ld worst %.4f mean %.5f", sweeps, worst, mean);
        if (worst < GF_GEN_TOL) break;
        if (++sweeps >= GF_GEN_MAX_SWEEPS)
            return gf_error_set(GF_ERR_STATE,
                                "packing: relaxation did not converge (largest overlap %.3g after "
                                "%ld sweeps)",
                                worst, sweeps);
        if ((st = gf_gen_keep_list(g, gf_gen_move(g, GF_GEN_EXPAND))) != GF_OK)
            return st == GF_ERR_INTERRUPTED ? gf_gen_stopped(g, sweeps) : st;
    }
    GF_GEN_TRACE("done: %ld sweeps", sweeps);
    return GF_OK;
}

// The bounce leaves particles pressed against a wall hovering a hair (well
// under SNAP) off it: put them on it. A pair gets closer by at most
// 2 sqrt(3) SNAP, which keeps the closest pair above 1 - TOL - 0.0035.
static void gf_gen_snap(gf_gen *g)
{
    const double xhi = 0.5 * g->width - 0.5, yhi = 0.5 * g->depth - 0.5, zlo = g->zlo;
    if (g->shaped) {
        // Onto the floor; and out of every wall closer than 1/2, by projecting
        // onto the most violated one until none is (in a corner the walls'
        // normals differ: a few rounds converge).
        for (size_t i = 0; i < g->n; i++) {
            if (g->z[i] < zlo + GF_GEN_SNAP) g->z[i] = zlo;
            for (int round = 0; round < 50; round++) {
                double p[3] = {g->x[i], g->y[i], g->z[i] + g->zoff};
                gf_wall_hit hit[GF_WALL_HITS];
                int nh = gf_container_walls(&g->box, p, 0.5, hit), worst = -1;
                for (int k = 0; k < nh; k++)
                    if (worst < 0 || hit[k].gap < hit[worst].gap) worst = k;
                if (worst < 0) break;
                double f = 0.5 - hit[worst].gap + 1e-12;
                g->x[i] += f * hit[worst].n[0];
                g->y[i] += f * hit[worst].n[1];
                g->z[i] += f * hit[worst].n[2];
            }
        }
        return;
    }
    for (size_t i = 0; i < g->n; i++) {
        if (g->x[i] > xhi - GF_GEN_SNAP) g->x[i] = xhi;
        if (g->x[i] < GF_GEN_SNAP - xhi) g->x[i] = -xhi;
        if (g->y[i] > yhi - GF_GEN_SNAP) g->y[i] = yhi;
        if (g->y[i] < GF_GEN_SNAP - yhi) g->y[i] = -yhi;
        if (g->z[i] < zlo + GF_GEN_SNAP) g->z[i] = zlo;
    }
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
static gf_status gf_gen_emit(const gf_gen *g, double zmax, const gf_packing_defs *pd, gf_packing *out)
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
            out->z[k] = g->z[i] + g->zoff;
            out->r[k] = 0.5;
        }
        out->n = m;
        gf_packing_tag_layers(out, pd->layer_thickness);
    }
    GF_DELETE(key, n);
    return st;
}

// Final acceptance check: the promises of SPEC 1.2 hold, or this is a bug.
static gf_status gf_gen_check(const gf_packing *p, const gf_gen *g, double width, double depth)
{
    double hw = 0.5 * width - GF_GEN_WALL, hd = 0.5 * depth - GF_GEN_WALL;
    for (size_t i = 0; i < p->n; i++) {
        bool in = g->shaped ? gf_container_contains(&g->box, p->x[i], p->y[i], p->z[i], GF_GEN_WALL, 1e-9) &&
                                  p->z[i] >= g->zoff + GF_GEN_WALL - 1e-9
                            : fabs(p->x[i]) <= hw && fabs(p->y[i]) <= hd && p->z[i] >= GF_GEN_WALL;
        if (!in)
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

// How many particles to build: packing_particles, or for a fill height more
// than fit below it at any fraction <= 0.66 over the whole footprint plus two
// layers, so that the column always overshoots and can be cut down to size.
static gf_status gf_gen_count(const gf_config *cfg, size_t *count)
{
    gf_container_defs cd;
    gf_config_container_defs(cfg, &cd);
    gf_packing_defs pd, def;
    gf_config_packing_defs(cfg, &pd);
    const gf_config dcfg = gf_config_default();
    gf_config_packing_defs(&dcfg, &def);
    double width = cd.width, depth = cd.depth;
    double fill = pd.fill_height;
    if (!(width >= 1.0 && depth >= 1.0 && isfinite(width) && isfinite(depth)))
        return gf_error_set(GF_ERR_PARAM,
                            "packing: a container %g x %g cannot hold a sphere of diameter 1",
                            width, depth);
    if (!(width * depth <= GF_GEN_MAX_FOOTPRINT))
        return gf_error_set(GF_ERR_PARAM,
                            "packing: a container %g x %g is larger than the generator's limit of %g d^2",
                            width, depth, GF_GEN_MAX_FOOTPRINT);
    if (!(pd.layer_thickness > 0.0 && isfinite(pd.layer_thickness)))
        return gf_error_set(GF_ERR_PARAM, "packing: layer thickness must be > 0 (got %g)",
                            pd.layer_thickness);
    double n;
    if (fill > 0.0) {
        if (!(fill >= 1.0 && isfinite(fill)))
            return gf_error_set(GF_ERR_PARAM,
                                "packing: fill height %g must be finite and at least one diameter",
                                fill);
        if (pd.particles != def.particles) // set, but not used: say so
            gf_warn("packing.particles = %lld is ignored: packing.fill_height = %g sets the count "
                    "(set packing.fill_height = 0 to use packing.particles)",
                    (long long)pd.particles, fill);
        n = ceil(0.66 * width * depth * (fill + 2.0) / (gf_gen_pi / 6.0));
        const gf_container c = gf_container_build(&cd); // and a pipe or chute below z = 0
        if (c.z_bottom < 0.0) n += ceil(0.66 * gf_container_slice_volume(&c, c.z_bottom, 0.0) / (gf_gen_pi / 6.0));
    } else {
        if (pd.particles < 1)
            return gf_error_set(GF_ERR_PARAM,
                                "packing: number of particles must be >= 1 (got %lld)",
                                (long long)pd.particles);
        n = (double)pd.particles;
    }
    if (!(n <= (double)GF_MAX_PARTICLES))
        return gf_error_set(GF_ERR_PARAM, "packing: %.0f particles is more than the limit %lld", n,
                            (long long)GF_MAX_PARTICLES);
    *count = (size_t)n;
    return GF_OK;
}

// Refuses up front a count whose generation could never fit in the memory
// this process may have (it used to allocate and zero gigabytes first).
static gf_status gf_gen_fits(size_t count)
{
    const char *what;
    double have = gf_cpu_memory(&what), need = (double)count * GF_GEN_BYTES_PER_PARTICLE;
    if (need <= have) return GF_OK;
    return gf_error_set(GF_ERR_NOMEM,
                        "packing: %zu particles need about %.1f GB to generate, more than the %.1f GB this process "
                        "may have (%s): lower packing.particles or packing.fill_height",
                        count, need / 1e9, have / 1e9, what);
}

gf_packing_opts gf_packing_opts_default(void) { return (gf_packing_opts){.stop = NULL}; }

gf_status gf_packing_generate(const gf_config *cfg, const gf_packing_opts *opts, gf_packing *out)
{
    volatile sig_atomic_t *stop = opts ? opts->stop : NULL;
    if (!cfg || !out) return gf_error_set(GF_ERR_PARAM, "packing: NULL argument");
    if (stop && *stop) return gf_error_set(GF_ERR_INTERRUPTED, "packing: interrupted before it began");
    gf_container_defs cd;
    gf_config_container_defs(cfg, &cd);
    gf_packing_defs pd;
    gf_config_packing_defs(cfg, &pd);
    size_t count = 0;
    gf_status st = gf_gen_count(cfg, &count);
    if (st == GF_OK) st = gf_gen_fits(count);
    gf_gen g = {0};
    g.width = cd.width;
    g.depth = cd.depth;
    g.stop = stop;
    g.box = gf_container_build(&cd);
    g.shaped = !gf_container_rectangular(&g.box);
    // A pipe is filled from its end up (or from the exit plane, when that is
    // higher). Below the pipe's end (or below the outlet, with no pipe) there
    // is no wall: the outlet is closed while the packing is built, as the box's
    // orifice is, and what falls through it when the run starts falls freely
    // to an exit plane lower down.
    g.zoff = g.shaped ? fmin(0.0, fmax(g.box.z_exit, g.box.z_bottom)) : 0.0;
    if (st == GF_OK) st = gf_gen_init(&g, count);
    if (st == GF_OK) st = gf_gen_run(&g, pd.seed);
    if (st == GF_OK && gf_gen_halted(&g)) // before the sort and the checks, long for many spheres
        st = gf_error_set(GF_ERR_INTERRUPTED, "packing: interrupted after its relaxation");
    if (st == GF_OK) gf_gen_snap(&g);
    double zmax = INFINITY;
    if (st == GF_OK && pd.fill_height > 0.0) {
        zmax = pd.fill_height - 0.5 - g.zoff;
        double ztop = 0.0;
        for (size_t i = 0; i < g.n; i++) ztop = fmax(ztop, g.z[i]);
        if (ztop < zmax + 1.0) // the count above makes this a bug
            st = gf_error_set(GF_ERR_STATE, "packing: the column reached only %g, short of %g",
                              ztop, zmax + 1.0);
    }
    if (st == GF_OK) st = gf_gen_emit(&g, zmax, &pd, out);
    gf_gen_release(&g);
    if (st == GF_OK && gf_gen_halted(&g)) st = gf_error_set(GF_ERR_INTERRUPTED, "packing: interrupted while checking it");
    if (st == GF_OK) st = gf_gen_check(out, &g, cd.width, cd.depth);
    if (st == GF_OK) st = gf_packing_bidisperse(cfg, out); // packing.radius2, fraction2
    if (st != GF_OK) gf_packing_free(out); // nothing half-made comes back
    return st;
}
