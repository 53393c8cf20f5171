// SPDX-License-Identifier: MIT
// Spatial correlation of velocity fluctuations about the mean flow in a square
// region high in the centre, fitted by C(r) = a exp(-r / beta) (thesis Sec. 3.3
// and Fig. 3-3: DEM beta = 1.87 d, which sets the spot radius 2.60 d).
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/motion.h"
#include "core/alloc.h"
#include "core/error.h"
#include "geom/container.h"
#include "granflow/analysis.h"
#include "granflow/defs.h"

#define GF_CORR_DR 0.1    // bin of r, d: resolves the shell structure of Fig. 3-3
#define GF_CORR_RMAX 8.0  // largest r, d (half the 16 d region)
// The fit: unweighted, free amplitude, over 1 <= r <= 8 (hard spheres have no
// pairs closer than 1 d). Fitted so to the theoretical curve (the overlap of
// two spot balls) over 0 < r < 2-3 R_s, a exp(-r / beta) gives beta =
// 0.71-0.74 R_s: the thesis' 0.72 R_s, so this is the fit the thesis made.
#define GF_CORR_FITMIN 1.0
#define GF_CORR_DEM 1.87  // thesis Sec. 3.3, d
#define GF_CORR_DY 0.25   // slices of the mean flow's depth profile, d (as velocity_depth)
// Above this unsteadiness (relative sd of the region's flow amplitude over
// the frame pairs) the amplitude of each frame pair is taken out of the
// fluctuations (gf_corr_bursts). Below it, it is not: in a steady spot run
// (0.02-0.05) part of that amplitude is the spots' own correlation, and
// taking it out shortens beta (r_s 2.2 read as 1.9 instead of 2.15).
#define GF_CORR_BURSTY 0.1

/// One particle of the region in one frame pair: midpoint position, velocity
/// u (replaced by the fluctuation du once the mean flow is known), mean flow there.
typedef struct gf_corr_pt {
    double x, y, z, u[3], mean[3];
} gf_corr_pt;

static int gf_corr_cmp(const void *pa, const void *pb)
{
    const gf_corr_pt *a = pa, *b = pb;
    return (a->x > b->x) - (a->x < b->x);
}

/// Sums over pairs at distance r (bins of GF_CORR_DR) and over particles.
typedef struct gf_corr_acc {
    size_t nb;
    double rmax;
    double *sum, *cnt, *rsum; ///< per bin: sum du_i.du_j, pairs, sum r
    double s2, n;             ///< sum du^2, particles
} gf_corr_acc;

/// Adds the pairs of one frame pair's fluctuations (sorted by x, then swept).
static void gf_corr_pairs(gf_corr_acc *a, gf_corr_pt *p, size_t m)
{
    qsort(p, m, sizeof *p, gf_corr_cmp);
    double r2max = a->rmax * a->rmax;
    for (size_t i = 0; i < m; i++) {
        a->s2 += p[i].u[0] * p[i].u[0] + p[i].u[1] * p[i].u[1] + p[i].u[2] * p[i].u[2];
        a->n += 1.0;
        for (size_t j = i + 1; j < m && p[j].x - p[i].x < a->rmax; j++) {
            double dx = p[j].x - p[i].x, dy = p[j].y - p[i].y, dz = p[j].z - p[i].z;
            double r2 = dx * dx + dy * dy + dz * dz;
            if (r2 >= r2max) continue;
            double r = sqrt(r2);
            size_t b = (size_t)(r / GF_CORR_DR);
            if (b >= a->nb) continue;
            a->sum[b] += p[i].u[0] * p[j].u[0] + p[i].u[1] * p[j].u[1] + p[i].u[2] * p[j].u[2];
            a->cnt[b] += 1.0;
            a->rsum[b] += r;
        }
    }
}

/// The region's particles over the window: pairs [off[k], off[k + 1]) of
/// points for frame pair k.
typedef struct gf_corr_set {
    gf_corr_pt *p;
    size_t n, cap;
    size_t *off, npair;
} gf_corr_set;

static void gf_corr_set_free(gf_corr_set *c)
{
    if (c->p) GF_DELETE(c->p, c->cap);
    if (c->off) GF_DELETE(c->off, c->npair + 1);
    memset(c, 0, sizeof *c);
}

