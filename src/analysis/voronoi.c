// SPDX-License-Identifier: MIT
// Local packing fraction from Voronoi cells (2009 paper Sec. 2, Figs. 4 and 6).
#include <math.h>
#include <string.h>

#include "analysis/structure.h"
#include "analysis/voronoi_cells.h"
#include "core/alloc.h"
#include "core/error.h"
#include "core/stop.h"
#include "geom/celllist.h"
#include "granflow/analysis.h"
#include "granflow/defs.h"

#define GF_PI 3.14159265358979323846
/// Particles whose centre is within this of the local top are the free surface, d.
#define GF_VOR_SURFACE_DEPTH 1.5
/// Columns of this edge, d, and this many either side, give the local top.
#define GF_VOR_COLUMN 1.0
#define GF_VOR_COLUMN_REACH 2
/// Margin of the sub-box around the region for the time average, d: a cell
/// computed there is exact when twice its circumradius is below the distance
/// to the sub-box's cut faces (any point further away cannot cut it).
#define GF_VOR_MARGIN 3.0

gf_status gf_voronoi_volumes(const gf_packing *pk, double width, double depth, double ztop, double *vol)
{
    const double lo[3] = {-0.5 * width, -0.5 * depth, 0.0}, hi[3] = {0.5 * width, 0.5 * depth, ztop};
    return gf_voro_cells(pk->n, pk->x, pk->y, pk->z, lo, hi, vol, NULL);
}

gf_status gf_voronoi_fraction(const gf_packing *pk, double width, double depth, double ztop, double *phi)
{
    gf_status st = gf_voronoi_volumes(pk, width, depth, ztop, phi);
    if (st != GF_OK) return st;
    for (size_t i = 0; i < pk->n; i++) {
        double r = pk->r[i];
        phi[i] = 4.0 / 3.0 * GF_PI * r * r * r / phi[i];
    }
    return GF_OK;
}

// One frame's cells: volumes, circumradii squared and the bulk flags.
typedef struct gf_vor_frame {
    size_t n;
    double ztop;           ///< top of the Voronoi box: highest centre + 1 d
    double *vol, *rad2;    ///< NaN outside the box
    unsigned char *bulk;   ///< a finite cell away from the free surface
} gf_vor_frame;

static void gf_vor_frame_free(gf_vor_frame *f)
{
    GF_DELETE(f->vol, f->n ? f->n : 1);
    GF_DELETE(f->rad2, f->n ? f->n : 1);
    GF_DELETE(f->bulk, f->n ? f->n : 1);
    memset(f, 0, sizeof *f);
}

static gf_status gf_vor_frame_alloc(gf_vor_frame *f, size_t n)
{
    memset(f, 0, sizeof *f);
    f->n = n;
    f->vol = GF_NEW(double, n ? n : 1);
    f->rad2 = GF_NEW(double, n ? n : 1);
    f->bulk = GF_NEW(unsigned char, n ? n : 1);
    if (!f->vol || !f->rad2 || !f->bulk) {
        gf_vor_frame_free(f);
        return gf_error_set(GF_ERR_NOMEM, "voronoi: out of memory for %zu cells", n);
    }
    return GF_OK;
}

static double gf_vor_sphere(double r)
{
    return 4.0 / 3.0 * GF_PI * r * r * r;
}

static bool gf_vor_in_region(const gf_analysis_opts *o, double x, double z)
{
    return x > o->gr_x0 && x < o->gr_x1 && z > o->gr_z0 && z < o->gr_z1;
}

// Highest centre in the container (z >= 0), or NaN when there is none.
static double gf_vor_zmax(const gf_packing *pk)
{
    double zmax = -INFINITY;
    for (size_t i = 0; i < pk->n; i++)
        if (pk->z[i] >= 0.0 && pk->z[i] > zmax && isfinite(pk->x[i]) && isfinite(pk->y[i])) zmax = pk->z[i];
    return isfinite(zmax) ? zmax : NAN;
}

