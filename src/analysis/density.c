// SPDX-License-Identifier: MIT
// Density drop: particles in the slice dens_z0 < z < dens_z1 per frame (SPEC
// 1.6; 2009 paper Sec. 2: in DEM 9,400 in 50 < z < 70 falls to 8,850 in flow).
#include <math.h>
#include <stdbool.h>

#include "core/error.h"
#include "granflow/analysis.h"

gf_status gf_measure_density(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out)
{
    if (!(o->dens_z0 < o->dens_z1))
        return gf_error_set(GF_ERR_PARAM, "density: the slice needs density.z0 < density.z1, got %g and %g",
                            o->dens_z0, o->dens_z1);
    double t0, t1;
    gf_analysis_window(o, s, &t0, &t1);
    gf_table *tb = &out->tables[out->ntables];
    gf_status st = gf_table_init(tb, "density", "time_tau,count");
    if (st != GF_OK) return st;
    out->ntables++;
    double sum = 0.0, first = NAN;
    size_t nwin = 0;
    for (size_t k = 0; k < s->nframes; k++) {
        const gf_packing *p = &s->frames[k].pk;
        size_t cnt = 0;
        for (size_t i = 0; i < p->n; i++) cnt += p->z[i] > o->dens_z0 && p->z[i] < o->dens_z1;
        double row[2] = {s->frames[k].time, (double)cnt};
        if ((st = gf_table_add(tb, row)) != GF_OK) return st;
        if (k == 0) first = (double)cnt;
        if (row[0] >= t0 && row[0] <= t1) {
            sum += (double)cnt;
            nwin++;
        }
    }
    double steady = nwin ? sum / (double)nwin : NAN;
    // A slice the packing never reached (the default 50 < z < 70 above a
    // hopper filled to 40 d) measures nothing: NaN, not a drop from 0 to 0.
    const bool empty = !(first > 0.0);
    if (empty) first = steady = NAN;
    if ((st = gf_measure_value(out, "density_initial", first)) != GF_OK) return st;
    if ((st = gf_measure_value(out, "density_steady", steady)) != GF_OK) return st;
    return gf_measure_gnuplot(out,
                              "set datafile separator ','\n"
                              "set title 'Particles in the slice %g < z < %g (d)%s'\n"
                              "set xlabel 'time t (tau)'\n"
                              "set ylabel 'particles in the slice'\n"
                              "set key bottom left\n%s"
                              "set arrow from %.10g, graph 0 to %.10g, graph 1 nohead dt 3\n"
                              "plot 'density.csv' skip 1 using 1:2 with linespoints pt 7 ps 0.6 title 'count', \\\n"
                              "     %.10g with lines dt 2 lw 2 title 'steady mean over %.4g-%.4g tau: %.6g'\n"
                              "unset arrow\n",
                              o->dens_z0, o->dens_z1,
                              empty ? ": empty in the first frame, set density.z0 and density.z1" : "",
                              empty ? "set yrange [0:1]\n" : "", t0, t0, isnan(steady) ? 0.0 : steady, t0, t1, steady);
}
