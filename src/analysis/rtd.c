// SPDX-License-Identifier: MIT
// Residence-time distribution per initial layer (SPEC 1.6): for every particle
// present in the first frame that later exits (within rtd.tmax of it), exit
// time minus the first frame's time, grouped by the particle's layer tag in
// the first frame. The exits are exits.csv's, or read off the frames
// (gf_series_derive_exits: the dumps of a DEM run), then each time is known
// to within +- s->exit_resolution, which the uncertainty of a mean includes.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/alloc.h"
#include "core/error.h"
#include "granflow/analysis.h"

enum { GF_RTD_BINS = 40 }; // histogram bins over the run length

typedef struct gf_rtd_rec {
    int64_t id;
    int32_t layer;
    double t; ///< residence time, tau (records of the first frame: 1 once the particle's first exit is counted)
} gf_rtd_rec;

static int gf_rtd_by_id(const void *pa, const void *pb)
{
    const gf_rtd_rec *a = pa, *b = pb;
    return (a->id > b->id) - (a->id < b->id);
}

static int gf_rtd_by_layer_time(const void *pa, const void *pb)
{
    const gf_rtd_rec *a = pa, *b = pb;
    if (a->layer != b->layer) return a->layer < b->layer ? -1 : 1;
    return (a->t > b->t) - (a->t < b->t);
}

static int gf_rtd_double_cmp(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    return (a > b) - (a < b);
}

