// SPDX-License-Identifier: MIT
// Options of the measurements: regions, heights and windows, with the papers'
// values as defaults (SPEC 1.6), set by name from "key=value".
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "granflow/analysis.h"

gf_analysis_opts gf_analysis_opts_default(void)
{
    gf_analysis_opts d, *o = &d;
    memset(o, 0, sizeof *o);
    o->t0 = o->t1 = NAN;
    o->dump_dt = 0.0;
    o->vel_bin = 1.0;
    for (size_t k = 0; k < 6; k++) o->vel_heights[k] = 10.0 * (double)(k + 1);
    o->vel_nheights = 6;
    o->vel_band = 1.0;
    o->vely_xhalf = 10.0; // 2009 paper Fig. 8: |x| < 10, 50 < z < 70
    o->vely_z0 = 50.0;
    o->vely_z1 = 70.0;
    o->diff_xhalf = 5.0;
    o->diff_z0 = 60.0;
    o->corr_size = 16.0; // thesis Sec. 3.3: a 16 x 16 region high in the centre
    o->corr_zc = 60.0;
    o->gr_x0 = -15.0; // SPEC 1.6: -15 < x < 15, 15 < z < 45
    o->gr_x1 = 15.0;
    o->gr_z0 = 15.0;
    o->gr_z1 = 45.0;
    o->gr_rmax = 4.0;
    o->gr_dr = 0.02;
    o->g3_rcut = 1.38;
    o->vor_avg_radius = 2.2; // 2009 paper Fig. 4
    o->dens_z0 = 50.0;       // SPEC 1.6: the slice 50 < z < 70
    o->dens_z1 = 70.0;
    o->surf_dx = 2.5; // 2009 paper Sec. 4: x_j = 2.5 j - 1.25, j = 1..10
    o->surf_ncols = 10;
    o->zone_nradii = 0;
    o->zone_dr = 0.5;
    o->zone_dz = 2.0;
    return d;
}

typedef enum { GF_OPT_REAL, GF_OPT_COUNT, GF_OPT_LIST } gf_opt_kind;

typedef struct gf_opt_key {
    const char *key;
    gf_opt_kind kind;
    size_t off;      ///< offset of the field in gf_analysis_opts
    double lo, hi;   ///< accepted range (inclusive)
} gf_opt_key;

#define GF_OPT(k, kind, field, lo, hi) {k, kind, offsetof(gf_analysis_opts, field), lo, hi}
static const gf_opt_key gf_opt_keys[] = {
    GF_OPT("window.t0", GF_OPT_REAL, t0, 0.0, 1e12),
    GF_OPT("window.t1", GF_OPT_REAL, t1, 0.0, 1e12),
    GF_OPT("dump.dt", GF_OPT_REAL, dump_dt, 0.0, 1e6),
    GF_OPT("velocity.bin", GF_OPT_REAL, vel_bin, 0.05, 100.0),
    GF_OPT("velocity.heights", GF_OPT_LIST, vel_heights, -1e6, 1e6),
    GF_OPT("velocity.band", GF_OPT_REAL, vel_band, 0.05, 100.0),
    GF_OPT("velocity.y_xhalf", GF_OPT_REAL, vely_xhalf, 0.1, 1e6),
    GF_OPT("velocity.y_z0", GF_OPT_REAL, vely_z0, -1e6, 1e6),
    GF_OPT("velocity.y_z1", GF_OPT_REAL, vely_z1, -1e6, 1e6),
    GF_OPT("diffusion.xhalf", GF_OPT_REAL, diff_xhalf, 0.1, 1e6),
    GF_OPT("diffusion.z0", GF_OPT_REAL, diff_z0, -1e6, 1e6),
    GF_OPT("correlation.size", GF_OPT_REAL, corr_size, 1.0, 1e6),
    GF_OPT("correlation.zc", GF_OPT_REAL, corr_zc, -1e6, 1e6),
    GF_OPT("gr.x0", GF_OPT_REAL, gr_x0, -1e6, 1e6),
    GF_OPT("gr.x1", GF_OPT_REAL, gr_x1, -1e6, 1e6),
    GF_OPT("gr.z0", GF_OPT_REAL, gr_z0, -1e6, 1e6),
    GF_OPT("gr.z1", GF_OPT_REAL, gr_z1, -1e6, 1e6),
    GF_OPT("gr.rmax", GF_OPT_REAL, gr_rmax, 0.1, 100.0),
    GF_OPT("gr.dr", GF_OPT_REAL, gr_dr, 1e-4, 1.0),
    GF_OPT("g3.rcut", GF_OPT_REAL, g3_rcut, 0.5, 10.0),
    GF_OPT("voronoi.radius", GF_OPT_REAL, vor_avg_radius, 0.0, 100.0),
    GF_OPT("density.z0", GF_OPT_REAL, dens_z0, -1e6, 1e6),
    GF_OPT("density.z1", GF_OPT_REAL, dens_z1, -1e6, 1e6),
    GF_OPT("surface.dx", GF_OPT_REAL, surf_dx, 0.1, 1e6),
    GF_OPT("surface.columns", GF_OPT_COUNT, surf_ncols, 2.0, 1000.0),
    GF_OPT("zones.radii", GF_OPT_LIST, zone_radii, 1e-6, 1e6),
    GF_OPT("zones.dr", GF_OPT_REAL, zone_dr, 0.01, 1e3),
    GF_OPT("zones.dz", GF_OPT_REAL, zone_dz, 0.01, 1e3),
};
#undef GF_OPT

