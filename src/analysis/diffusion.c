// SPDX-License-Identifier: MIT
// Particle diffusion length b_p = Var(dx_p) / (2 dz_p) of particles starting
// high in the centre, tracked as they drop (thesis Sec. 3.3: DEM 2.86e-3 d,
// spot 2.73e-3 d). In a cylinder dx_p is the tangential displacement
// (gf_diff_frame), which the axisymmetric mean flow does not produce.
#include <math.h>
#include <string.h>

#include "analysis/motion.h"
#include "core/alloc.h"
#include "core/error.h"
#include "core/stop.h"
#include "geom/container.h"
#include "granflow/analysis.h"
#include "granflow/defs.h"

#define GF_DIFF_DEM 2.86e-3 // thesis Sec. 3.3, d

/// The tracked particles' start positions, and per frame their displacements.
typedef struct gf_diff_work {
    gf_packing start; ///< the particles selected at the start frame
    gf_idmap map;     ///< id -> index in `start`
    size_t cap;
    double *dx, *dz, *c1, *c2; ///< displacements and two regressors, per present particle
    double *tout;              ///< per tracked particle: its first exit after the start frame (INFINITY: none)
} gf_diff_work;

static void gf_diff_free(gf_diff_work *w)
{
    gf_packing_free(&w->start);
    gf_idmap_free(&w->map);
    if (w->cap) {
        GF_DELETE(w->dx, w->cap);
        GF_DELETE(w->dz, w->cap);
        GF_DELETE(w->c1, w->cap);
        GF_DELETE(w->c2, w->cap);
        GF_DELETE(w->tout, w->cap);
    }
}

/// Removes from r (n entries) its projection on column c (already orthogonal
/// to the columns projected out before); returns false when c is ~0 (a
/// degenerate regressor, skipped).
static bool gf_diff_project(double *r, double *c, size_t n)
{
    double cc = 0.0, rc = 0.0, scale = 0.0;
    for (size_t i = 0; i < n; i++) scale = fmax(scale, fabs(c[i]));
    for (size_t i = 0; i < n; i++) cc += c[i] * c[i];
    if (!(cc > 1e-20 * scale * scale * (double)n)) return false;
    for (size_t i = 0; i < n; i++) rc += r[i] * c[i];
    for (size_t i = 0; i < n; i++) r[i] -= rc / cc * c[i];
    return true;
}

/// Variance of dx about the mean flow: the residual of dx regressed on
/// 1, x0 and x0 (z0 - mean z0), divided by n - (parameters). The mean flow
/// converges towards the orifice, so dx has a drift ~ -x0 dz b_s / Var(z)
/// (x0 measured from the orifice's x, container.orifice_x)
/// (kinematic model) that varies with the start position; high in the centre
/// (|x0| < 5, dz = 20) its spread is ~10x the diffusive Var(dx) = 2 b_p dz, so
/// it is removed as the part of dx linear in x0, with a slope varying with z0.
/// c1 = x0, c2 = x0 (z0 - mean z0) on entry; all three arrays are overwritten.
static double gf_diff_resid_var(double *dx, double *c1, double *c2, size_t n)
{
    double m = 0.0, m1 = 0.0, m2 = 0.0;
    for (size_t i = 0; i < n; i++) {
        m += dx[i];
        m1 += c1[i];
    }
    m /= (double)n;
    m1 /= (double)n;
    for (size_t i = 0; i < n; i++) {
        dx[i] -= m;
        c1[i] -= m1;
        m2 += c2[i];
    }
    m2 /= (double)n;
    size_t p = 1;
    // Gram-Schmidt: c2 made orthogonal to 1 and c1 before it is projected out.
    double c11 = 0.0, c21 = 0.0;
    for (size_t i = 0; i < n; i++) {
        c2[i] -= m2;
        c11 += c1[i] * c1[i];
        c21 += c2[i] * c1[i];
    }
    if (gf_diff_project(dx, c1, n)) {
        p++;
        for (size_t i = 0; i < n; i++) c2[i] -= c21 / c11 * c1[i];
    }
    if (gf_diff_project(dx, c2, n)) p++;
    if (n <= p) return NAN;
    double ss = 0.0;
    for (size_t i = 0; i < n; i++) ss += dx[i] * dx[i];
    return ss / (double)(n - p);
}

