// SPDX-License-Identifier: MIT
// Outflow: particles exited vs time and the steady flow rate (SPEC 1.6; the
// 2009 paper's DEM drains at 131.1 particles per tau).
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>

#include "core/alloc.h"
#include "core/error.h"
#include "granflow/analysis.h"

/// The curve of exited particles vs time, and the points the rate is fitted to.
typedef struct gf_outflow_curve {
    double *t, *c;  ///< rows: time (tau), exited
    size_t n, cap;
    size_t fit0, fit1; ///< rows [fit0, fit1) are data points (exits or frames)
} gf_outflow_curve;

static void gf_outflow_free(gf_outflow_curve *k)
{
    if (k->t) GF_DELETE(k->t, k->cap);
    if (k->c) GF_DELETE(k->c, k->cap);
}

/// Whether the curve is made of the exits: only exits.csv's, which are exact;
/// exits read off the frames carry no more than the frames' counts.
static bool gf_outflow_from_exits(const gf_series *s) { return s->has_exits && !s->exits_derived; }

/// From the exits (one row per exit: a step curve, between a start row at the
/// first frame and a row holding the count to the last frame) when the series
/// has them, else n_initial - n per frame. Counts start at the first frame;
/// exits before it are not counted.
static gf_status gf_outflow_make(const gf_series *s, gf_outflow_curve *k)
{
    k->cap = (gf_outflow_from_exits(s) ? s->nexits + 2 : s->nframes) + 1;
    k->t = GF_NEW(double, k->cap);
    k->c = GF_NEW(double, k->cap);
    if (!k->t || !k->c) return gf_error_set(GF_ERR_NOMEM, "outflow: out of memory for %zu points", k->cap);
    if (!gf_outflow_from_exits(s)) {
        for (size_t f = 0; f < s->nframes; f++) {
            k->t[f] = s->frames[f].time;
            k->c[f] = (double)s->n_initial - (double)s->frames[f].pk.n;
        }
        k->n = k->fit1 = s->nframes;
        return GF_OK;
    }
    double t_first = s->nframes ? s->frames[0].time : -INFINITY;
    size_t m = 0, count = 0;
    if (s->nframes) {
        k->t[m] = t_first;
        k->c[m++] = 0.0;
    }
    k->fit0 = m;
    for (size_t e = 0; e < s->nexits; e++) {
        if (s->exits[e].time < t_first) continue;
        k->t[m] = s->exits[e].time;
        k->c[m++] = (double)++count;
    }
    k->fit1 = m;
    double t_last = s->nframes ? s->frames[s->nframes - 1].time : -INFINITY;
    if (m > 0 && t_last > k->t[m - 1]) {
        k->t[m] = t_last;
        k->c[m++] = (double)count;
    }
    k->n = m;
    return GF_OK;
}

gf_status gf_measure_outflow(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out)
{
    double t0, t1;
    gf_analysis_window(o, s, &t0, &t1);
    gf_outflow_curve k = {0};
    gf_status st = gf_outflow_make(s, &k);
    // The steady rate: least squares of exited vs time over the window. With
    // exits the points are (t_k, k), so exits at a constant rate R give exactly R.
    double a = NAN, b = NAN;
    if (st == GF_OK) {
        size_t m = 0;
        for (size_t r = k.fit0; r < k.fit1; r++)
            if (k.t[r] >= t0 && k.t[r] <= t1) m++;
        double *wt = GF_NEW(double, m + 1), *wc = GF_NEW(double, m + 1);
        if (!wt || !wc) st = gf_error_set(GF_ERR_NOMEM, "outflow: out of memory");
        m = 0;
        for (size_t r = k.fit0; st == GF_OK && r < k.fit1; r++)
            if (k.t[r] >= t0 && k.t[r] <= t1) {
                wt[m] = k.t[r];
                wc[m++] = k.c[r];
            }
        if (st == GF_OK && gf_fit_linear(wt, wc, m, &a, &b) != GF_OK) {
            gf_error_clear(); // too few points in the window: the rate is unknown (NaN)
            a = b = NAN;
        }
        if (wt) GF_DELETE(wt, m + 1);
        if (wc) GF_DELETE(wc, m + 1);
    }
    gf_table *tb = &out->tables[out->ntables];
    if (st == GF_OK && (st = gf_table_init(tb, "outflow", "time_tau,exited,fit_exited")) == GF_OK) out->ntables++;
    for (size_t r = 0; st == GF_OK && r < k.n; r++) {
        double row[3] = {k.t[r], k.c[r], k.t[r] >= t0 && k.t[r] <= t1 ? a * k.t[r] + b : NAN};
        st = gf_table_add(tb, row);
    }
    if (st == GF_OK) st = gf_measure_value(out, "flow_rate", a);
    if (st == GF_OK) st = gf_measure_value(out, "particles_exited", k.n ? k.c[k.n - 1] : 0.0);
    if (st == GF_OK)
        st = gf_measure_gnuplot(out,
                                "set datafile separator ','\n"
                                "set title 'Outflow (%s)'\n"
                                "set xlabel 'time t (tau)'\n"
                                "set ylabel 'particles exited'\n"
                                "set key top left\n"
                                "plot 'outflow.csv' skip 1 using 1:2 with steps lw 2 title 'exited', \\\n"
                                "     '' skip 1 using 1:3 with lines dt 2 lw 2 title 'fit over %.4g-%.4g tau: "
                                "%.5g particles/tau'\n",
                                gf_outflow_from_exits(s) ? "from exits.csv" : "from snapshot counts", t0, t1, a);
    gf_outflow_free(&k);
    return st;
}