/// Collects every frame pair of [k0, k1): the particles in the region
/// |x - orifice_x| < size/2, |z - zc| < size/2 (all y) with their velocity and the binned
/// mean field at their position (in a cylinder the (r, z) field's
/// (v_r, v_theta, v_z) turned to the particle's azimuth).
static gf_status gf_corr_collect(const gf_series *s, size_t k0, size_t k1, const gf_vfield *f,
                                 const gf_analysis_opts *o, gf_corr_set *c)
{
    c->npair = k1 > k0 + 1 ? k1 - k0 - 1 : 0;
    c->off = GF_NEW(size_t, c->npair + 1);
    if (!c->off) return gf_error_set(GF_ERR_NOMEM, "correlation: out of memory");
    gf_steps st = {0};
    gf_status rc = GF_OK;
    gf_container_defs cd;
    gf_config_container_defs(&s->cfg, &cd);
    double half = 0.5 * o->corr_size, ox = cd.orifice.x; // the region: above the orifice
    for (size_t k = 0; rc == GF_OK && k < c->npair; k++) {
        c->off[k] = c->n;
        rc = gf_steps_between(&s->frames[k0 + k], &s->frames[k0 + k + 1], &st);
        if (rc != GF_OK) break;
        if (c->n + st.n > c->cap) {
            size_t cap = 2 * (c->n + st.n);
            gf_corr_pt *p = gf_realloc(c->p, sizeof *p * c->cap, sizeof *p * cap);
            if (!p) {
                rc = gf_error_set(GF_ERR_NOMEM, "correlation: out of memory for %zu particles", cap);
                break;
            }
            c->p = p;
            c->cap = cap;
        }
        for (size_t j = 0; j < st.n; j++) {
            if (!(fabs(st.x[j] - ox) < half && fabs(st.z[j] - o->corr_zc) < half)) continue;
            gf_corr_pt *q = &c->p[c->n];
            if (gf_vfield_mean(f, st.x[j], st.y[j], st.z[j], q->mean) == 0.0) continue; // cannot happen: it is in the field
            q->x = st.x[j];
            q->y = st.y[j];
            q->z = st.z[j];
            q->u[0] = st.vx[j];
            q->u[1] = st.vy[j];
            q->u[2] = st.vz[j];
            c->n++;
        }
    }
    c->off[c->npair] = c->n;
    gf_steps_free(&st);
    return rc;
}

/// The depth profile of the mean flow: in each slice of GF_CORR_DY across the
/// depth D, the factor f minimising sum |v - f <v>(x, z)|^2 over the region's
/// particles (1 where there is no flow). The (x, z) field is an average over
/// y, but the flow is slower in the wall layers (2009 paper Fig. 8: v_z(y)
/// drops by ~40% at mu_w = 0.5); left in du, that offset correlates all wall
/// particles with each other, at every r. Then du = v - f(y) <v>(x, z).
static gf_status gf_corr_fluctuations(gf_corr_set *c, double depth)
{
    size_t ny = depth > 0.0 ? (size_t)ceil(depth / GF_CORR_DY - 1e-9) : 1;
    double *num = GF_NEW(double, ny), *den = GF_NEW(double, ny);
    if (!num || !den) {
        if (num) GF_DELETE(num, ny);
        if (den) GF_DELETE(den, ny);
        return gf_error_set(GF_ERR_NOMEM, "correlation: out of memory");
    }
    size_t *slice = c->n ? GF_NEW(size_t, c->n) : NULL;
    if (c->n && !slice) {
        GF_DELETE(num, ny);
        GF_DELETE(den, ny);
        return gf_error_set(GF_ERR_NOMEM, "correlation: out of memory");
    }
    for (size_t i = 0; i < c->n; i++) {
        const gf_corr_pt *q = &c->p[i];
        double b = depth > 0.0 ? floor((q->y + 0.5 * depth) / GF_CORR_DY) : 0.0;
        slice[i] = b < 0.0 ? 0 : b >= (double)ny ? ny - 1 : (size_t)b;
        for (int d = 0; d < 3; d++) {
            num[slice[i]] += q->u[d] * q->mean[d];
            den[slice[i]] += q->mean[d] * q->mean[d];
        }
    }
    for (size_t b = 0; b < ny; b++) num[b] = den[b] > 0.0 ? num[b] / den[b] : 1.0;
    for (size_t i = 0; i < c->n; i++)
        for (int d = 0; d < 3; d++) {
            c->p[i].mean[d] *= num[slice[i]];
            c->p[i].u[d] -= c->p[i].mean[d];
        }
    if (slice) GF_DELETE(slice, c->n);
    GF_DELETE(num, ny);
    GF_DELETE(den, ny);
    return GF_OK;
}