// Marks as bulk the particles with a cell that are neither within
// GF_VOR_SURFACE_DEPTH of the local top (the highest centre in the 1 d columns
// within GF_VOR_COLUMN_REACH columns) nor have a cell reaching the box top.
static gf_status gf_vor_mark_bulk(const gf_packing *pk, double W, double D, gf_vor_frame *f)
{
    int nx = (int)ceil(W / GF_VOR_COLUMN), ny = (int)ceil(D / GF_VOR_COLUMN);
    if (nx < 1) nx = 1;
    if (ny < 1) ny = 1;
    size_t ncol = (size_t)nx * (size_t)ny;
    double *top = GF_NEW(double, ncol), *near = GF_NEW(double, ncol);
    if (!top || !near) {
        GF_DELETE(top, ncol);
        GF_DELETE(near, ncol);
        return gf_error_set(GF_ERR_NOMEM, "voronoi: out of memory for %zu columns", ncol);
    }
    for (size_t c = 0; c < ncol; c++) top[c] = -INFINITY;
#define GF_COL(v, lo, n) ((int)fmin(fmax(floor(((v) - (lo)) / GF_VOR_COLUMN), 0.0), (double)((n) - 1)))
    for (size_t i = 0; i < pk->n; i++) {
        if (!(pk->z[i] >= 0.0) || !isfinite(pk->x[i]) || !isfinite(pk->y[i])) continue;
        size_t c = (size_t)GF_COL(pk->y[i], -0.5 * D, ny) * (size_t)nx + (size_t)GF_COL(pk->x[i], -0.5 * W, nx);
        top[c] = fmax(top[c], pk->z[i]);
    }
    for (int cy = 0; cy < ny; cy++)
        for (int cx = 0; cx < nx; cx++) {
            double t = -INFINITY;
            for (int b = cy - GF_VOR_COLUMN_REACH; b <= cy + GF_VOR_COLUMN_REACH; b++)
                for (int a = cx - GF_VOR_COLUMN_REACH; a <= cx + GF_VOR_COLUMN_REACH; a++)
                    if (a >= 0 && a < nx && b >= 0 && b < ny) t = fmax(t, top[(size_t)b * (size_t)nx + (size_t)a]);
            near[(size_t)cy * (size_t)nx + (size_t)cx] = t;
        }
    for (size_t i = 0; i < pk->n; i++) {
        f->bulk[i] = 0;
        if (!isfinite(f->vol[i])) continue;
        size_t c = (size_t)GF_COL(pk->y[i], -0.5 * D, ny) * (size_t)nx + (size_t)GF_COL(pk->x[i], -0.5 * W, nx);
        bool surface = pk->z[i] > near[c] - GF_VOR_SURFACE_DEPTH || pk->z[i] + sqrt(f->rad2[i]) >= f->ztop - 1e-9;
        f->bulk[i] = !surface;
    }
#undef GF_COL
    GF_DELETE(top, ncol);
    GF_DELETE(near, ncol);
    return GF_OK;
}

// Every cell of the frame, cut by the walls, the base and the top z = ztop
// (NaN: the highest centre + 1 d, the top gf_measure_voronoi uses).
static gf_status gf_vor_full(const gf_packing *pk, double W, double D, double ztop, gf_vor_frame *f)
{
    gf_status st = gf_vor_frame_alloc(f, pk->n);
    if (st != GF_OK) return st;
    f->ztop = isnan(ztop) ? gf_vor_zmax(pk) + 1.0 : ztop;
    if (isnan(f->ztop)) {
        for (size_t i = 0; i < pk->n; i++) f->vol[i] = f->rad2[i] = NAN;
    } else {
        const double lo[3] = {-0.5 * W, -0.5 * D, 0.0}, hi[3] = {0.5 * W, 0.5 * D, f->ztop};
        st = gf_voro_cells(pk->n, pk->x, pk->y, pk->z, lo, hi, f->vol, f->rad2);
    }
    if (st == GF_OK) st = gf_vor_mark_bulk(pk, W, D, f);
    if (st != GF_OK) gf_vor_frame_free(f);
    return st;
}

