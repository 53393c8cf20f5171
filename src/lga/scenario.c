// SPDX-License-Identifier: MIT
// The pile, the channel and the silo of the LGA paper (Sec. 3.1-3.3).
#include "lga/scenario.h"

#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"

#define GF_LGA_SQRT3_2 0.86602540378443864676 // column spacing

double gf_lga_hopper_angle(const gf_lga_defs *d)
{
    if (!isnan(d->angle)) return d->angle;
    return d->flow == GF_LGA_FUNNEL ? GF_LGA_FUNNEL_ANGLE : GF_LGA_MASS_ANGLE;
}

static int gf_lga_or(int64_t v, int def) { return v > 0 ? (int)v : def; }

// A lattice size key that is too small: "WHERE: lga.KEY = N is too small: the
// SCENARIO needs at least MIN UNIT".
static gf_status gf_lga_size_error(const gf_lga *l, const char *key, int v, const char *scenario, int min)
{
    const char *unit = strcmp(key, "lga.width") == 0 ? "columns" : "rows";
    char at[GF_PATH_MAX + 40];
    gf_config_where_lead(&l->cfg, key, at, sizeof at);
    const char *auto_note = gf_config_is_set(&l->cfg, key) ? "" : " (the scenario's default)";
    return gf_error_set(GF_ERR_PARAM, "%s%s = %d%s is too small: the %s needs at least %d %s", at, key, v, auto_note,
                        scenario, min, unit);
}

// gf_lga_lattice_alloc, with a lattice too large blamed on lga.width and lga.height.
static gf_status gf_lga_scenario_alloc(gf_lga *l, int w, int h, bool periodic)
{
    if (!gf_lga_lattice_fits(w, h)) {
        const char *key = gf_config_is_set(&l->cfg, "lga.width") ? "lga.width" : "lga.height";
        char at[GF_PATH_MAX + 40];
        gf_config_where_lead(&l->cfg, key, at, sizeof at);
        return gf_error_set(GF_ERR_PARAM,
                            "%slga.width = %lld and lga.height = %lld make a lattice of %d x %d sites, too large (at "
                            "most %.0f sites)",
                            at, (long long)l->d.width, (long long)l->d.height, w, h,
                            (double)GF_LGA_MAX_SITES);
    }
    return gf_lga_lattice_alloc(l, w, h, periodic);
}

gf_status gf_lga_scenario_finish(gf_lga *l)
{
    gf_status st = gf_lga_lattice_walls(l);
    if (st != GF_OK) return st;
    size_t nsinks = 0;
    int64_t particles = 0, fluid = 0;
    for (int j = 0; j < l->h; j++)
        for (int i = 0; i < l->w; i++) {
            uint16_t s = l->state[gf_lga_index(l, i, j)];
            if (s & GF_LGA_SINK) nsinks++;
            if (!(s & GF_LGA_WALL)) fluid++;
            particles += gf_lga_count(l, s) + l->excess[gf_lga_index(l, i, j)];
        }
    if (l->sinks) GF_DELETE(l->sinks, l->nsinks);
    l->sinks = NULL;
    l->nsinks = 0;
    if (nsinks) {
        l->sinks = GF_NEW(size_t, nsinks);
        if (!l->sinks) return gf_error_set(GF_ERR_NOMEM, "out of memory (LGA sinks)");
        for (int j = 0; j < l->h; j++)
            for (int i = 0; i < l->w; i++)
                if (l->state[gf_lga_index(l, i, j)] & GF_LGA_SINK) l->sinks[l->nsinks++] = gf_lga_index(l, i, j);
    }
    l->particles = particles;
    l->fluid_sites = fluid;
    gf_lga_lattice_busy(l);
    return GF_OK;
}

