// SPDX-License-Identifier: MIT
// Radial distribution g(r) and bond-angle distribution g3(theta) in a region
// of the flow (2009 paper Sec. 5, Fig. 11; thesis Sec. 3.4, Figs. 3-6, 3-7).
#include <math.h>
#include <string.h>

#include "analysis/structure.h"
#include "core/alloc.h"
#include "core/error.h"
#include "core/stop.h"
#include "geom/celllist.h"
#include "granflow/analysis.h"
#include "granflow/defs.h"

#define GF_PI 3.14159265358979323846
#define GF_G3_BINS 180 // 1 degree bins on 0..180

// The container's walls: x = x0, x1, y = y0, y1 and the base z = z0 (no top).
typedef struct gf_walls {
    double x0, x1, y0, y1, z0;
} gf_walls;

// Volume of the cap of height h cut from a ball of radius R.
static double gf_cap(double R, double h)
{
    if (h <= 0.0) return 0.0;
    if (h > 2.0 * R) h = 2.0 * R;
    return GF_PI * h * h * (3.0 * R - h) / 3.0;
}

// Volume of the ball of radius R about a centre at distances dlo, dhi from
// two parallel walls (the two caps never overlap when the centre lies between).
static double gf_ball_in_slab(double R, double dlo, double dhi)
{
    double v = 4.0 / 3.0 * GF_PI * R * R * R - gf_cap(R, R - dlo) - gf_cap(R, R - dhi);
    return v > 0.0 ? v : 0.0;
}

static bool gf_xz_inside(const gf_walls *w, double x, double z)
{
    return x >= w->x0 && x <= w->x1 && z >= w->z0;
}

static void gf_sort_small(double *a, int n)
{
    for (int i = 1; i < n; i++) {
        double v = a[i];
        int j = i - 1;
        while (j >= 0 && a[j] > v) {
            a[j + 1] = a[j];
            j--;
        }
        a[j + 1] = v;
    }
}

// Fraction of the circle of radius rho about (cx, cz) in the xz plane that
// lies inside the walls x0 <= x <= x1, z >= z0: exact, from the angles where
// it crosses them.
static double gf_arc_inside(const gf_walls *w, double rho, double cx, double cz)
{
    if (rho <= 0.0) return gf_xz_inside(w, cx, cz) ? 1.0 : 0.0;
    double ang[8];
    int n = 0;
    const double xs[2] = {w->x0, w->x1};
    for (int k = 0; k < 2; k++) {
        double c = (xs[k] - cx) / rho;
        if (c > -1.0 && c < 1.0) {
            double a = acos(c);
            ang[n++] = a;
            ang[n++] = 2.0 * GF_PI - a;
        }
    }
    double s = (w->z0 - cz) / rho;
    if (s > -1.0 && s < 1.0) {
        double a = asin(s);
        ang[n++] = a < 0.0 ? a + 2.0 * GF_PI : a;
        ang[n++] = GF_PI - a;
    }
    gf_sort_small(ang, n);
    ang[n++] = 2.0 * GF_PI;
    double inside = 0.0, prev = 0.0;
    for (int k = 0; k < n; k++) {
        double mid = 0.5 * (prev + ang[k]);
        if (ang[k] > prev && gf_xz_inside(w, cx + rho * cos(mid), cz + rho * sin(mid))) inside += ang[k] - prev;
        prev = ang[k];
    }
    return inside / (2.0 * GF_PI);
}

