// SPDX-License-Identifier: MIT
// Packing badness: the summed squared overlaps per particle (2009 paper Sec. 5, Fig. 9).
#include <math.h>
#include <string.h>

#include "analysis/structure.h"
#include "core/error.h"
#include "core/stop.h"
#include "geom/celllist.h"
#include "granflow/analysis.h"

// The paper's Fig. 9 values over 40 tau < t < 160 tau.
#define GF_BADNESS_FULL_RELAX 0.0011
#define GF_BADNESS_DEM 0.00365

static bool gf_in_box(const gf_packing *pk, size_t i, const double lo[3], const double hi[3])
{
    return pk->x[i] >= lo[0] && pk->x[i] <= hi[0] && pk->y[i] >= lo[1] && pk->y[i] <= hi[1] &&
           pk->z[i] >= lo[2] && pk->z[i] <= hi[2];
}

// Sum over i in the box and every j != i (anywhere) of delta_ij^2; *p = the
// particles i. Each overlapping pair with both centres in the box counts
// twice, once from each side, as the paper's sum over i and its n_i contacts.
static gf_status gf_badness_sum(const gf_packing *pk, const double lo[3], const double hi[3], double *sum,
                                size_t *p)
{
    *sum = 0.0;
    *p = 0;
    double rmax = 0.0;
    for (size_t i = 0; i < pk->n; i++)
        if (pk->r[i] > rmax) rmax = pk->r[i];
    gf_celllist cl = {0};
    gf_status st = gf_celllist_fit(&cl, pk->x, pk->y, pk->z, pk->n, fmax(2.0 * rmax, 0.25));
    if (st != GF_OK) {
        gf_celllist_free(&cl);
        return st;
    }
    double s = 0.0;
    size_t count = 0;
    for (size_t i = 0; i < pk->n; i++) {
        if (!gf_in_box(pk, i, lo, hi)) continue;
        count++;
        const double c[3] = {pk->x[i], pk->y[i], pk->z[i]};
        gf_celllist_near it;
        gf_celllist_near_start(&it, &cl, c, pk->r[i] + rmax);
        for (size_t j; gf_celllist_near_next(&it, &j);) {
            if (j == i) continue;
            double dx = pk->x[j] - c[0], dy = pk->y[j] - c[1], dz = pk->z[j] - c[2];
            double dist = sqrt(dx * dx + dy * dy + dz * dz);
            double delta = pk->r[i] + pk->r[j] - dist;
            if (delta > 0.0) s += delta * delta;
        }
    }
    gf_celllist_free(&cl);
    *sum = s;
    *p = count;
    return GF_OK;
}

// 2009 paper Sec. 5: B = (1/p) sum_i sum_{j=1}^{n_i} delta_ij^2 / d^2 (d = 1).
double gf_badness(const gf_packing *pk, const double lo[3], const double hi[3])
{
    double sum;
    size_t p;
    if (gf_badness_sum(pk, lo, hi, &sum, &p) != GF_OK || p == 0) return NAN;
    return sum / (double)p;
}

gf_status gf_measure_badness(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out)
{
    size_t k0, k1;
    gf_structure_window(s, o, &k0, &k1);
    gf_table *t = &out->tables[out->ntables];
    gf_status st = gf_table_init(t, "badness", "time_tau,badness,particles");
    if (st != GF_OK) return st;
    out->ntables++;
    const double lo[3] = {o->gr_x0, -INFINITY, o->gr_z0}, hi[3] = {o->gr_x1, INFINITY, o->gr_z1};
    double total = 0.0;
    size_t nf = 0;
    for (size_t k = k0; k < k1; k++) {
        double sum;
        size_t p;
        st = gf_stop_check(o->stop, "badness");
        if (st == GF_OK) st = gf_badness_sum(&s->frames[k].pk, lo, hi, &sum, &p);
        if (st != GF_OK) return st;
        double b = p ? sum / (double)p : NAN;
        const double row[3] = {s->frames[k].time, b, (double)p};
        st = gf_table_add(t, row);
        if (st != GF_OK) return st;
        if (p) {
            total += b;
            nf++;
        }
    }
    st = gf_measure_value(out, "badness", nf ? total / (double)nf : NAN);
    if (st != GF_OK) return st;
    return gf_measure_gnuplot(
        out,
        "set datafile separator ','\n"
        "set xlabel 't (tau)'\n"
        "set ylabel 'badness B'\n"
        "set logscale y\n"
        "set format y '%%g'\n"
        "set key top right\n"
        "set title 'Packing badness in %g < x < %g, %g < z < %g (d)'\n"
        "plot 'badness.csv' skip 1 using 1:2 with linespoints pt 7 ps 0.6 title 'this run', \\\n"
        "     %g with lines dt 2 lw 2 title 'paper: full relaxation (%g)', \\\n"
        "     %g with lines dt 3 lw 2 title 'paper: DEM (%g)'\n",
        o->gr_x0, o->gr_x1, o->gr_z0, o->gr_z1, GF_BADNESS_FULL_RELAX, GF_BADNESS_FULL_RELAX,
        GF_BADNESS_DEM, GF_BADNESS_DEM);
}