/// A cylinder's fluctuations: du = v - <v>(r, z). The axisymmetric mean flow
/// (thesis Sec. 3.3: fluctuations about the local mean) converges radially,
/// v = (v_r x/r, v_r y/r, v_z), so an (x, z) field averaged over y leaves the
/// convergence in du (beta +37% on a granflow cylinder, r_s 2.2); binned in
/// (r, z) it also resolves the slow wall layer, which the box's depth
/// profile (gf_corr_fluctuations) stands in for.
static void gf_corr_about_mean(gf_corr_set *c)
{
    for (size_t i = 0; i < c->n; i++)
        for (int d = 0; d < 3; d++) c->p[i].u[d] -= c->p[i].mean[d];
}

/// Relative sd over the frame pairs of the flow's amplitude in the region
/// (the factor a_k minimising sum |v - a_k <v>|^2): ~0 in steady flow. A
/// window where the flow still grows (spots not yet up to the region) gives a
/// large value, and a mean field that leaves a coherent du over the whole region.
static double gf_corr_unsteadiness(const gf_corr_set *c)
{
    double sa = 0.0, saa = 0.0;
    size_t m = 0;
    for (size_t k = 0; k < c->npair; k++) {
        double num = 0.0, den = 0.0;
        for (size_t i = c->off[k]; i < c->off[k + 1]; i++)
            for (int d = 0; d < 3; d++) {
                num += (c->p[i].u[d] + c->p[i].mean[d]) * c->p[i].mean[d];
                den += c->p[i].mean[d] * c->p[i].mean[d];
            }
        if (!(den > 0.0)) continue;
        sa += num / den;
        saa += num / den * num / den;
        m++;
    }
    if (m < 2) return NAN;
    double mean = sa / (double)m, var = (saa - sa * mean) / (double)(m - 1);
    return sqrt(fmax(var, 0.0)) / fabs(mean);
}

/// Removes the flow's amplitude in each frame pair from the fluctuations:
/// du -= (a_k - 1) f(y) <v>, a_k minimising sum |v - a_k f(y) <v>|^2 over the
/// region (as gf_corr_unsteadiness). A DEM silo flows in bursts (arches form
/// and break at the orifice), and a burst speeds up or slows down the whole
/// region at once; left in du, it correlates every pair at every r
/// (measured on a LAMMPS slit silo, unsteadiness 0.49: beta 22 d in an 11 d
/// region; 1.8 d with it removed). What remains is the local, spot-sized part.
static void gf_corr_bursts(gf_corr_set *c)
{
    for (size_t k = 0; k < c->npair; k++) {
        double sn = 0.0, sd = 0.0;
        for (size_t i = c->off[k]; i < c->off[k + 1]; i++)
            for (int d = 0; d < 3; d++) {
                sn += c->p[i].u[d] * c->p[i].mean[d];
                sd += c->p[i].mean[d] * c->p[i].mean[d];
            }
        double da = sd > 0.0 ? sn / sd : 0.0; // a_k - 1: u is already v - <v>
        for (size_t i = c->off[k]; i < c->off[k + 1]; i++)
            for (int d = 0; d < 3; d++) {
                c->p[i].u[d] -= da * c->p[i].mean[d];
                c->p[i].mean[d] *= 1.0 + da;
            }
    }
}

static void gf_corr_free(gf_corr_acc *a)
{
    if (a->sum) GF_DELETE(a->sum, a->nb);
    if (a->cnt) GF_DELETE(a->cnt, a->nb);
    if (a->rsum) GF_DELETE(a->rsum, a->nb);
}