static gf_status gf_opt_number(const char *key, const char *text, double lo, double hi, double *v)
{
    char *end;
    errno = 0;
    double x = strtod(text, &end);
    while (*end == ' ') end++;
    if (end == text || *end || errno || !isfinite(x))
        return gf_error_set(GF_ERR_PARAM, "analysis option %s: '%s' is not a number", key, text);
    if (x < lo || x > hi)
        return gf_error_set(GF_ERR_PARAM, "analysis option %s = %g is out of range [%g, %g]", key, x, lo, hi);
    *v = x;
    return GF_OK;
}

gf_status gf_analysis_opts_set(gf_analysis_opts *o, const char *assignment)
{
    const char *eq = strchr(assignment, '=');
    if (!eq) return gf_error_set(GF_ERR_PARAM, "analysis option '%s': expected key=value", assignment);
    size_t klen = (size_t)(eq - assignment);
    const char *val = eq + 1;
    for (size_t k = 0; k < sizeof gf_opt_keys / sizeof gf_opt_keys[0]; k++) {
        const gf_opt_key *d = &gf_opt_keys[k];
        if (strlen(d->key) != klen || strncmp(d->key, assignment, klen) != 0) continue;
        char *field = (char *)o + d->off;
        // The window ends may go back to their automatic values.
        if (d->kind == GF_OPT_REAL && (d->off == offsetof(gf_analysis_opts, t0) || d->off == offsetof(gf_analysis_opts, t1)) &&
            !strcmp(val, "auto")) {
            *(double *)(void *)field = NAN;
            return GF_OK;
        }
        if (d->off == offsetof(gf_analysis_opts, zone_radii) && !strcmp(val, "auto")) {
            o->zone_nradii = 0; // four zones of equal area
            memset(o->zone_radii, 0, sizeof o->zone_radii);
            return GF_OK;
        }
        if (d->kind == GF_OPT_REAL) return gf_opt_number(d->key, val, d->lo, d->hi, (double *)(void *)field);
        if (d->kind == GF_OPT_COUNT) {
            double x;
            gf_status st = gf_opt_number(d->key, val, d->lo, d->hi, &x);
            if (st != GF_OK) return st;
            if (x != floor(x)) return gf_error_set(GF_ERR_PARAM, "analysis option %s: '%s' is not a whole number", d->key, val);
            *(size_t *)(void *)field = (size_t)x;
            return GF_OK;
        }
        // A comma-separated list of heights.
        double list[16];
        size_t n = 0;
        char buf[512];
        if (strlen(val) >= sizeof buf) return gf_error_set(GF_ERR_PARAM, "analysis option %s: value too long", d->key);
        strcpy(buf, val);
        for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
            if (n == 16) return gf_error_set(GF_ERR_PARAM, "analysis option %s: at most 16 values", d->key);
            gf_status st = gf_opt_number(d->key, tok, d->lo, d->hi, &list[n]);
            if (st != GF_OK) return st;
            n++;
        }
        if (n == 0) return gf_error_set(GF_ERR_PARAM, "analysis option %s: empty list", d->key);
        memcpy(field, list, sizeof(double) * n);
        if (d->off == offsetof(gf_analysis_opts, zone_radii)) {
            for (size_t k2 = 1; k2 < n; k2++)
                if (!(list[k2] > list[k2 - 1]))
                    return gf_error_set(GF_ERR_PARAM, "analysis option %s: the radii must increase", d->key);
            o->zone_nradii = n;
        } else {
            o->vel_nheights = n;
        }
        return GF_OK;
    }
    return gf_error_set(GF_ERR_PARAM, "unknown analysis option '%.*s' (see docs/analysis.md)", (int)klen, assignment);
}

void gf_analysis_window(const gf_analysis_opts *o, const gf_series *s, double *t0, double *t1)
{
    double first = s->nframes ? s->frames[0].time : 0.0;
    double last = s->nframes ? s->frames[s->nframes - 1].time : 0.0;
    *t0 = isnan(o->t0) ? first + 0.25 * (last - first) : o->t0;
    *t1 = isnan(o->t1) ? last : o->t1;
}
