// SPDX-License-Identifier: MIT
// The steady-flow window of a drainage, from its outflow: a DEM run starts
// from rest (the rate ramps up) and may end with the silo emptying (the rate
// falls); the thesis' averages (Sec. 3.3) belong to the part in between,
// where the particles exited grow linearly with time.
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "granflow/analysis.h"
#include "granflow/defs.h"

enum {
    GF_STEADY_MIN_FRAMES = 4,   // fewer snapshots cannot show a transient
    GF_STEADY_SMOOTH_COUNT = 100 // particles per smoothing span (rate noise ~ 1/sqrt of it)
};
#define GF_STEADY_TOL 0.05       // rates within 5% of the steady one are steady (noise permitting)
#define GF_STEADY_EDGE_TOL 0.005 // an edge chunk within 0.5% of the rest's rate is steady (noise permitting)
#define GF_STEADY_EDGE_SIGMAS 2.5 // ... or within this many standard deviations of the difference
#define GF_STEADY_MIN_SPAN 0.2   // a window shorter than this fraction of the run is not trusted

static int gf_steady_cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/// Median of v[0..n) (sorts a copy in tmp).
static double gf_steady_median(const double *v, size_t n, double *tmp)
{
    if (n == 0) return NAN;
    memcpy(tmp, v, n * sizeof *v);
    qsort(tmp, n, sizeof *tmp, gf_steady_cmp);
    return n % 2 ? tmp[n / 2] : 0.5 * (tmp[n / 2 - 1] + tmp[n / 2]);
}

static void gf_steady_fallback(const double *t, size_t n, gf_steady *w, const char *why)
{
    w->found = false;
    w->t0 = n ? t[0] + 0.25 * (t[n - 1] - t[0]) : 0.0;
    w->t1 = n ? t[n - 1] : 0.0;
    w->rate = NAN;
    snprintf(w->reason, sizeof w->reason, "%s: the default window, from a quarter of the run to its end", why);
}

/// A rough steady stretch of the smoothed rates s[0..m): the longest run
/// within max(5%, 3 sigma) of their median (over those reaching half the
/// largest), bridging single outliers. Frames [*a, *b]; false when none.
static bool gf_steady_rough(const double *s, size_t m, double sigma, double *tmp, size_t *a, size_t *b, double *tol)
{
    double smax = 0.0;
    for (size_t i = 0; i < m; i++) smax = fmax(smax, s[i]);
    size_t k = 0;
    for (size_t i = 0; i < m; i++)
        if (s[i] >= 0.5 * smax) tmp[m + k++] = s[i];
    double R = gf_steady_median(tmp + m, k, tmp);
    *tol = fmax(GF_STEADY_TOL * R, 3.0 * sigma);
    size_t best0 = 0, best1 = 0, run0 = 0, gap = 0;
    bool in = false;
    for (size_t i = 0; i < m; i++) {
        if (fabs(s[i] - R) <= *tol) {
            if (!in) run0 = i;
            in = true;
            gap = 0;
            if (i + 1 - run0 > best1 - best0) {
                best0 = run0;
                best1 = i + 1;
            }
        } else if (in && ++gap > 1) {
            in = false;
        }
    }
    *a = best0;
    *b = best1;
    return best1 >= best0 + 2;
}

/// Whether the edge chunk of the window [f0, f1] (its first J intervals when
/// dir = -1, its last J when dir = +1) flows at the rate of the rest of the
/// window: within max(0.5%, 2.5 standard deviations of the difference), the
/// counts' noise being sigma_c per interval.
static bool gf_steady_same(const double *t, const double *c, size_t f0, size_t f1, size_t J, double sigma_c, int dir)
{
    size_t a = dir < 0 ? f0 : f1 - J, b = dir < 0 ? f0 + J : f1;   // the chunk
    size_t ra = dir < 0 ? f0 + J : f0, rb = dir < 0 ? f1 : f1 - J; // the rest
    double r_chunk = (c[b] - c[a]) / (t[b] - t[a]), r_rest = (c[rb] - c[ra]) / (t[rb] - t[ra]);
    double s_chunk = sigma_c * sqrt((double)(b - a)) / (t[b] - t[a]);
    double s_rest = sigma_c * sqrt((double)(rb - ra)) / (t[rb] - t[ra]);
    return fabs(r_chunk - r_rest) <= fmax(GF_STEADY_EDGE_TOL * fabs(r_rest), GF_STEADY_EDGE_SIGMAS * hypot(s_chunk, s_rest));
}

