// SPDX-License-Identifier: MIT
// Options of the measurements: regions, heights and windows, with the papers'
// values as defaults (SPEC 1.6), set by name from "key=value": a key table
// of config/keys.h, parsed, checked and printed by its one implementation.
#include "analysis/options.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "granflow/analysis.h"

#define GF_AOFF(field) offsetof(gf_analysis_opts, field)
#define GF_IN(lo, hi) .min = (lo), .max = (hi)
#define GF_Z GF_IN(-1e6, 1e6) // any height or abscissa

static const char *const gf_vel_window_names[] = {"height", "run", NULL};

// The options by section, defaults the papers' values (docs/analysis.md has
// the same table, checked by tests/test_docs_analysis.c).
static const gf_key gf_analysis_key_list[] = {
    {"window", "t0", GF_KEY_AUTO, GF_AOFF(t0), GF_IN(0, 1e12), .def = "auto", .unit = "tau",
     .doc = "start of the averaging window (auto: the start of the steady flow, else a quarter of the way through)"},
    {"window", "t1", GF_KEY_AUTO, GF_AOFF(t1), GF_IN(0, 1e12), .def = "auto", .unit = "tau",
     .doc = "end of the averaging window (auto: the end of the steady flow, else the last snapshot)"},
    {"window", "parts", GF_KEY_SIZE, GF_AOFF(window_parts), GF_IN(2, 64), .def = "4", .unit = "",
     .doc = "sub-windows of the window that calibrate's and compare's uncertainties come from (the standard error "
            "of the mean over them; 2 when the window has fewer than 3 frames a part, none under 6 frames); more for "
            "long references, so that the errors themselves are less noisy"},
    {"dump", "dt", GF_KEY_DOUBLE, GF_AOFF(dump_dt), GF_IN(0, 1e6), .def = "0", .unit = "tau",
     .doc = "time per TIMESTEP, for dumps without ITEM: TIME (0: such dumps are an error); in the dumps' time unit "
            "when dump.diameter and dump.gravity are set (seconds in SI)"},
    {"velocity", "bin", GF_KEY_DOUBLE, GF_AOFF(vel_bin), GF_IN(0.05, 100), .def = "1", .unit = "d",
     .doc = "edge of the square (x, z) bins of the mean velocity field and of the v_z(x) profiles"},
    {"velocity", "heights", GF_KEY_LIST, GF_AOFF(vel_heights), GF_Z, .def = "10,20,30,40,50,60", .unit = "d",
     .doc = "heights z of the v_z(x) profiles, comma-separated, 1 to 16 values", .count_offset = GF_AOFF(vel_nheights),
     .list_max = 16},
    {"velocity", "band", GF_KEY_DOUBLE, GF_AOFF(vel_band), GF_IN(0.05, 100), .def = "1", .unit = "d",
     .doc = "half-thickness of the band |z - height| < band of each profile"},
    {"velocity", "window", GF_KEY_ENUM, GF_AOFF(vel_window), .names = gf_vel_window_names, .def = "height",
     .unit = "", .doc = "frames of each v_z(x) profile: height (only the frame pairs where the mean v_z at that height "
                       "has reached its late value; a height with none is reported, not fitted) or run (every pair of "
                       "the window)"},
    {"velocity", "y_xhalf", GF_KEY_DOUBLE, GF_AOFF(vely_xhalf), GF_IN(0.1, 1e6), .def = "10", .unit = "d",
     .doc = "v_z(y) region: |x - container.orifice_x| < this (2009 paper Fig. 8)"},
    {"velocity", "y_z0", GF_KEY_DOUBLE, GF_AOFF(vely_z0), GF_Z, .def = "50", .unit = "d",
     .doc = "v_z(y) region: z above this"},
    {"velocity", "y_z1", GF_KEY_DOUBLE, GF_AOFF(vely_z1), GF_Z, .def = "70", .unit = "d",
     .doc = "v_z(y) region: z below this"},
    {"diffusion", "xhalf", GF_KEY_DOUBLE, GF_AOFF(diff_xhalf), GF_IN(0.1, 1e6), .def = "5", .unit = "d",
     .doc = "tracked particles start with |x - container.orifice_x| < this (r < this in a cylinder)"},
    {"diffusion", "z0", GF_KEY_DOUBLE, GF_AOFF(diff_z0), GF_Z, .def = "60", .unit = "d",
     .doc = "... and with z above this"},
    {"correlation", "size", GF_KEY_DOUBLE, GF_AOFF(corr_size), GF_IN(1, 1e6), .def = "16", .unit = "d",
     .doc = "edge of the square region of the velocity correlation (thesis Sec. 3.3)"},
    {"correlation", "zc", GF_KEY_DOUBLE, GF_AOFF(corr_zc), GF_Z, .def = "60", .unit = "d",
     .doc = "height of its centre"},
    {"gr", "x0", GF_KEY_DOUBLE, GF_AOFF(gr_x0), GF_Z, .def = "-15", .unit = "d",
     .doc = "structure region, x from (g(r), g3, badness, bulk packing fraction; SPEC 1.6)"},
    {"gr", "x1", GF_KEY_DOUBLE, GF_AOFF(gr_x1), GF_Z, .def = "15", .unit = "d", .doc = "structure region, x to"},
    {"gr", "z0", GF_KEY_DOUBLE, GF_AOFF(gr_z0), GF_Z, .def = "15", .unit = "d", .doc = "structure region, z from"},
    {"gr", "z1", GF_KEY_DOUBLE, GF_AOFF(gr_z1), GF_Z, .def = "45", .unit = "d", .doc = "structure region, z to"},
    {"gr", "rmax", GF_KEY_DOUBLE, GF_AOFF(gr_rmax), GF_IN(0.1, 100), .def = "4", .unit = "d",
     .doc = "g(r) computed for 0 < r < rmax"},
    {"gr", "dr", GF_KEY_DOUBLE, GF_AOFF(gr_dr), GF_IN(1e-4, 1), .def = "0.02", .unit = "d", .doc = "g(r) bin width"},
    {"g3", "rcut", GF_KEY_DOUBLE, GF_AOFF(g3_rcut), GF_IN(0.5, 10), .def = "1.38", .unit = "d",
     .doc = "bond length: neighbours closer than this make the bond angles"},
    {"voronoi", "radius", GF_KEY_DOUBLE, GF_AOFF(vor_avg_radius), GF_IN(0, 100), .def = "2.2", .unit = "d",
     .doc = "radius of the averaged packing-fraction field (2009 paper Fig. 4)"},
    {"density", "z0", GF_KEY_DOUBLE, GF_AOFF(dens_z0), GF_Z, .def = "50", .unit = "d",
     .doc = "the counted slice: z above this (SPEC 1.6)"},
    {"density", "z1", GF_KEY_DOUBLE, GF_AOFF(dens_z1), GF_Z, .def = "70", .unit = "d",
     .doc = "the counted slice: z below this"},
    {"surface", "dx", GF_KEY_DOUBLE, GF_AOFF(surf_dx), GF_IN(0.1, 1e6), .def = "2.5", .unit = "d",
     .doc = "column spacing of the surface regression: x_j = dx j - dx/2 (2009 paper Sec. 4)"},
    {"surface", "columns", GF_KEY_SIZE, GF_AOFF(surf_ncols), GF_IN(2, 1000), .def = "10", .unit = "",
     .doc = "number of columns j = 1..columns"},
    {"zones", "radii", GF_KEY_LIST, GF_AOFF(zone_radii), GF_IN(1e-6, 1e6), .def = "auto", .unit = "d",
     .doc = "outer radii of the radial zones around the axis, increasing (auto: four zones of equal area)",
     .count_offset = GF_AOFF(zone_nradii), .list_max = 16, .increasing = true, .auto_empty = true},
    {"zones", "dr", GF_KEY_DOUBLE, GF_AOFF(zone_dr), GF_IN(0.01, 1e3), .def = "0.5", .unit = "d",
     .doc = "radial bin of v_z(r)"},
    {"zones", "dz", GF_KEY_DOUBLE, GF_AOFF(zone_dz), GF_IN(0.01, 1e3), .def = "2", .unit = "d",
     .doc = "height bin of the streamlines"},
    {"rtd", "tmax", GF_KEY_AUTO, GF_AOFF(rtd_tmax), GF_IN(0, 1e12), .def = "auto", .unit = "tau",
     .doc = "residence times counted up to this after the first frame (auto: the whole run)"},
};
#undef GF_Z
#undef GF_IN
#undef GF_AOFF

