// SPDX-License-Identifier: MIT
// Reactor outputs (issue 14; Rycroft et al. 2006, Phys. Rev. E 74, 021306,
// Secs. III-IV: residence times, radial zones and streamlines of pebbles):
// what a burnup or streamline code reads from a recirculating run.
//
// Radial zones are annuli around the axis x = y = 0 (zones.radii: their
// outer radii; the last zone reaches the wall). From exits.csv (pass,
// entry_time, entry_r of every exit):
//   zones         per entry zone: exits, flow share, mean and sd of the
//                 transit time (exit time - entry time), and the share of
//                 exits leaving through the zone
//   zones_matrix  entry zone (where a pass began on the surface) x exit zone
//                 (where it crossed the exit plane): counts and fractions
//   rtd_pass      residence time per pass: count, mean, sd, median
//   rtd_zone_hist residence-time distribution by entry zone (pdf)
// From the snapshots (ids followed frame to frame; a particle that rises by
// more than GF_MOTION_JUMP between two frames was put back on the surface):
//   streamlines   mean radius against height of the particles that started
//                 at the surface (re-inserted, or in the top zones.dz of the
//                 first frame), per entry zone: the mean paths
//   vz_r          v_z(r) and v_r(r) in cylindrical coordinates over the window
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "core/stop.h"
#include "analysis/motion.h"
#include "geom/container.h"
#include "granflow/analysis.h"

enum { GF_ZONES_MAX = 17, GF_ZONES_BINS = 40 };

typedef struct gf_zones {
    double edge[GF_ZONES_MAX]; ///< outer radius of zone k (the last: the wall)
    size_t n;
} gf_zones;

static size_t gf_zone_of(const gf_zones *z, double r)
{
    for (size_t k = 0; k + 1 < z->n; k++)
        if (r < z->edge[k]) return k;
    return z->n - 1;
}

static void gf_zones_make(const gf_series *s, const gf_analysis_opts *o, gf_zones *z)
{
    // The wall: the cylinder's, or the box's corners; a central column is the inner edge.
    const gf_container c = gf_container_make(&s->cfg);
    double wall = gf_container_outer_radius(&c), core = gf_container_inner_radius(&c);
    if (o->zone_nradii > 0) {
        z->n = 0;
        for (size_t k = 0; k < o->zone_nradii && o->zone_radii[k] < wall; k++) z->edge[z->n++] = o->zone_radii[k];
        z->edge[z->n++] = wall;
    } else { // four zones of equal area between the column (if any) and the wall
        z->n = 4;
        for (size_t k = 0; k < 4; k++) z->edge[k] = sqrt(core * core + (wall * wall - core * core) * (double)(k + 1) / 4.0);
    }
}

static int gf_zones_cmp_double(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    return (a > b) - (a < b);
}