gf_status gf_measure_correlation(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out)
{
    if (!(o->corr_size > 0.0) || !(o->vel_bin > 0.0))
        return gf_error_set(GF_ERR_PARAM, "correlation: region size (%g) and velocity bin (%g) must be positive",
                            o->corr_size, o->vel_bin);
    double t0, t1;
    gf_analysis_window(o, s, &t0, &t1);
    size_t k0, k1;
    gf_window_frames(s, t0, t1, &k0, &k1);
    // The mean flow: the binned field of the same window (as the velocity measurement).
    // In a cylinder it is binned in (r, z): the flow is axisymmetric.
    const gf_container ctr = gf_container_make(&s->cfg);
    bool radial = gf_container_profile_radial(&ctr);
    gf_vfield f;
    size_t npairs;
    gf_status st = gf_vfield_window(s, t0, t1, o->vel_bin, radial, o->stop, &f, &npairs);
    if (st != GF_OK) return st;
    gf_corr_acc a = {0};
    a.rmax = fmin(GF_CORR_RMAX, 0.5 * o->corr_size);
    a.nb = (size_t)ceil(a.rmax / GF_CORR_DR - 1e-9);
    a.sum = GF_NEW(double, a.nb);
    a.cnt = GF_NEW(double, a.nb);
    a.rsum = GF_NEW(double, a.nb);
    if (!a.sum || !a.cnt || !a.rsum) st = gf_error_set(GF_ERR_NOMEM, "correlation: out of memory");
    gf_corr_set set = {0};
    if (st == GF_OK) st = gf_corr_collect(s, k0, k1, &f, o, &set);
    gf_vfield_free(&f);
    gf_container_defs cd;
    gf_config_container_defs(&s->cfg, &cd);
    if (st == GF_OK && radial) gf_corr_about_mean(&set);
    else if (st == GF_OK) st = gf_corr_fluctuations(&set, cd.depth);
    double unsteady = st == GF_OK ? gf_corr_unsteadiness(&set) : NAN;
    if (st == GF_OK && unsteady > GF_CORR_BURSTY) gf_corr_bursts(&set);
    for (size_t k = 0; st == GF_OK && k < set.npair; k++)
        gf_corr_pairs(&a, set.p + set.off[k], set.off[k + 1] - set.off[k]);
    gf_corr_set_free(&set);

    // C(r) = <du_i . du_j>_{|r_ij| in the bin} / <du^2>; r is the bin's mean pair distance.
    gf_table *t = &out->tables[out->ntables];
    if (st == GF_OK && (st = gf_table_init(t, "correlation", "r_d,c,pairs,fit")) == GF_OK) out->ntables++;
    double var = a.n > 0.0 ? a.s2 / a.n : NAN;
    double *fr = st == GF_OK ? GF_NEW(double, a.nb) : NULL, *fc = st == GF_OK ? GF_NEW(double, a.nb) : NULL;
    if (st == GF_OK && (!fr || !fc)) st = gf_error_set(GF_ERR_NOMEM, "correlation: out of memory");
    size_t nfit = 0;
    for (size_t b = 0; st == GF_OK && b < a.nb; b++) {
        if (a.cnt[b] == 0.0 || !(var > 0.0)) continue;
        double r = a.rsum[b] / a.cnt[b], c = a.sum[b] / a.cnt[b] / var;
        if (r >= GF_CORR_FITMIN) {
            fr[nfit] = r;
            fc[nfit++] = c;
        }
    }
    double amp = NAN, beta = NAN;
    if (st == GF_OK && nfit > 0 && gf_fit_exponential(fr, fc, nfit, &amp, &beta) != GF_OK) {
        gf_error_clear(); // no decay to fit (no flow, too few pairs): NaN
        amp = beta = NAN;
    }
    for (size_t b = 0; st == GF_OK && b < a.nb; b++) {
        if (a.cnt[b] == 0.0 || !(var > 0.0)) continue;
        double r = a.rsum[b] / a.cnt[b];
        double row[4] = {r, a.sum[b] / a.cnt[b] / var, a.cnt[b], amp * exp(-r / beta)};
        st = gf_table_add(t, row);
    }
    if (fr) GF_DELETE(fr, a.nb);
    if (fc) GF_DELETE(fc, a.nb);
    gf_corr_free(&a);
    if (st == GF_OK) st = gf_measure_value(out, "correlation_length", beta);
    if (st == GF_OK) st = gf_measure_value(out, "correlation_amplitude", amp);
    if (st == GF_OK) st = gf_measure_value(out, "correlation_unsteadiness", unsteady);
    if (st != GF_OK) return st;

    double ref = isfinite(amp) ? amp : 1.0;
    st = gf_measure_gnuplot(out,
                            "set datafile separator ','\n"
                            "set title 'Velocity correlation, %g x %g d region at z = %g'\n"
                            "set xlabel 'r (d)'\nset ylabel 'C(r)'\nset key top right\nset xrange [0:%g]\n"
                            "plot %.10g*exp(-x/%g) with lines dt 2 lc 'black' title 'DEM: beta = 1.87 d'",
                            o->corr_size, o->corr_size, o->corr_zc, GF_CORR_RMAX, ref, GF_CORR_DEM);
    if (st == GF_OK && isfinite(beta))
        st = gf_measure_gnuplot(out, ", \\\n  (x >= %g ? %.10g*exp(-x/%.10g) : 1/0) with lines lc 2 "
                                     "title 'fit: beta = %.3g d'", GF_CORR_FITMIN, amp, beta, beta);
    if (st == GF_OK && t->nrow)
        st = gf_measure_gnuplot(out, ", \\\n  'correlation.csv' skip 1 using 1:2 with linespoints pt 7 ps 0.4 lc 2 "
                                     "title 'measured'");
    if (st == GF_OK) st = gf_measure_gnuplot(out, "\n");
    return st;
}