const gf_key_table gf_analysis_keys = {gf_analysis_key_list,
                                              sizeof gf_analysis_key_list / sizeof gf_analysis_key_list[0]};

gf_analysis_opts gf_analysis_opts_default(void)
{
    gf_analysis_opts o;
    memset(&o, 0, sizeof o);
    gf_keys_defaults(&gf_analysis_keys, &o);
    return o;
}

gf_analysis_opts *gf_analysis_opts_create(void)
{
    gf_analysis_opts *o = GF_NEW(gf_analysis_opts, 1);
    if (!o) {
        gf_error_set(GF_ERR_NOMEM, "gf_analysis_opts_create: out of memory");
        return NULL;
    }
    *o = gf_analysis_opts_default();
    return o;
}

void gf_analysis_opts_destroy(gf_analysis_opts *o) { GF_DELETE(o, 1); }

gf_status gf_analysis_opts_copy(gf_analysis_opts *dst, const gf_analysis_opts *src)
{
    if (!dst || !src) return gf_error_set(GF_ERR_PARAM, "gf_analysis_opts_copy: NULL options");
    *dst = *src;
    return GF_OK;
}

gf_status gf_analysis_opts_set(gf_analysis_opts *o, const char *assignment)
{
    if (!o) return gf_error_set(GF_ERR_PARAM, "analysis option: NULL options");
    return gf_keys_set(&gf_analysis_keys, o, assignment, "analysis option", NULL);
}

