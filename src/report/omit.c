// SPDX-License-Identifier: MIT
// The numbers a report leaves out because they mean nothing for the run, and
// the line saying why: a colleague reading the page should not have to know
// that `transit_mean` of a box silo is `rtd_mean` again, or that a surface
// angle of -0.35 degrees is the packing's, not the flow's.
#include "report/omit.h"

#include "core/textscan.h"
#include "report/html.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "granflow/config.h"

#define GF_OMIT_ENTRIES 256 // keys of one summary.json

// A config key's value as text into buf ("" when it cannot be read).
static void gf_omit_key(const gf_config *cfg, const char *key, char *buf, size_t size)
{
    if (gf_config_get_key(cfg, key, buf, size) != GF_OK) buf[0] = '\0';
}

// The surface angles of analysis/surface.csv (time_tau,slope,angle_deg): did
// they change? A surface the flow never reached keeps its angle bit for bit.
static void gf_omit_surface(gf_report_context *c, const char *dir)
{
    char path[4352];
    snprintf(path, sizeof path, "%s/analysis/surface.csv", dir);
    gf_textscan ts;
    if (gf_textscan_open_regular(&ts, path, GF_HTML_TEXT_MAX) != GF_OK) return; // absent or not a file: no claim
    ts.max_line = GF_TEXTSCAN_MAX_SHORT_LINE;
    char *line;
    size_t len, rows = 0;
    gf_status st;
    double lo = INFINITY, hi = -INFINITY;
    while (gf_textscan_next(&ts, &line, &len, &st) > 0) {
        double t, slope, angle;
        if (sscanf(line, "%lf,%lf,%lf", &t, &slope, &angle) != 3 || !isfinite(angle)) continue;
        lo = fmin(lo, angle);
        hi = fmax(hi, angle);
        rows++;
    }
    gf_textscan_close(&ts);
    if (rows >= 2 && hi - lo <= 1e-9) {
        c->surface_still = true;
        snprintf(c->surface_why, sizeof c->surface_why,
                 "the free surface did not move during the run (its angle is %.4g degrees in all %zu snapshots): the "
                 "flow had not reached it, so the angle is the one the packing was poured with",
                 lo, rows);
    }
}

void gf_report_context_read(gf_report_context *c, const char *dir, const gf_html_entry *run, size_t nrun)
{
    memset(c, 0, sizeof *c);
    for (size_t k = 0; k < nrun; k++)
        if (!strcmp(run[k].key, "scenario") && run[k].text)
            snprintf(c->scenario, sizeof c->scenario, "%s", run[k].value);
    char path[4352];
    snprintf(path, sizeof path, "%s/config.ini", dir);
    gf_config *cfg = gf_config_create();
    if (cfg && gf_config_load(cfg, path) == GF_OK) {
        char shape[32], recirc[32];
        gf_omit_key(cfg, "container.shape", shape, sizeof shape);
        gf_omit_key(cfg, "run.recirculate", recirc, sizeof recirc);
        c->have_config = true;
        c->box = !strcmp(shape, "box");
        c->recirculate = !strcmp(recirc, "on");
    }
    gf_error_clear(); // an unreadable config.ini only means nothing is left out for it
    if (cfg) gf_config_destroy(cfg);
    gf_omit_surface(c, dir);
    // The analysis' numbers that empty a plot: nobody followed, an empty slice.
    snprintf(path, sizeof path, "%s/analysis/summary.json", dir);
    gf_html_entry *e = GF_NEW(gf_html_entry, GF_OMIT_ENTRIES);
    int n = e ? gf_html_json_read(path, e, GF_OMIT_ENTRIES) : -1;
    for (int k = 0; k < n; k++) {
        if (!strcmp(e[k].key, "diffusion_particles") && !strcmp(e[k].value, "0")) c->diffusion_empty = true;
        if (!strcmp(e[k].key, "density_initial") && !strcmp(e[k].value, "null")) c->density_empty = true;
    }
    if (e) GF_DELETE(e, GF_OMIT_ENTRIES);
}

static bool gf_omit_is(const char *key, const char *const *keys, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (!strcmp(key, keys[k])) return true;
    return false;
}

#define GF_OMIT_IS(key, ...) gf_omit_is((key), (const char *const[]){__VA_ARGS__}, \
                                        sizeof((const char *const[]){__VA_ARGS__}) / sizeof(const char *))