/// Selects the particles of frame `f` with |x - ox| < xhalf, above the
/// orifice at x = ox (r < xhalf in a cylinder), and z > z0, and notes when
/// each first exits after `f` (exits sorted by time): a recirculating run
/// puts an exited particle back on the free surface under the same id, and
/// its jump there is no displacement of the flow.
static gf_status gf_diff_select(const gf_frame *f, const gf_exit *exits, size_t nexits, const gf_analysis_opts *o,
                                bool radial, double ox, gf_diff_work *w)
{
    const gf_packing *pk = &f->pk;
    gf_status st = GF_OK;
    for (size_t i = 0; st == GF_OK && i < pk->n; i++)
        if ((radial ? hypot(pk->x[i], pk->y[i]) : fabs(pk->x[i] - ox)) < o->diff_xhalf && pk->z[i] > o->diff_z0)
            st = gf_packing_push(&w->start, pk->id[i], pk->layer ? pk->layer[i] : 0, pk->x[i], pk->y[i], pk->z[i],
                                 pk->r ? pk->r[i] : 0.5);
    if (st == GF_OK) st = gf_idmap_build(&w->start, &w->map);
    size_t n = w->start.n;
    if (st == GF_OK && n) {
        w->cap = n;
        w->dx = GF_NEW(double, n);
        w->dz = GF_NEW(double, n);
        w->c1 = GF_NEW(double, n);
        w->c2 = GF_NEW(double, n);
        w->tout = GF_NEW(double, n);
        if (!w->dx || !w->dz || !w->c1 || !w->c2 || !w->tout)
            st = gf_error_set(GF_ERR_NOMEM, "diffusion: out of memory");
    }
    if (st == GF_OK && n) {
        for (size_t i = 0; i < n; i++) w->tout[i] = INFINITY;
        for (size_t e = nexits; e-- > 0 && exits[e].time > f->time;) {
            size_t i = gf_idmap_find(&w->map, exits[e].id);
            if (i != SIZE_MAX) w->tout[i] = exits[e].time; // backwards: the earliest is written last
        }
    }
    return st;
}

/// One table row for frame `f`: time, mean |dz|, Var(dx) about the mean flow,
/// particles, raw Var(dx). Returns false when fewer than 4 particles remain.
/// In a cylinder (radial) dx is the displacement along the start position's
/// tangent, dt = (x0 dy - y0 dx) / r0: the mean flow is axisymmetric and
/// carries a particle in the plane through the axis and its start (thesis
/// Sec. 3.3's b_p is per lateral axis), so dt has no drift and no regression:
/// Var(dt) = 2 b_p |dz|, as Var(dx) in the box, with the same small
/// compression by the converging flow. (dx itself would keep the radial
/// convergence, a drift ~ r0 that varies with the azimuth: b_p ~4x.) The raw
/// column is then the same dt.
static bool gf_diff_frame(const gf_frame *f, gf_diff_work *w, bool radial, double ox, double row[5])
{
    const gf_packing *pk = &f->pk, *s0 = &w->start;
    double zbar = 0.0;
    for (size_t i = 0; i < s0->n; i++) zbar += s0->z[i];
    zbar /= (double)s0->n;
    size_t n = 0;
    double adz = 0.0, mx = 0.0;
    for (size_t j = 0; j < pk->n; j++) {
        size_t i = gf_idmap_find(&w->map, pk->id[j]);
        if (i == SIZE_MAX || w->tout[i] <= f->time) continue; // not tracked, or exited (and put back) since
        w->dx[n] = pk->x[j] - s0->x[i];
        w->dz[n] = pk->z[j] - s0->z[i];
        w->c1[n] = s0->x[i] - ox; // the drift grows with the distance from the orifice's x
        w->c2[n] = (s0->x[i] - ox) * (s0->z[i] - zbar);
        if (radial) {
            double r0 = hypot(s0->x[i], s0->y[i]), dy = pk->y[j] - s0->y[i];
            w->dx[n] = r0 > 0.0 ? (s0->x[i] * dy - s0->y[i] * w->dx[n]) / r0 : dy;
            w->c1[n] = w->c2[n] = 0.0; // no regressor: gf_diff_resid_var is then the variance about the mean
        }
        adz += fabs(w->dz[n]);
        mx += w->dx[n];
        n++;
    }
    if (n < 4) return false;
    mx /= (double)n;
    double raw = 0.0;
    for (size_t k = 0; k < n; k++) raw += (w->dx[k] - mx) * (w->dx[k] - mx);
    row[0] = f->time;
    row[1] = adz / (double)n;
    row[2] = gf_diff_resid_var(w->dx, w->c1, w->c2, n);
    row[3] = (double)n;
    row[4] = raw / (double)(n - 1);
    return isfinite(row[2]);
}