gf_status gf_analysis_opts_get(const gf_analysis_opts *o, const char *key, char *buf, size_t size)
{
    return gf_keys_get(&gf_analysis_keys, o, key, buf, size, "gf_analysis_opts_get");
}

size_t gf_analysis_opts_key_count(void) { return gf_analysis_keys.count; }

gf_status gf_analysis_opts_key_name(size_t i, char *buf, size_t size)
{
    return gf_keys_name(&gf_analysis_keys, i, buf, size, "gf_analysis_opts_key_name");
}

const char *gf_analysis_opts_key_doc(size_t i) { return i < gf_analysis_keys.count ? gf_analysis_key_list[i].doc : NULL; }

const char *gf_analysis_opts_key_default(size_t i)
{
    return i < gf_analysis_keys.count ? gf_analysis_key_list[i].def : NULL;
}

gf_status gf_analysis_opts_check(const gf_analysis_opts *o)
{
    if (!o) return gf_error_set(GF_ERR_PARAM, "gf_analysis_opts_check: NULL options");
    if (!isnan(o->t0) && !isnan(o->t1) && !(o->t0 < o->t1)) {
        char a[32], b[32];
        gf_keys_format_double(o->t0, a, sizeof a);
        gf_keys_format_double(o->t1, b, sizeof b);
        return gf_error_set(GF_ERR_PARAM, "window.t0 = %s must be less than window.t1 = %s (the window is [t0, t1], tau)",
                            a, b);
    }
    return GF_OK;
}

void gf_analysis_window(const gf_analysis_opts *o, const gf_series *s, double *t0, double *t1)
{
    double first = s->nframes ? s->frames[0].time : 0.0;
    double last = s->nframes ? s->frames[s->nframes - 1].time : 0.0;
    *t0 = isnan(o->t0) ? first + 0.25 * (last - first) : o->t0;
    *t1 = isnan(o->t1) ? last : o->t1;
}