static const char gf_omit_zones[] =
    "a box silo without recirculation: the zones are rings about the axis of a cylindrical core, and every exit is a "
    "first pass (the transit time is the residence time, the highest pass 1)";

// Why a null number of an analysis could not be measured.
static const char *gf_omit_null_analysis(const char *key)
{
    if (GF_OMIT_IS(key, "velocity_variance_slope", "velocity_variance_intercept"))
        return "fewer than two of the heights velocity.heights had a velocity profile to fit (heights above the "
               "packing or outside the flow; set velocity.heights inside it) or steady frames (velocity.window = height: "
               "velocity_unsteady_heights counts the heights whose flow had not settled)";
    if (!strcmp(key, "diffusion_length"))
        return "no particle to follow: none started in the region of diffusion.z0 and diffusion.xhalf, or none "
               "moved there";
    if (GF_OMIT_IS(key, "correlation_length", "correlation_amplitude", "correlation_unsteadiness"))
        return "no decay to fit in the correlation region (correlation.zc, correlation.size): no flow there, or too "
               "few pairs";
    if (GF_OMIT_IS(key, "density_initial", "density_steady"))
        return "no particle in the counted slice density.z0 < z < density.z1 in the first snapshot (set the slice "
               "inside the packing)";
    if (!strcmp(key, "surface_angle")) return "no free surface to fit in any snapshot";
    return "could not be measured on this run (null in summary.json)";
}

// Why a number of an LGA run means nothing for its scenario.
static const char *gf_omit_lga(const gf_report_context *c, const gf_html_entry *e)
{
    bool null = !e->text && !strcmp(e->value, "null");
    bool pile = !strcmp(c->scenario, "pile"), channel = !strcmp(c->scenario, "channel");
    bool silo = !strcmp(c->scenario, "silo");
    if (GF_OMIT_IS(e->key, "slope_angle", "slope_left", "slope_right")) {
        if (!pile) return "the heap's slope is measured in the pile only";
        return null ? "the heap has no flank long enough to fit a slope" : NULL;
    }
    if (GF_OMIT_IS(e->key, "wave_variance_initial", "wave_variance_final", "wave_variance_ratio"))
        return channel ? (null ? "no density profile to measure" : NULL) : "density waves are measured in the channel only";
    if (!strcmp(e->key, "particles_added") && !pile) return "only the pile is fed from the top";
    if (channel && GF_OMIT_IS(e->key, "particles_removed", "mean_outflow_rate", "iterations_to_stop", "t50", "t90", "t99"))
        return "nothing leaves the channel (periodic top and bottom)";
    if (!strcmp(e->key, "iterations_to_empty") && null)
        return silo ? "the silo was not empty at the end of the run (a stagnant heap stayed, or the run stopped "
                      "first): the iteration of the last outflow and t50, t90, t99 say when the outflow left"
                    : "only a silo runs until it is empty";
    if (null && GF_OMIT_IS(e->key, "iterations_to_stop", "t50", "t90", "t99")) return "no particle left";
    return NULL;
}

void gf_report_omit(const gf_report_context *c, const gf_html_entry *e, size_t n, const char **why)
{
    for (size_t k = 0; k < n; k++) {
        const char *key = e[k].key;
        bool null = !e[k].text && !strcmp(e[k].value, "null");
        why[k] = NULL;
        if (c->scenario[0]) {
            why[k] = gf_omit_lga(c, &e[k]);
            continue;
        }
        if (!strncmp(key, "skipped_", 8) && e[k].text) why[k] = e[k].value; // the analysis said why
        else if (c->have_config && c->box && !c->recirculate && GF_OMIT_IS(key, "zones_count", "transit_mean", "passes_max"))
            why[k] = gf_omit_zones;
        else if (c->have_config && !c->recirculate && !strcmp(key, "particles_reinserted"))
            why[k] = "no recirculation (run.recirculate = off): no particle is put back";
        else if (c->surface_still && !strcmp(key, "surface_angle")) why[k] = c->surface_why;
        else if (null) why[k] = gf_omit_null_analysis(key);
    }
}

bool gf_report_omit_plot(const gf_report_context *c, const char *name)
{
    if (!strcmp(name, "zones")) return c->have_config && c->box && !c->recirculate;
    if (!strcmp(name, "surface")) return c->surface_still;
    if (!strcmp(name, "diffusion")) return c->diffusion_empty;
    if (!strcmp(name, "density")) return c->density_empty;
    return false;
}