// Fraction of the sphere of radius r about c inside all the walls. By
// Archimedes' hat-box theorem the area is uniform in u = (y - c_y) / r, so
// f = (1/2) int du (fraction of the circle at that u inside in x and z),
// integrated by 8-point Gauss-Legendre between the u where that fraction has
// kinks (the circle's radius equal to a wall or corner distance).
static double gf_sphere_inside(const gf_walls *w, const double c[3], double r)
{
    static const double gx[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                 -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                 0.7966664774136267,  0.9602898564975363};
    static const double gw[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                 0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                 0.2223810344533745, 0.1012285362903763};
    double ulo = fmax(-1.0, (w->y0 - c[1]) / r), uhi = fmin(1.0, (w->y1 - c[1]) / r);
    if (!(uhi > ulo)) return 0.0;
    double dx0 = c[0] - w->x0, dx1 = w->x1 - c[0], dz = c[2] - w->z0;
    const double d[5] = {dx0, dx1, dz, sqrt(dx0 * dx0 + dz * dz), sqrt(dx1 * dx1 + dz * dz)};
    double br[12];
    int nb = 0;
    br[nb++] = ulo;
    for (int k = 0; k < 5; k++) {
        if (!(d[k] > 0.0 && d[k] < r)) continue;
        double u = sqrt(1.0 - (d[k] / r) * (d[k] / r));
        if (u > ulo && u < uhi) br[nb++] = u;
        if (-u > ulo && -u < uhi) br[nb++] = -u;
    }
    br[nb++] = uhi;
    gf_sort_small(br, nb);
    double f = 0.0;
    for (int k = 0; k + 1 < nb; k++) {
        double h = 0.5 * (br[k + 1] - br[k]), m = 0.5 * (br[k + 1] + br[k]);
        if (h <= 0.0) continue;
        for (int q = 0; q < 8; q++) {
            double u = m + h * gx[q];
            double rho = r * sqrt(fmax(0.0, 1.0 - u * u));
            f += h * gw[q] * gf_arc_inside(w, rho, c[0], c[2]);
        }
    }
    return 0.5 * f;
}

// Adds to vin[k] the volume of shell k (radii k dr .. (k+1) dr) about c that
// lies inside the container. Exact (ball in a slab) while the shell stays
// clear of the x walls and the base; beyond, the sphere fraction at the
// shell's mid radius times the shell volume.
static void gf_shell_volumes(const gf_walls *w, const double c[3], double dr, size_t nbin, double *vin)
{
    double dlo = c[1] - w->y0, dhi = w->y1 - c[1];
    double dclear = fmin(fmin(c[0] - w->x0, w->x1 - c[0]), c[2] - w->z0);
    double vprev = 0.0;
    for (size_t k = 0; k < nbin; k++) {
        double r0 = (double)k * dr, r1 = (double)(k + 1) * dr;
        if (r1 <= dclear) {
            double v = gf_ball_in_slab(r1, dlo, dhi);
            vin[k] += v - vprev;
            vprev = v;
        } else {
            double rm = 0.5 * (r0 + r1);
            vin[k] += 4.0 / 3.0 * GF_PI * (r1 * r1 * r1 - r0 * r0 * r0) * gf_sphere_inside(w, c, rm);
        }
    }
}

typedef struct gf_gr_acc {
    size_t nbin;
    double dr, rcut;
    double *count;   ///< pairs per r bin (each pair once per centre)
    double *norm;    ///< sum over frames of density x shell volume inside, per bin
    double *vin;     ///< scratch: shell volumes inside for one frame
    double *angle;   ///< bond angles per degree bin
    double centres;  ///< centres over all frames
    double bonds;    ///< neighbours within rcut over all centres
    double (*nb)[3]; ///< scratch: bond vectors of one centre
    size_t nbcap;
} gf_gr_acc;

static gf_status gf_gr_push_bond(gf_gr_acc *a, size_t *n, double dx, double dy, double dz)
{
    if (*n == a->nbcap) {
        size_t cap = a->nbcap ? 2 * a->nbcap : 64;
        double(*nb)[3] = gf_realloc(a->nb, sizeof(*a->nb) * a->nbcap, sizeof(*a->nb) * cap);
        if (!nb) return gf_error_set(GF_ERR_NOMEM, "g3: out of memory for %zu bonds", cap);
        a->nb = nb;
        a->nbcap = cap;
    }
    a->nb[*n][0] = dx;
    a->nb[*n][1] = dy;
    a->nb[*n][2] = dz;
    (*n)++;
    return GF_OK;
}