// Puts `n` particles at random free (site, velocity) slots of the non-wall, non-sink sites.
static gf_status gf_lga_fill_random(gf_lga *l, int64_t n)
{
    size_t nf = 0;
    for (int j = 0; j < l->h; j++)
        for (int i = 0; i < l->w; i++)
            if (!(l->state[gf_lga_index(l, i, j)] & (GF_LGA_WALL | GF_LGA_SINK))) nf++;
    if (n > (int64_t)nf * 12) {
        char at[GF_PATH_MAX + 40];
        gf_config_where_lead(&l->cfg, "lga.particles", at, sizeof at);
        return gf_error_set(GF_ERR_PARAM, "%slga.particles = %lld does not fit: at most 12 per site, %zu sites", at,
                            (long long)n, nf);
    }
    size_t *fl = GF_NEW(size_t, nf ? nf : 1);
    if (!fl) return gf_error_set(GF_ERR_NOMEM, "out of memory (LGA fill)");
    nf = 0;
    for (int j = 0; j < l->h; j++)
        for (int i = 0; i < l->w; i++)
            if (!(l->state[gf_lga_index(l, i, j)] & (GF_LGA_WALL | GF_LGA_SINK))) fl[nf++] = gf_lga_index(l, i, j);
    for (int64_t k = 0; k < n;) {
        size_t s = fl[gf_rng_below(&l->rng, nf)];
        int e = (int)gf_rng_below(&l->rng, 13);
        if (l->state[s] & (1u << e)) continue;
        l->state[s] |= (uint16_t)(1u << e);
        k++;
    }
    GF_DELETE(fl, nf ? nf : 1);
    return GF_OK;
}

// Sec. 3.1: a floor (two wall rows), open sides (sink columns: what flows off
// the edge leaves), particles fed in as v4 at the top centre.
static gf_status gf_lga_build_pile(gf_lga *l)
{
    int w = gf_lga_or(l->d.width, GF_LGA_PILE_WIDTH), h = gf_lga_or(l->d.height, GF_LGA_PILE_HEIGHT);
    if (w < 8) return gf_lga_size_error(l, "lga.width", w, "pile", 8);
    if (h < 6) return gf_lga_size_error(l, "lga.height", h, "pile", 6);
    gf_status st = gf_lga_scenario_alloc(l, w, h, false);
    if (st != GF_OK) return st;
    for (int i = 0; i < w; i++)
        for (int j = 0; j < h; j++) {
            uint16_t *s = &l->state[gf_lga_index(l, i, j)];
            if (j < 2) *s = GF_LGA_WALL;
            else if (i == 0 || i == w - 1) *s = GF_LGA_SINK;
        }
    // Feed: the top two rows, |x - centre| <= 2.
    double xc = 0.5 * (w - 1) * GF_LGA_SQRT3_2;
    size_t nfeed = 0;
    for (int pass = 0; pass < 2; pass++) {
        for (int j = h - 2; j < h; j++)
            for (int i = 1; i < w - 1; i++) {
                if (fabs(i * GF_LGA_SQRT3_2 - xc) > 2.0) continue;
                if (pass) l->feed_sites[l->nfeed++] = gf_lga_index(l, i, j);
                else nfeed++;
            }
        if (!pass) {
            l->feed_sites = GF_NEW(size_t, nfeed);
            if (!l->feed_sites) return gf_error_set(GF_ERR_NOMEM, "out of memory (LGA feed)");
        }
    }
    l->feed_total = l->d.particles > 0 ? l->d.particles : GF_LGA_PILE_PARTICLES;
    l->feed_rate = l->d.feed_rate;
    return gf_lga_scenario_finish(l);
}

// Sec. 3.2: a vertical channel, one wall column on each side, rows periodic,
// particles placed at random with random velocities.
static gf_status gf_lga_build_channel(gf_lga *l)
{
    int w = gf_lga_or(l->d.width, GF_LGA_CHANNEL_WIDTH) + 2, h = gf_lga_or(l->d.height, GF_LGA_CHANNEL_HEIGHT);
    if (h < 8) return gf_lga_size_error(l, "lga.height", h, "channel", 8);
    gf_status st = gf_lga_scenario_alloc(l, w, h, true);
    if (st != GF_OK) return st;
    for (int j = 0; j < h; j++) {
        l->state[gf_lga_index(l, 0, j)] = GF_LGA_WALL;
        l->state[gf_lga_index(l, w - 1, j)] = GF_LGA_WALL;
    }
    int64_t n = l->d.particles > 0 ? l->d.particles : GF_LGA_CHANNEL_PARTICLES;
    if (l->d.particles == 0 && (l->d.width > 0 || l->d.height > 0))
        n = (int64_t)(0.7 * (w - 2) * (double)h + 0.5); // the default density, 0.7 per site
    if ((st = gf_lga_fill_random(l, n)) != GF_OK) return st;
    return gf_lga_scenario_finish(l);
}