// Count, mean, sample sd and median of v[0, n) (sorts v).
static void gf_zones_stats(double *v, size_t n, double out[4])
{
    double mean = 0.0, var = 0.0;
    for (size_t i = 0; i < n; i++) mean += v[i];
    mean = n ? mean / (double)n : NAN;
    for (size_t i = 0; i < n; i++) var += (v[i] - mean) * (v[i] - mean);
    qsort(v, n, sizeof *v, gf_zones_cmp_double);
    out[0] = (double)n;
    out[1] = mean;
    out[2] = n > 1 ? sqrt(var / (double)(n - 1)) : NAN;
    out[3] = n == 0 ? NAN : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static gf_status gf_zones_add_table(gf_measure_out *out, const char *name, const char *cols, gf_table **t)
{
    *t = &out->tables[out->ntables];
    gf_status st = gf_table_init(*t, name, cols);
    if (st == GF_OK) out->ntables++;
    return st;
}

// The tables made from exits.csv.
static gf_status gf_zones_exits(const gf_series *s, const gf_zones *z, gf_measure_out *out, double *mean_all)
{
    const size_t n = s->nexits;
    double *v = GF_NEW(double, n + 1);
    if (!v) return gf_error_set(GF_ERR_NOMEM, "zones: out of memory");
    size_t cnt[GF_ZONES_MAX] = {0}, ecnt[GF_ZONES_MAX] = {0}, mat[GF_ZONES_MAX][GF_ZONES_MAX] = {{0}}, tot = 0;
    double tmax = 0.0;
    for (size_t e = 0; e < n; e++) {
        const gf_exit *x = &s->exits[e];
        if (!isfinite(x->entry_r)) continue;
        size_t a = gf_zone_of(z, x->entry_r), b = gf_zone_of(z, hypot(x->x, x->y));
        cnt[a]++;
        ecnt[b]++;
        mat[a][b]++;
        tot++;
        tmax = fmax(tmax, x->time - x->entry_time);
    }
    gf_table *tz, *tm, *tp, *th;
    gf_status st = gf_zones_add_table(out, "zones", "zone,r_inner_d,r_outer_d,exits,flow_share,mean_transit_tau,"
                                                    "sd_transit_tau,exit_share", &tz);
    for (size_t k = 0; st == GF_OK && k < z->n; k++) {
        size_t m = 0;
        for (size_t e = 0; e < n; e++) {
            const gf_exit *x = &s->exits[e];
            if (isfinite(x->entry_r) && gf_zone_of(z, x->entry_r) == k) v[m++] = x->time - x->entry_time;
        }
        double r4[4];
        gf_zones_stats(v, m, r4);
        double row[8] = {(double)k, k ? z->edge[k - 1] : 0.0, z->edge[k], (double)cnt[k],
                         tot ? (double)cnt[k] / (double)tot : NAN, r4[1], r4[2],
                         tot ? (double)ecnt[k] / (double)tot : NAN};
        st = gf_table_add(tz, row);
    }
    if (st == GF_OK) st = gf_zones_add_table(out, "zones_matrix", "entry_zone,exit_zone,count,fraction", &tm);
    for (size_t a = 0; st == GF_OK && a < z->n; a++)
        for (size_t b = 0; st == GF_OK && b < z->n; b++) {
            double row[4] = {(double)a, (double)b, (double)mat[a][b], cnt[a] ? (double)mat[a][b] / (double)cnt[a] : NAN};
            st = gf_table_add(tm, row);
        }
    // Residence time per pass.
    int64_t pmax = 0;
    for (size_t e = 0; e < n; e++) pmax = s->exits[e].pass > pmax ? s->exits[e].pass : pmax;
    if (st == GF_OK) st = gf_zones_add_table(out, "rtd_pass", "pass,count,mean_tau,sd_tau,median_tau", &tp);
    for (int64_t p = 1; st == GF_OK && p <= pmax; p++) {
        size_t m = 0;
        for (size_t e = 0; e < n; e++)
            if (s->exits[e].pass == p) v[m++] = s->exits[e].time - s->exits[e].entry_time;
        if (m == 0) continue;
        double r4[4];
        gf_zones_stats(v, m, r4);
        double row[5] = {(double)p, r4[0], r4[1], r4[2], r4[3]};
        st = gf_table_add(tp, row);
    }
    // Distribution by entry zone: a pdf over GF_ZONES_BINS bins up to the longest transit.
    double bw = tmax > 0 ? tmax / GF_ZONES_BINS : 1.0;
    if (st == GF_OK) st = gf_zones_add_table(out, "rtd_zone_hist", "time_tau,zone,pdf", &th);
    for (size_t k = 0; st == GF_OK && k < z->n; k++) {
        if (!cnt[k]) continue;
        size_t h[GF_ZONES_BINS] = {0};
        for (size_t e = 0; e < n; e++) {
            const gf_exit *x = &s->exits[e];
            if (!isfinite(x->entry_r) || gf_zone_of(z, x->entry_r) != k) continue;
            size_t b = (size_t)((x->time - x->entry_time) / bw);
            h[b < GF_ZONES_BINS ? b : GF_ZONES_BINS - 1]++;
        }
        for (size_t b = 0; st == GF_OK && b < GF_ZONES_BINS; b++) {
            double row[3] = {bw * ((double)b + 0.5), (double)k, (double)h[b] / ((double)cnt[k] * bw)};
            st = gf_table_add(th, row);
        }
    }
    size_t m = 0;
    for (size_t e = 0; e < n; e++) v[m++] = s->exits[e].time - s->exits[e].entry_time;
    double r4[4];
    gf_zones_stats(v, m, r4);
    *mean_all = r4[1];
    GF_DELETE(v, n + 1);
    return st;
}

// Streamlines and v_z(r) from the snapshots.
static gf_status gf_zones_frames(const gf_series *s, const gf_analysis_opts *o, const gf_zones *z, gf_measure_out *out)
{
    int64_t maxid = 0;
    size_t nmax = 0;
    for (size_t f = 0; f < s->nframes; f++) {
        const gf_packing *p = &s->frames[f].pk;
        nmax = p->n > nmax ? p->n : nmax;
        for (size_t i = 0; i < p->n; i++) maxid = p->id[i] > maxid ? p->id[i] : maxid;
    }
    if (maxid > 64 * (int64_t)nmax + 4096)
        return gf_error_set(GF_ERR_PARAM, "zones: particle ids up to %lld for %zu particles: too sparse to follow",
                            (long long)maxid, nmax);
    const size_t nid = (size_t)maxid + 1;
    const double top_zmax = z->edge[z->n - 1];
    const size_t nr = (size_t)ceil(top_zmax / o->zone_dr) + 1;
    double zlo = 0.0, zhi = 0.0;
    for (size_t f = 0; f < s->nframes; f++)
        for (size_t i = 0; i < s->frames[f].pk.n; i++) zhi = fmax(zhi, s->frames[f].pk.z[i]);
    const size_t nzb = (size_t)ceil((zhi - zlo) / o->zone_dz) + 1;
    int32_t *prev = GF_NEW(int32_t, nid), *cur = GF_NEW(int32_t, nid), *entry = GF_NEW(int32_t, nid);
    double *vz = GF_NEW(double, 3 * nr), *sl = GF_NEW(double, 2 * nzb * z->n);
    gf_status st = prev && cur && entry && vz && sl ? GF_OK : gf_error_set(GF_ERR_NOMEM, "zones: out of memory");
    double t0, t1;
    gf_analysis_window(o, s, &t0, &t1);
    for (size_t i = 0; st == GF_OK && i < nid; i++) prev[i] = cur[i] = entry[i] = -1;
    for (size_t f = 0; st == GF_OK && f < s->nframes; f++) {
        if ((st = gf_stop_check(o->stop, "zones")) != GF_OK) break;
        const gf_packing *p = &s->frames[f].pk;
        for (size_t i = 0; i < p->n; i++) cur[p->id[i]] = (int32_t)i;
        double ztop = -INFINITY;
        for (size_t i = 0; f == 0 && i < p->n; i++) ztop = fmax(ztop, p->z[i]);
        const gf_packing *q = f ? &s->frames[f - 1].pk : NULL;
        double dt = f ? s->frames[f].time - s->frames[f - 1].time : 0.0;
        bool in_window = f && s->frames[f - 1].time >= t0 && s->frames[f].time <= t1 && dt > 0;
        for (size_t i = 0; i < p->n; i++) {
            int64_t id = p->id[i];
            double r = hypot(p->x[i], p->y[i]);
            int32_t j = q ? prev[id] : -1;
            bool jumped = j >= 0 && p->z[i] - q->z[j] > GF_MOTION_JUMP;
            if (f == 0 && p->z[i] > ztop - o->zone_dz) entry[id] = (int32_t)gf_zone_of(z, r);
            if (f > 0 && (j < 0 || jumped)) entry[id] = jumped ? (int32_t)gf_zone_of(z, r) : -1;
            if (entry[id] >= 0) {
                size_t b = (size_t)((p->z[i] - zlo) / o->zone_dz);
                if (p->z[i] >= zlo && b < nzb) {
                    double *c = &sl[2 * ((size_t)entry[id] * nzb + b)];
                    c[0] += r;
                    c[1] += 1.0;
                }
            }
            if (!in_window || j < 0 || jumped) continue;
            double rq = hypot(q->x[j], q->y[j]), rm = 0.5 * (r + rq);
            size_t b = (size_t)(rm / o->zone_dr);
            if (b >= nr) continue;
            vz[3 * b] += (p->z[i] - q->z[j]) / dt;
            vz[3 * b + 1] += (r - rq) / dt;
            vz[3 * b + 2] += 1.0;
        }
        for (size_t i = 0; q && i < q->n; i++) prev[q->id[i]] = -1;
        int32_t *tmp = prev;
        prev = cur;
        cur = tmp;
    }
    gf_table *ts, *tv;
    if (st == GF_OK) st = gf_zones_add_table(out, "streamlines", "zone,z_d,r_mean_d,count", &ts);
    for (size_t k = 0; st == GF_OK && k < z->n; k++)
        for (size_t b = 0; st == GF_OK && b < nzb; b++) {
            const double *c = &sl[2 * (k * nzb + b)];
            if (c[1] == 0.0) continue;
            double row[4] = {(double)k, zlo + o->zone_dz * ((double)b + 0.5), c[0] / c[1], c[1]};
            st = gf_table_add(ts, row);
        }
    if (st == GF_OK) st = gf_zones_add_table(out, "vz_r", "r_d,vz_d_per_tau,vr_d_per_tau,count", &tv);
    for (size_t b = 0; st == GF_OK && b < nr; b++) {
        if (vz[3 * b + 2] == 0.0) continue;
        double c = vz[3 * b + 2], row[4] = {o->zone_dr * ((double)b + 0.5), vz[3 * b] / c, vz[3 * b + 1] / c, c};
        st = gf_table_add(tv, row);
    }
    if (prev) GF_DELETE(prev, nid);
    if (cur) GF_DELETE(cur, nid);
    if (entry) GF_DELETE(entry, nid);
    if (vz) GF_DELETE(vz, 3 * nr);
    if (sl) GF_DELETE(sl, 2 * nzb * z->n);
    return st;
}

gf_status gf_measure_zones(const gf_series *s, const gf_analysis_opts *o, gf_measure_out *out)
{
    if (s->nframes == 0) return gf_error_set(GF_ERR_PARAM, "zones: the series has no frames");
    gf_zones z;
    gf_zones_make(s, o, &z);
    double mean = NAN;
    gf_status st = gf_zones_exits(s, &z, out, &mean);
    if (st == GF_OK) st = gf_zones_frames(s, o, &z, out);
    // v(r) needs two snapshots inside the steady window; without them the
    // panel says so (gnuplot refuses to plot an empty file).
    const gf_table *tv = st == GF_OK ? &out->tables[out->ntables - 1] : NULL;
    const char *vplot = tv && tv->nrow > 0
                            ? "plot 'vz_r.csv' skip 1 using 1:2 with linespoints title 'v_z', "
                              "'' skip 1 using 1:3 with linespoints title 'v_r'\n"
                            : "set label 1 'no two snapshots inside the steady window' at graph 0.5, 0.5 center\n"
                              "set xrange [0:1]\nset yrange [0:1]\nplot NaN notitle\n";
    int64_t pmax = 0;
    for (size_t e = 0; e < s->nexits; e++) pmax = s->exits[e].pass > pmax ? s->exits[e].pass : pmax;
    if (st == GF_OK) st = gf_measure_value(out, "zones_count", (double)z.n);
    if (st == GF_OK) st = gf_measure_value(out, "transit_mean", mean);
    if (st == GF_OK) st = gf_measure_value(out, "passes_max", (double)pmax);
    if (st == GF_OK)
        st = gf_measure_gnuplot(out,
                                "set datafile separator ','\n"
                                "set multiplot layout 1,2\n"
                                "set title 'Residence time by entry zone'\n"
                                "set xlabel 'transit time (tau)'\nset ylabel 'probability density (1/tau)'\n"
                                "plot for [k=0:%zu] 'rtd_zone_hist.csv' skip 1 "
                                "using 1:(column(2) == k ? column(3) : 1/0) with histeps lw 2 title 'zone '.k\n"
                                "set title 'Velocity against distance from the axis'\n"
                                "set xlabel 'r (d)'\nset ylabel 'v (d/tau)'\n"
                                "%s"
                                "unset multiplot\n",
                                z.n - 1, vplot);
    return st;
}