static gf_status gf_gr_frame(const gf_packing *pk, const gf_analysis_opts *o, const gf_walls *w, double vregion,
                             gf_gr_acc *a)
{
    double rmax = (double)a->nbin * a->dr, rmax2 = rmax * rmax, rcut2 = a->rcut * a->rcut;
    gf_celllist cl = {0};
    gf_status st = gf_celllist_fit(&cl, pk->x, pk->y, pk->z, pk->n, fmax(0.5 * rmax, 0.5));
    if (st != GF_OK) {
        gf_celllist_free(&cl);
        return st;
    }
    memset(a->vin, 0, sizeof(double) * a->nbin);
    size_t ncentre = 0;
    for (size_t i = 0; i < pk->n && st == GF_OK; i++) {
        const double c[3] = {pk->x[i], pk->y[i], pk->z[i]};
        if (!(c[0] > o->gr_x0 && c[0] < o->gr_x1 && c[2] > o->gr_z0 && c[2] < o->gr_z1)) continue;
        if (!isfinite(c[1])) continue;
        if ((st = gf_stop_check(o->stop, "g(r)")) != GF_OK) break; // a large gr.rmax: minutes per frame
        ncentre++;
        gf_shell_volumes(w, c, a->dr, a->nbin, a->vin);
        size_t nbond = 0;
        gf_celllist_near it;
        gf_celllist_near_start(&it, &cl, c, rmax);
        for (size_t j; st == GF_OK && gf_celllist_near_next(&it, &j);) {
            if (j == i) continue;
            double dx = pk->x[j] - c[0], dy = pk->y[j] - c[1], dz = pk->z[j] - c[2];
            double d2 = dx * dx + dy * dy + dz * dz;
            if (d2 >= rmax2) continue;
            size_t bin = (size_t)(sqrt(d2) / a->dr);
            a->count[bin < a->nbin ? bin : a->nbin - 1] += 1.0;
            if (d2 < rcut2 && d2 > 0.0) st = gf_gr_push_bond(a, &nbond, dx, dy, dz);
        }
        a->bonds += (double)nbond;
        // Thesis Sec. 3.4: the angle j-i-k between every two first neighbours.
        for (size_t p = 0; p < nbond; p++) {
            const double *u = a->nb[p];
            double uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
            for (size_t q = p + 1; q < nbond; q++) {
                const double *v = a->nb[q];
                double vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
                double cs = (u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) / sqrt(uu * vv);
                cs = cs > 1.0 ? 1.0 : cs < -1.0 ? -1.0 : cs;
                size_t bin = (size_t)(acos(cs) * (180.0 / GF_PI));
                a->angle[bin < GF_G3_BINS ? bin : GF_G3_BINS - 1] += 1.0;
            }
        }
    }
    gf_celllist_free(&cl);
    if (st != GF_OK) return st;
    // Ideal-gas reference: the frame's number density in the region.
    double rho = (double)ncentre / vregion;
    for (size_t k = 0; k < a->nbin; k++) a->norm[k] += rho * a->vin[k];
    a->centres += (double)ncentre;
    return GF_OK;
}

static void gf_gr_acc_free(gf_gr_acc *a)
{
    GF_DELETE(a->count, a->nbin);
    GF_DELETE(a->norm, a->nbin);
    GF_DELETE(a->vin, a->nbin);
    GF_DELETE(a->angle, GF_G3_BINS);
    if (a->nb) GF_DELETE(a->nb, a->nbcap);
    memset(a, 0, sizeof *a);
}

static gf_status gf_gr_tables(const gf_gr_acc *a, gf_measure_out *out, double *peak_r)
{
    gf_table *t = &out->tables[out->ntables];
    gf_status st = gf_table_init(t, "gr", "r_d,g");
    if (st != GF_OK) return st;
    out->ntables++;
    double best = -INFINITY;
    *peak_r = NAN;
    for (size_t k = 0; k < a->nbin && st == GF_OK; k++) {
        double r = ((double)k + 0.5) * a->dr;
        double g = a->norm[k] > 0.0 ? a->count[k] / a->norm[k] : NAN;
        if (g > best) {
            best = g;
            *peak_r = r;
        }
        const double row[2] = {r, g};
        st = gf_table_add(t, row);
    }
    if (st != GF_OK) return st;
    t = &out->tables[out->ntables];
    st = gf_table_init(t, "g3", "theta_deg,g3");
    if (st != GF_OK) return st;
    out->ntables++;
    double total = 0.0;
    for (size_t k = 0; k < GF_G3_BINS; k++) total += a->angle[k];
    for (size_t k = 0; k < GF_G3_BINS && st == GF_OK; k++) {
        // A probability density per degree (not divided by sin theta).
        const double row[2] = {(double)k + 0.5, total > 0.0 ? a->angle[k] / total : NAN};
        st = gf_table_add(t, row);
    }
    return st;
}