// Sum of phi and count over the bulk particles of the region in one frame.
static void gf_vor_region_sum(const gf_packing *pk, const gf_analysis_opts *o, const gf_vor_frame *f, double *sum,
                              double *count)
{
    for (size_t i = 0; i < pk->n; i++)
        if (f->bulk[i] && gf_vor_in_region(o, pk->x[i], pk->z[i])) {
            *sum += gf_vor_sphere(pk->r[i]) / f->vol[i];
            *count += 1.0;
        }
}

// The region's cells from a sub-box around it (GF_VOR_MARGIN): much cheaper
// than the whole packing. *exact is false when some region cell came too close
// to a cut face for the result to be trusted (the caller then does it all).
static gf_status gf_vor_region(const gf_packing *pk, const gf_analysis_opts *o, double W, double D, double *sum,
                               double *count, bool *exact)
{
    *exact = true;
    double ztop = gf_vor_zmax(pk) + 1.0;
    const double lo[3] = {fmax(o->gr_x0 - GF_VOR_MARGIN, -0.5 * W), -0.5 * D, fmax(o->gr_z0 - GF_VOR_MARGIN, 0.0)};
    const double hi[3] = {fmin(o->gr_x1 + GF_VOR_MARGIN, 0.5 * W), 0.5 * D, fmin(o->gr_z1 + GF_VOR_MARGIN, ztop)};
    if (isnan(ztop) || !(hi[0] > lo[0]) || !(hi[2] > lo[2])) return GF_OK; // nothing in the region
    // Faces of the sub-box that are not faces of the whole box cut cells wrongly.
    const bool cut[4] = {lo[0] > -0.5 * W, hi[0] < 0.5 * W, lo[2] > 0.0, hi[2] < ztop};
    gf_vor_frame f;
    gf_status st = gf_vor_frame_alloc(&f, pk->n);
    if (st != GF_OK) return st;
    f.ztop = ztop;
    st = gf_voro_cells(pk->n, pk->x, pk->y, pk->z, lo, hi, f.vol, f.rad2);
    if (st == GF_OK) st = gf_vor_mark_bulk(pk, W, D, &f);
    for (size_t i = 0; i < pk->n && st == GF_OK && *exact; i++) {
        if (!isfinite(f.vol[i]) || !gf_vor_in_region(o, pk->x[i], pk->z[i])) continue;
        double m = INFINITY;
        if (cut[0]) m = fmin(m, pk->x[i] - lo[0]);
        if (cut[1]) m = fmin(m, hi[0] - pk->x[i]);
        if (cut[2]) m = fmin(m, pk->z[i] - lo[2]);
        if (cut[3]) m = fmin(m, hi[2] - pk->z[i]);
        if (!(4.0 * f.rad2[i] < m * m)) *exact = false;
    }
    if (st == GF_OK && *exact) gf_vor_region_sum(pk, o, &f, sum, count);
    gf_vor_frame_free(&f);
    return st;
}