// Sec. 3.3: a parallel part of `width` columns and `height` rows over a hopper
// whose walls make `hopper_angle` with the vertical, down to an outlet of
// `outlet_width` d; two sink rows below the outlet; walls everywhere else.
// Filled from the bottom up with resting particles, one per site.
static gf_status gf_lga_build_silo(gf_lga *l)
{
    const gf_config *c = &l->cfg;
    int wp = gf_lga_or(l->d.width, GF_LGA_SILO_WIDTH), hp = gf_lga_or(l->d.height, GF_LGA_SILO_HEIGHT);
    double angle = gf_lga_hopper_angle(&l->d);
    double half = 0.5 * wp * GF_LGA_SQRT3_2; // half-width of the parallel part, d
    double out = 0.5 * l->d.outlet_width;
    if (out > half - 1.0) {
        char at[GF_PATH_MAX + 40], where[GF_PATH_MAX + 32];
        gf_config_where_lead(c, gf_config_is_set(c, "lga.outlet_width") ? "lga.outlet_width" : "lga.width", at,
                             sizeof at);
        gf_config_where(c, "lga.width", where, sizeof where);
        return gf_error_set(GF_ERR_PARAM,
                            "%slga.outlet_width = %g must be less than the silo's width %g d - 2 (lga.width = %d "
                            "columns, %s)",
                            at, l->d.outlet_width, 2.0 * half, wp, where);
    }
    if (hp < 4) return gf_lga_size_error(l, "lga.height", hp, "silo's parallel part", 4);
    double tana = tan(angle * 3.14159265358979323846 / 180.0);
    double y0 = 2.0;                           // outlet level: two sink rows below
    double y1 = y0 + (half - out) / tana;      // top of the hopper
    double ytop = y1 + hp;
    int w = wp + 4;                            // two wall columns each side
    int h = (int)ceil(ytop) + 1;
    gf_status st = gf_lga_scenario_alloc(l, w, h, false);
    if (st != GF_OK) return st;
    double xc = 0.5 * (w - 1) * GF_LGA_SQRT3_2;
    for (int i = 0; i < w; i++)
        for (int j = 0; j < h; j++) {
            double x, y;
            gf_lga_site_position(i, j, &x, &y);
            double dx = fabs(x - xc);
            uint16_t *s = &l->state[gf_lga_index(l, i, j)];
            if (y < y0) *s = dx < out ? GF_LGA_SINK : GF_LGA_WALL;
            else if (!(dx < fmin(half, out + (y - y0) * tana))) *s = GF_LGA_WALL;
        }
    int64_t n = l->d.particles > 0 ? l->d.particles : GF_LGA_SILO_PARTICLES;
    int64_t placed = 0;
    for (int j = 0; j < h && placed < n; j++)
        for (int i = 0; i < w && placed < n; i++) {
            uint16_t *s = &l->state[gf_lga_index(l, i, j)];
            if (*s & (GF_LGA_WALL | GF_LGA_SINK)) continue;
            *s |= GF_LGA_REST;
            placed++;
        }
    if (placed < n) {
        char at[GF_PATH_MAX + 40];
        gf_config_where_lead(c, "lga.particles", at, sizeof at);
        return gf_error_set(GF_ERR_PARAM, "%slga.particles = %lld does not fit in the silo (%lld sites); raise lga.height",
                            at, (long long)n, (long long)placed);
    }
    return gf_lga_scenario_finish(l);
}

gf_status gf_lga_scenario_build(gf_lga *l)
{
    switch (l->d.scenario) {
    case GF_LGA_PILE: return gf_lga_build_pile(l);
    case GF_LGA_CHANNEL: return gf_lga_build_channel(l);
    case GF_LGA_SILO: return gf_lga_build_silo(l);
    }
    return gf_error_set(GF_ERR_PARAM, "lga.scenario: unknown scenario %d", (int)l->d.scenario);
}