gf_status gf_measure_diffusion(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out)
{
    double t0, t1;
    gf_analysis_window(o, s, &t0, &t1);
    size_t k0, k1;
    gf_window_frames(s, t0, t1, &k0, &k1);
    // Particles start at the first frame of the window, not of the run: b_p is
    // a property of steady flow (thesis Sec. 3.3 fits it "during steady flow"),
    // and before the window the flow is still spreading up from the orifice.
    const gf_container ctr = gf_container_make(&s->cfg);
    bool radial = gf_container_profile_radial(&ctr);
    gf_diff_work w = {0};
    gf_container_defs cd;
    gf_config_container_defs(&s->cfg, &cd);
    gf_status st = k1 > k0 ? gf_diff_select(&s->frames[k0], s->exits, s->nexits, o, radial, cd.orifice.x, &w) : GF_OK;
    gf_table *t = &out->tables[out->ntables];
    if (st == GF_OK && (st = gf_table_init(t, "diffusion", "time_tau,mean_dz_d,var_dx_d2,particles,var_dx_raw_d2")) == GF_OK)
        out->ntables++;
    // b_p = Var(dx) / (2 |dz|): the slope of Var(dx) against mean |dz| through
    // the origin (thesis Sec. 3.3: Var grows in proportion to the distance dropped).
    double smv = 0.0, smm = 0.0;
    for (size_t k = k0 + 1; st == GF_OK && w.start.n && k < k1; k++) {
        if ((st = gf_stop_check(o->stop, "diffusion")) != GF_OK) break;
        double row[5];
        if (!gf_diff_frame(&s->frames[k], &w, radial, cd.orifice.x, row)) continue;
        st = gf_table_add(t, row);
        smv += row[1] * row[2];
        smm += row[1] * row[1];
    }
    double bp = smm > 0.0 ? 0.5 * smv / smm : NAN;
    size_t nstart = w.start.n;
    gf_diff_free(&w);
    if (st == GF_OK) st = gf_measure_value(out, "diffusion_length", bp);
    if (st == GF_OK) st = gf_measure_value(out, "diffusion_particles", (double)nstart);
    if (st != GF_OK) return st;
    st = gf_measure_gnuplot(out,
                            "set datafile separator ','\n"
                            "set title 'Particle diffusion: %zu particles from %s < %g, z > %g at t = %g tau'\n"
                            "set xlabel 'mean distance dropped |dz| (d)'\n"
                            "set ylabel '%s (d^2)'\n"
                            "set key top left\n"
                            "plot 2*%.10g*x with lines dt 2 lc 'black' title 'DEM: b_p = 2.86e-3 d'",
                            nstart, radial ? "r" : "|x|", o->diff_xhalf, o->diff_z0, k1 > k0 ? s->frames[k0].time : t0,
                            radial ? "Var(tangential dx)" : "Var(dx)", GF_DIFF_DEM);
    if (st == GF_OK && isfinite(bp))
        st = gf_measure_gnuplot(out, ", \\\n  2*%.10g*x with lines lc 2 title 'fit: b_p = %.3g d'", bp, bp);
    if (st == GF_OK && t->nrow)
        st = gf_measure_gnuplot(out, ", \\\n  'diffusion.csv' skip 1 using 2:3 with points pt 7 lc 2 "
                                     "title 'about the mean flow'");
    if (st == GF_OK) st = gf_measure_gnuplot(out, "\n");
    return st;
}
