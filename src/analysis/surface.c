// SPDX-License-Identifier: MIT
// Free-surface angle per frame by the 2009 paper's regression (Sec. 3, Fig. 7).
//
// Columns x_j = dx j - dx/2, j = 1..ncols (the paper: 2.5 j - 1.25, j = 1..10);
// z_j = the highest particle centre with ||x - orifice_x| - x_j| < dx/2
// (columns with no particle are skipped); the slope of the least-squares line through the
// (x_j, z_j) gives the angle atan(slope) in degrees. Sign: a draining silo's
// surface dips towards the centre and rises towards the walls, so its angle is
// positive (as in the paper's Fig. 7); a heap peaked at the centre is negative.
#include <math.h>

#include "core/alloc.h"
#include "core/error.h"
#include "core/stop.h"
#include "granflow/analysis.h"
#include "granflow/defs.h"

static const double gf_deg_per_rad = 57.295779513082320876798154814105;

/// The regression slope of one packing's surface, NaN with fewer than 2 columns.
static double gf_surface_slope(const gf_packing *p, double ox, double dx, size_t ncols, double *zmax, double *xj)
{
    for (size_t j = 0; j < ncols; j++) {
        zmax[j] = -INFINITY;
        xj[j] = dx * (double)(j + 1) - 0.5 * dx;
    }
    for (size_t i = 0; i < p->n; i++) {
        double ax = fabs(p->x[i] - ox); // distance from the orifice's x
        // The column is ||x| - x_j| < dx/2, i.e. (j-1) dx < |x| < j dx (open at both ends).
        double u = ax / dx;
        double fl = floor(u);
        if (u == fl) continue; // on a column boundary: in no column
        size_t j = (size_t)fl;
        if (fl >= (double)ncols) continue;
        if (p->z[i] > zmax[j]) zmax[j] = p->z[i];
    }
    size_t m = 0;
    for (size_t j = 0; j < ncols; j++)
        if (zmax[j] > -INFINITY) {
            xj[m] = xj[j];
            zmax[m++] = zmax[j];
        }
    double a, b;
    if (gf_fit_linear(xj, zmax, m, &a, &b) != GF_OK) {
        gf_error_clear();
        return NAN;
    }
    return a;
}

gf_status gf_measure_surface(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out)
{
    if (!(o->surf_dx > 0) || o->surf_ncols < 2)
        return gf_error_set(GF_ERR_PARAM, "surface: needs surface.dx > 0 and surface.columns >= 2, got %g and %zu",
                            o->surf_dx, o->surf_ncols);
    double t0, t1;
    gf_analysis_window(o, s, &t0, &t1);
    double *zmax = GF_NEW(double, o->surf_ncols), *xj = GF_NEW(double, o->surf_ncols);
    gf_status st = zmax && xj ? GF_OK : gf_error_set(GF_ERR_NOMEM, "surface: out of memory");
    gf_table *tb = &out->tables[out->ntables];
    if (st == GF_OK && (st = gf_table_init(tb, "surface", "time_tau,slope,angle_deg")) == GF_OK) out->ntables++;
    double sum = 0.0;
    size_t nwin = 0;
    gf_container_defs cd;
    gf_config_container_defs(&s->cfg, &cd);
    for (size_t k = 0; st == GF_OK && k < s->nframes; k++) {
        if ((st = gf_stop_check(o->stop, "surface")) != GF_OK) break;
        double slope = gf_surface_slope(&s->frames[k].pk, cd.orifice.x, o->surf_dx, o->surf_ncols, zmax, xj);
        double row[3] = {s->frames[k].time, slope, atan(slope) * gf_deg_per_rad};
        st = gf_table_add(tb, row);
        if (row[0] >= t0 && row[0] <= t1 && !isnan(row[2])) {
            sum += row[2];
            nwin++;
        }
    }
    if (zmax) GF_DELETE(zmax, o->surf_ncols);
    if (xj) GF_DELETE(xj, o->surf_ncols);
    if (st != GF_OK) return st;
    double mean = nwin ? sum / (double)nwin : NAN;
    if ((st = gf_measure_value(out, "surface_angle", mean)) != GF_OK) return st;
    return gf_measure_gnuplot(out,
                              "set datafile separator ','\n"
                              "set title 'Free-surface angle (regression over %zu columns of %g d)'\n"
                              "set xlabel 'time t (tau)'\n"
                              "set ylabel 'surface angle (degrees)'\n"
                              "set key top left\n"
                              "plot 'surface.csv' skip 1 using 1:3 with linespoints pt 7 ps 0.6 title 'angle', \\\n"
                              "     %.10g with lines dt 2 lw 2 title 'mean over %.4g-%.4g tau: %.4g degrees'\n",
                              o->surf_ncols, o->surf_dx, isnan(mean) ? 0.0 : mean, t0, t1, mean);
}