/// Places one edge of the window [*f0, *f1] (dir = -1: the start, +1: the
/// end): the outermost frame, scanning from the series' end inwards, whose
/// edge chunk flows like the rest of the window. A start-up or an emptying
/// is cut off as far as the noise lets it be seen; scanning from outside (not
/// walking inwards) keeps a noisy chunk inside the steady part from pulling
/// the edge further in.
static void gf_steady_edge(const double *t, const double *c, size_t n, size_t *f0, size_t *f1, size_t L,
                           double sigma_c, int dir)
{
    size_t mid = (*f0 + *f1) / 2;
    if (dir < 0) {
        for (size_t f = 0; f < mid; f++) {
            size_t J = (*f1 - f) / 8 > L ? (*f1 - f) / 8 : L;
            if (*f1 < f + J + 2) break;
            if (gf_steady_same(t, c, f, *f1, J, sigma_c, -1)) {
                *f0 = f;
                return;
            }
        }
    } else {
        for (size_t f = n - 1; f > mid; f--) {
            size_t J = (f - *f0) / 8 > L ? (f - *f0) / 8 : L;
            if (f < *f0 + J + 2) break;
            if (gf_steady_same(t, c, *f0, f, J, sigma_c, +1)) {
                *f1 = f;
                return;
            }
        }
    }
}