// Paper Fig. 4: around each particle, the total volume of the bulk particles
// within R over the total volume of their Voronoi cells.
static gf_status gf_vor_field(const gf_packing *pk, const gf_vor_frame *f, double R, double *avg)
{
    size_t n = pk->n ? pk->n : 1;
    double *bx = GF_NEW(double, n), *by = GF_NEW(double, n), *bz = GF_NEW(double, n);
    gf_celllist cl = {0};
    gf_status st = GF_OK;
    if (!bx || !by || !bz) {
        st = gf_error_set(GF_ERR_NOMEM, "voronoi: out of memory for %zu particles", pk->n);
        goto done;
    }
    for (size_t i = 0; i < pk->n; i++) {
        bx[i] = f->bulk[i] ? pk->x[i] : NAN; // the cell list leaves NaN out
        by[i] = pk->y[i];
        bz[i] = pk->z[i];
    }
    st = gf_celllist_fit(&cl, bx, by, bz, pk->n, fmax(R, 0.5));
    if (st != GF_OK) goto done;
    for (size_t i = 0; i < pk->n; i++) {
        avg[i] = NAN;
        if (!isfinite(f->vol[i])) continue;
        const double c[3] = {pk->x[i], pk->y[i], pk->z[i]};
        double vp = 0.0, vc = 0.0;
        gf_celllist_near it;
        gf_celllist_near_start(&it, &cl, c, R);
        for (size_t j; gf_celllist_near_next(&it, &j);) {
            double dx = pk->x[j] - c[0], dy = pk->y[j] - c[1], dz = pk->z[j] - c[2];
            if (dx * dx + dy * dy + dz * dz > R * R) continue;
            vp += gf_vor_sphere(pk->r[j]);
            vc += f->vol[j];
        }
        if (vc > 0.0) avg[i] = vp / vc;
    }
done:
    gf_celllist_free(&cl);
    GF_DELETE(bx, n);
    GF_DELETE(by, n);
    GF_DELETE(bz, n);
    return st;
}

gf_status gf_voronoi_field(const gf_packing *pk, double width, double depth, double ztop, double radius,
                           double *phi_avg)
{
    if (!(width > 0.0) || !(depth > 0.0) || !isfinite(width) || !isfinite(depth))
        return gf_error_set(GF_ERR_PARAM, "voronoi field: container %g x %g has no volume", width, depth);
    if (!isnan(ztop) && !(ztop > 0.0 && isfinite(ztop)))
        return gf_error_set(GF_ERR_PARAM, "voronoi field: top of the box z = %g is not above the base", ztop);
    if (!(radius >= 0.0) || !isfinite(radius))
        return gf_error_set(GF_ERR_PARAM, "voronoi field: averaging radius %g must be finite and >= 0", radius);
    gf_vor_frame f;
    gf_status st = gf_vor_full(pk, width, depth, ztop, &f);
    if (st != GF_OK) return st;
    st = gf_vor_field(pk, &f, radius, phi_avg);
    gf_vor_frame_free(&f);
    return st;
}

static gf_status gf_vor_tables(const gf_packing *pk, const gf_vor_frame *f, const double *avg, gf_measure_out *out)
{
    gf_table *t = &out->tables[out->ntables];
    gf_status st = gf_table_init(t, "voronoi", "id,x_d,y_d,z_d,phi,phi_avg,bulk");
    if (st != GF_OK) return st;
    out->ntables++;
    for (size_t i = 0; i < pk->n && st == GF_OK; i++) {
        const double row[7] = {(double)pk->id[i], pk->x[i], pk->y[i], pk->z[i],
                               gf_vor_sphere(pk->r[i]) / f->vol[i], avg[i], f->bulk[i] ? 1.0 : 0.0};
        st = gf_table_add(t, row);
    }
    if (st != GF_OK) return st;
    t = &out->tables[out->ntables];
    st = gf_table_init(t, "voronoi_profile", "z_d,phi_mean,particles");
    if (st != GF_OK) return st;
    out->ntables++;
    size_t nslab = isfinite(f->ztop) ? (size_t)ceil(f->ztop) : 0;
    for (size_t k = 0; k < nslab && st == GF_OK; k++) {
        double sum = 0.0, count = 0.0;
        for (size_t i = 0; i < pk->n; i++)
            if (f->bulk[i] && pk->z[i] >= (double)k && pk->z[i] < (double)(k + 1)) {
                sum += gf_vor_sphere(pk->r[i]) / f->vol[i];
                count += 1.0;
            }
        const double row[3] = {(double)k + 0.5, count > 0.0 ? sum / count : NAN, count};
        st = gf_table_add(t, row);
    }
    return st;
}