/// Median of sorted v[0..n): the middle value, or the mean of the two middle ones.
static double gf_rtd_median(const double *v, size_t n)
{
    if (n == 0) return NAN;
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// Uncertainty of a mean of n residence times of sample sd: the standard
/// error sd / sqrt(n), combined with the exit-time resolution h taken as an
/// error of the whole mean, uniform in [-h, h] (h / sqrt 3).
static double gf_rtd_mean_err(double sd, size_t n, double h)
{
    return n > 1 ? hypot(sd / sqrt((double)n), h / sqrt(3.0)) : NAN;
}

/// The times of r[0..n) (n > 0) copied into scratch, their mean and sample
/// standard deviation (n - 1: NaN for a single particle).
static void gf_rtd_moments(const gf_rtd_rec *r, size_t n, double *scratch, double *mean, double *sd)
{
    double m = 0.0, var = 0.0;
    for (size_t i = 0; i < n; i++) {
        scratch[i] = r[i].t;
        m += r[i].t;
    }
    m /= (double)n;
    for (size_t i = 0; i < n; i++) var += (r[i].t - m) * (r[i].t - m);
    *mean = m;
    *sd = n > 1 ? sqrt(var / (double)(n - 1)) : NAN;
}

/// Adds the rows of one layer (records r[0..n), sorted by time) to both tables.
static gf_status gf_rtd_layer(const gf_rtd_rec *r, size_t n, double *scratch, double bw, size_t nbins, double res,
                              gf_table *tb, gf_table *th)
{
    double mean, sd;
    gf_rtd_moments(r, n, scratch, &mean, &sd);
    double row[7] = {(double)r[0].layer, (double)n, mean, sd, gf_rtd_median(scratch, n), r[0].t,
                     gf_rtd_mean_err(sd, n, res)};
    gf_status st = gf_table_add(tb, row);
    // Histogram normalised to a probability density over the layer's exited particles.
    for (size_t b = 0, i = 0; st == GF_OK && b < nbins; b++) {
        size_t cnt = 0;
        while (i < n && (r[i].t < bw * (double)(b + 1) || b + 1 == nbins)) {
            cnt++;
            i++;
        }
        double h[3] = {bw * ((double)b + 0.5), (double)r[0].layer, (double)cnt / ((double)n * bw)};
        st = gf_table_add(th, h);
    }
    return st;
}

static gf_status gf_rtd_plot(gf_measure_out *out, const gf_table *tb, const gf_series *s)
{
    char src[96];
    if (s->exits_derived) snprintf(src, sizeof src, " (exits from the snapshots, +- %.3g tau)", s->exit_resolution);
    else src[0] = '\0';
    if (tb->nrow == 0)
        return gf_measure_gnuplot(out, "set title 'Residence-time distribution'\n"
                                       "set xlabel 'residence time (tau)%s'\n"
                                       "set ylabel 'probability density (1/tau)'\n"
                                       "set xrange [0:1]\nset yrange [0:1]\n"
                                       "set label 1 'no particle has exited' at graph 0.5, 0.5 center\n"
                                       "plot -1 notitle\n"
                                       "unset label 1\nset autoscale\n",
                                       src);
    char layers[1024];
    size_t len = 0;
    layers[0] = '\0';
    for (size_t r = 0; r < tb->nrow && len + 16 < sizeof layers; r++)
        len += (size_t)snprintf(layers + len, sizeof layers - len, "%s%d", r ? " " : "", (int)tb->v[r * tb->ncol]);
    return gf_measure_gnuplot(out,
                              "set datafile separator ','\n"
                              "set title 'Residence-time distribution by initial layer'\n"
                              "set xlabel 'residence time (tau)%s'\n"
                              "set ylabel 'probability density (1/tau)'\n"
                              "set key top right\n"
                              "LAYERS = '%s'\n"
                              "plot for [i=1:words(LAYERS)] 'rtd_hist.csv' skip 1 "
                              "using 1:(column(2) == word(LAYERS, i) + 0 ? column(3) : 1/0) "
                              "with histeps lw 2 title 'layer '.word(LAYERS, i)\n",
                              src, layers);
}

gf_status gf_measure_rtd(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out)
{
    if (!s->has_exits)
        return gf_error_set(GF_ERR_PARAM,
                            "rtd: needs the exit time of every particle (the exits.csv of a granflow run, or "
                            "exits read off the snapshots, which `granflow analyze` does for dumps); "
                            "this series has none");
    if (s->nframes == 0) return gf_error_set(GF_ERR_PARAM, "rtd: the series has no frames");
    const gf_packing *p0 = &s->frames[0].pk;
    double t_first = s->frames[0].time, t_last = s->frames[s->nframes - 1].time;
    size_t n0 = p0->n, cap = s->nexits + 1;
    const double h = s->exits_derived ? s->exit_resolution : 0.0;
    const double tmax_cut = isnan(o->rtd_tmax) ? INFINITY : o->rtd_tmax;
    gf_rtd_rec *first = GF_NEW(gf_rtd_rec, n0 + 1), *rec = GF_NEW(gf_rtd_rec, cap);
    double *scratch = GF_NEW(double, cap);
    gf_status st = first && rec && scratch ? GF_OK : gf_error_set(GF_ERR_NOMEM, "rtd: out of memory");
    size_t n = 0;
    if (st == GF_OK) {
        for (size_t i = 0; i < n0; i++) first[i] = (gf_rtd_rec){p0->id[i], p0->layer[i], 0.0};
        qsort(first, n0, sizeof *first, gf_rtd_by_id);
        // Exits of particles not in the first frame, or before it, have no known entry time.
        // A particle's residence time ends at its first exit (exits sorted by time): in a
        // recirculating run it comes back and exits again, a later pass (`zones` measures those).
        for (size_t e = 0; e < s->nexits; e++) {
            if (s->exits[e].time < t_first || s->exits[e].time - t_first > tmax_cut) continue;
            gf_rtd_rec key = {s->exits[e].id, 0, 0.0};
            gf_rtd_rec *hit = n0 ? bsearch(&key, first, n0, sizeof *first, gf_rtd_by_id) : NULL;
            if (!hit || hit->t != 0.0) continue;
            hit->t = 1.0; // its first exit is counted
            rec[n++] = (gf_rtd_rec){key.id, hit->layer, s->exits[e].time - t_first};
        }
        qsort(rec, n, sizeof *rec, gf_rtd_by_layer_time);
    }
    double tmax = 0.0;
    for (size_t i = 0; i < n; i++) tmax = fmax(tmax, rec[i].t);
    double span = t_last - t_first > 0 ? t_last - t_first : tmax;
    if (tmax_cut < span) span = tmax_cut; // the histograms of two runs cut at one time share their bins
    double bw = span > 0 ? span / GF_RTD_BINS : 1.0;
    size_t nbins = (size_t)floor(tmax / bw) + 1;
    gf_table *tb = &out->tables[out->ntables];
    if (st == GF_OK && (st = gf_table_init(tb, "rtd", "layer,count,mean_tau,sd_tau,median_tau,first_tau,err_mean_tau")) == GF_OK)
        out->ntables++;
    gf_table *th = &out->tables[out->ntables];
    if (st == GF_OK && (st = gf_table_init(th, "rtd_hist", "time_tau,layer,pdf")) == GF_OK) out->ntables++;
    for (size_t i = 0; st == GF_OK && i < n;) {
        size_t j = i;
        while (j < n && rec[j].layer == rec[i].layer) j++;
        st = gf_rtd_layer(rec + i, j - i, scratch, bw, nbins, h, tb, th);
        i = j;
    }
    double mean = NAN, median = NAN, err = NAN;
    if (st == GF_OK && n > 0) {
        double sd;
        gf_rtd_moments(rec, n, scratch, &mean, &sd);
        err = gf_rtd_mean_err(sd, n, h);
        qsort(scratch, n, sizeof *scratch, gf_rtd_double_cmp);
        median = gf_rtd_median(scratch, n);
    }
    if (st == GF_OK) st = gf_measure_value(out, "rtd_mean", mean);
    if (st == GF_OK) st = gf_measure_value(out, "rtd_median", median);
    if (st == GF_OK) st = gf_measure_value(out, "rtd_exited", (double)n);
    if (st == GF_OK) st = gf_measure_value(out, "rtd_mean_err", err);
    if (st == GF_OK) st = gf_measure_value(out, "rtd_resolution", h);
    if (st == GF_OK) st = gf_measure_value(out, "rtd_tmax", isfinite(tmax_cut) ? tmax_cut : fmax(t_last - t_first, tmax));
    if (st == GF_OK) st = gf_rtd_plot(out, tb, s);
    if (first) GF_DELETE(first, n0 + 1);
    if (rec) GF_DELETE(rec, cap);
    if (scratch) GF_DELETE(scratch, cap);
    return st;
}