gf_status gf_measure_gr(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out)
{
    if (!(o->gr_dr > 0.0) || !(o->gr_rmax > o->gr_dr) || !(o->g3_rcut > 0.0))
        return gf_error_set(GF_ERR_PARAM, "gr: need 0 < gr.dr < gr.rmax and g3.rcut > 0 (got %g, %g, %g)",
                            o->gr_dr, o->gr_rmax, o->g3_rcut);
    gf_container_defs cd;
    gf_config_container_defs(&s->cfg, &cd);
    const double W = cd.width, D = cd.depth;
    const gf_walls w = {-0.5 * W, 0.5 * W, -0.5 * D, 0.5 * D, 0.0};
    double vregion = (fmin(o->gr_x1, w.x1) - fmax(o->gr_x0, w.x0)) * D * (o->gr_z1 - fmax(o->gr_z0, 0.0));
    if (!(vregion > 0.0))
        return gf_error_set(GF_ERR_PARAM, "gr: the region %g < x < %g, %g < z < %g is empty in the container",
                            o->gr_x0, o->gr_x1, o->gr_z0, o->gr_z1);
    gf_gr_acc a = {0};
    a.nbin = (size_t)ceil(o->gr_rmax / o->gr_dr - 1e-9);
    a.dr = o->gr_dr;
    a.rcut = o->g3_rcut;
    a.count = GF_NEW(double, a.nbin);
    a.norm = GF_NEW(double, a.nbin);
    a.vin = GF_NEW(double, a.nbin);
    a.angle = GF_NEW(double, GF_G3_BINS);
    if (!a.count || !a.norm || !a.vin || !a.angle) {
        gf_gr_acc_free(&a);
        return gf_error_set(GF_ERR_NOMEM, "gr: out of memory for %zu bins", a.nbin);
    }
    size_t k0, k1;
    gf_structure_window(s, o, &k0, &k1);
    gf_status st = GF_OK;
    for (size_t k = k0; k < k1 && st == GF_OK; k++)
        if ((st = gf_stop_check(o->stop, "g(r)")) == GF_OK) st = gf_gr_frame(&s->frames[k].pk, o, &w, vregion, &a);
    double peak_r = NAN;
    if (st == GF_OK) st = gf_gr_tables(&a, out, &peak_r);
    double coord = a.centres > 0.0 ? a.bonds / a.centres : NAN;
    double rmax = (double)a.nbin * a.dr;
    gf_gr_acc_free(&a);
    if (st == GF_OK) st = gf_measure_value(out, "gr_first_peak_r", peak_r);
    if (st == GF_OK) st = gf_measure_value(out, "coordination", coord);
    if (st != GF_OK) return st;
    return gf_measure_gnuplot(
        out,
        "set datafile separator ','\n"
        "set multiplot layout 1,2 title 'Structure in %g < x < %g, %g < z < %g (d)'\n"
        "set xlabel 'r (d)'\n"
        "set ylabel 'g(r)'\n"
        "set xrange [0:%g]\n"
        "plot 'gr.csv' skip 1 using 1:2 with lines lw 2 title 'g(r)', 1 with lines dt 2 lc rgb 'gray' notitle\n"
        "set xlabel 'theta (degrees)'\n"
        "set ylabel 'g3(theta) (per degree)'\n"
        "set xrange [0:180]\n"
        "set xtics 30\n"
        "plot 'g3.csv' skip 1 using 1:2 with lines lw 2 title 'bond angles, r < %g d'\n"
        "unset multiplot\n",
        o->gr_x0, o->gr_x1, o->gr_z0, o->gr_z1, rmax, o->g3_rcut);
}