gf_status gf_measure_voronoi(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out)
{
    gf_container_defs cd;
    gf_config_container_defs(&s->cfg, &cd);
    const double W = cd.width, D = cd.depth;
    if (!(W > 0.0) || !(D > 0.0))
        return gf_error_set(GF_ERR_PARAM, "voronoi: container %g x %g has no volume", W, D);
    size_t k0, k1;
    gf_structure_window(s, o, &k0, &k1);
    gf_vor_frame f = {0};
    double *avg = NULL;
    gf_status st = GF_OK;
    double sum = 0.0, count = 0.0, tlast = NAN;
    if (k1 > k0) {
        // The field and the tables: the last frame of the window.
        const gf_packing *pk = &s->frames[k1 - 1].pk;
        tlast = s->frames[k1 - 1].time;
        st = gf_vor_full(pk, W, D, NAN, &f);
        if (st == GF_OK) {
            avg = GF_NEW(double, pk->n ? pk->n : 1);
            if (!avg) st = gf_error_set(GF_ERR_NOMEM, "voronoi: out of memory for %zu particles", pk->n);
        }
        if (st == GF_OK) st = gf_vor_field(pk, &f, o->vor_avg_radius, avg);
        if (st == GF_OK) st = gf_vor_tables(pk, &f, avg, out);
        if (st == GF_OK) gf_vor_region_sum(pk, o, &f, &sum, &count);
        if (avg) GF_DELETE(avg, pk->n ? pk->n : 1);
        gf_vor_frame_free(&f);
    } else {
        // Empty tables: nothing in the window.
        st = gf_table_init(&out->tables[out->ntables], "voronoi", "id,x_d,y_d,z_d,phi,phi_avg,bulk");
        if (st == GF_OK) out->ntables++;
        if (st == GF_OK) st = gf_table_init(&out->tables[out->ntables], "voronoi_profile", "z_d,phi_mean,particles");
        if (st == GF_OK) out->ntables++;
    }
    // The headline: every frame of the window, from the region's sub-box.
    for (size_t k = k0; k + 1 < k1 && st == GF_OK; k++) {
        if ((st = gf_stop_check(o->stop, "voronoi")) != GF_OK) break;
        const gf_packing *pk = &s->frames[k].pk;
        bool exact;
        double fs = 0.0, fc = 0.0;
        st = gf_vor_region(pk, o, W, D, &fs, &fc, &exact);
        if (st == GF_OK && !exact) {
            st = gf_vor_full(pk, W, D, NAN, &f);
            if (st == GF_OK) gf_vor_region_sum(pk, o, &f, &fs, &fc);
            gf_vor_frame_free(&f);
        }
        sum += fs;
        count += fc;
    }
    if (st != GF_OK) return st;
    st = gf_measure_value(out, "bulk_packing_fraction", count > 0.0 ? sum / count : NAN);
    if (st != GF_OK) return st;
    // Paper Figs. 4 and 6 render the particles with y > 0 seen from the
    // central plane y = 0: in a flat plot, the layer 0 < y < 1 d is what shows.
    return gf_measure_gnuplot(
        out,
        "set datafile separator ','\n"
        "set title 'Local packing fraction (Voronoi, within %g d), central slice 0 < y < 1 d, t = %g tau'\n"
        "set xlabel 'x (d)'\n"
        "set ylabel 'z (d)'\n"
        "set size ratio -1\n"
        "set xrange [%g:%g]\n"
        "set yrange [0:*]\n"
        "set cbrange [0.55:0.65]\n"
        "set cblabel 'packing fraction'\n"
        "set palette defined (0 '#b2182b', 0.35 '#f4a582', 0.5 '#f7f7f7', 0.65 '#92c5de', 1 '#2166ac')\n"
        "plot 'voronoi.csv' skip 1 using 2:($3 > 0 && $3 < 1 ? $4 : 1/0):(0.5):6 with circles fill solid noborder "
        "lc palette notitle\n",
        o->vor_avg_radius, tlast, -0.5 * W, 0.5 * W);
}