gf_status gf_steady_window_curve(const double *t, const double *c, size_t n, gf_steady *w)
{
    memset(w, 0, sizeof *w);
    if (n < GF_STEADY_MIN_FRAMES) {
        gf_steady_fallback(t, n, w, "too few snapshots to find the steady flow");
        return GF_OK;
    }
    double total = c[n - 1] - c[0], span = t[n - 1] - t[0];
    if (!(span > 0) || !(total >= 10.0)) {
        char why[96];
        snprintf(why, sizeof why, "only %g particles exited", total);
        gf_steady_fallback(t, n, w, why);
        return GF_OK;
    }
    size_t m = n - 1;
    double *r = GF_NEW(double, m), *s = GF_NEW(double, m), *tmp = GF_NEW(double, 2 * m);
    if (!r || !s || !tmp) {
        if (r) GF_DELETE(r, m);
        if (s) GF_DELETE(s, m);
        if (tmp) GF_DELETE(tmp, 2 * m);
        return gf_error_set(GF_ERR_NOMEM, "steady window: out of memory for %zu snapshots", n);
    }
    for (size_t i = 0; i < m; i++) r[i] = t[i + 1] > t[i] ? (c[i + 1] - c[i]) / (t[i + 1] - t[i]) : 0.0;
    // Smoothing span: enough intervals to hold ~100 exits at the mean rate,
    // at most an eighth of the run.
    double per = total / (double)m;
    size_t L = per > 0 ? (size_t)ceil(GF_STEADY_SMOOTH_COUNT / per) : 1;
    if (L > m / 8) L = m / 8;
    if (L < 1) L = 1;
    for (size_t i = 0; i < m; i++) {
        size_t a = i >= L / 2 ? i - L / 2 : 0; // the span: frames a..a + L, centred on interval i
        if (a + L > m) a = m - L;
        s[i] = (c[a + L] - c[a]) / (t[a + L] - t[a]);
    }
    // The noise of one interval's count from successive differences (robust:
    // 1.4826 MAD / sqrt 2), and of a smoothed rate.
    for (size_t i = 0; i + 1 < m; i++) tmp[m + i] = fabs((c[i + 2] - c[i + 1]) - (c[i + 1] - c[i]));
    double sigma_c = m > 1 ? 1.4826 * gf_steady_median(tmp + m, m - 1, tmp) / sqrt(2.0) : 0.0;
    double sigma = sigma_c / sqrt((double)L) / (span / (double)m);
    size_t a, b;
    double tol;
    bool rough = gf_steady_rough(s, m, sigma, tmp, &a, &b, &tol);
    if (rough) {
        // Each edge tested against the rest of the window (gf_steady_edge),
        // twice round since each move changes the rest.
        size_t f0 = a, f1 = b;
        for (int round = 0; round < 2; round++) {
            gf_steady_edge(t, c, n, &f0, &f1, L, sigma_c, -1);
            gf_steady_edge(t, c, n, &f0, &f1, L, sigma_c, +1);
        }
        double slope = NAN, icpt;
        if (f1 < f0 + 2 || gf_fit_linear(t + f0, c + f0, f1 - f0 + 1, &slope, &icpt) != GF_OK) slope = NAN;
        gf_error_clear();
        w->t0 = t[f0];
        w->t1 = t[f1];
        w->rate = slope;
        w->found = true;
    }
    if (!rough || !(w->rate > 0) || w->t1 - w->t0 < GF_STEADY_MIN_SPAN * span) {
        char why[128];
        snprintf(why, sizeof why, "no steady outflow over %.0f%% of the run (the rate keeps changing)",
                 100.0 * GF_STEADY_MIN_SPAN);
        gf_steady_fallback(t, n, w, why);
    } else {
        // Why: the rate just outside the window, smoothed the same way.
        char before[96] = "from the first snapshot", after[96] = "to the end of the run";
        size_t i0 = 0, i1 = m;
        while (i0 < m && t[i0] < w->t0) i0++;
        while (i1 > 0 && t[i1] > w->t1) i1--;
        if (i0 > 0)
            snprintf(before, sizeof before, "after the start-up (rate %.3g/tau over %.4g..%.4g tau)",
                     (c[i0] - c[0]) / (t[i0] - t[0]), t[0], t[i0]);
        if (i1 < m)
            snprintf(after, sizeof after, "before the %s (rate %.3g/tau over %.4g..%.4g tau)",
                     (c[m] - c[i1]) / (t[m] - t[i1]) < w->rate ? "emptying" : "speed-up",
                     (c[m] - c[i1]) / (t[m] - t[i1]), t[i1], t[m]);
        snprintf(w->reason, sizeof w->reason,
                 "steady outflow of %.4g particles/tau, %s, %s", w->rate, before, after);
    }
    GF_DELETE(r, m);
    GF_DELETE(s, m);
    GF_DELETE(tmp, 2 * m);
    return GF_OK;
}

gf_status gf_steady_window(const gf_series *s, gf_steady *w)
{
    size_t n = s->nframes;
    double *t = GF_NEW(double, n + 1), *c = GF_NEW(double, n + 1);
    if (!t || !c) {
        if (t) GF_DELETE(t, n + 1);
        if (c) GF_DELETE(c, n + 1);
        return gf_error_set(GF_ERR_NOMEM, "steady window: out of memory");
    }
    gf_rundir_defs rd;
    gf_config_rundir_defs(&s->cfg, &rd);
    // The outflow curve: particles gone since the first frame, or, when exited
    // particles are put back (run.recirculate: the count stays constant), the
    // exits recorded by each frame's time (exits.csv is sorted by time).
    const bool by_exits = rd.recirculate && s->has_exits;
    size_t e = 0;
    for (size_t f = 0; f < n; f++) {
        t[f] = s->frames[f].time;
        while (by_exits && e < s->nexits && s->exits[e].time <= t[f]) e++;
        c[f] = by_exits ? (double)e : (double)s->n_initial - (double)s->frames[f].pk.n;
    }
    gf_status st = gf_steady_window_curve(t, c, n, w);
    GF_DELETE(t, n + 1);
    GF_DELETE(c, n + 1);
    return st;
}
