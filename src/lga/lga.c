// SPDX-License-Identifier: MIT
// The LGA engine's public face: create, step, run, counters, sites.
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "lga/scenario.h"
#include "lga/step.h"

// Separates the LGA's random stream from the spot engine's for the same run.seed.
#define GF_LGA_RNG_STREAM 0x4C4741u

static gf_status gf_lga_begin(const gf_config *cfg, gf_lga **out, gf_lga **l)
{
    if (!out) return gf_error_set(GF_ERR_PARAM, "gf_lga_create: out is NULL");
    *out = NULL;
    if (!cfg) return gf_error_set(GF_ERR_PARAM, "gf_lga_create: cfg is NULL");
    gf_config c = *cfg;
    gf_status st = gf_config_validate(&c);
    if (st != GF_OK) return st;
    *l = gf_alloc(sizeof **l);
    if (!*l) return gf_error_set(GF_ERR_NOMEM, "out of memory (LGA engine)");
    (*l)->cfg = c;
    gf_config_lga_defs(&c, &(*l)->d);
    (*l)->scenario = (*l)->d.scenario;
    gf_rng_seed(&(*l)->rng, (*l)->d.seed, GF_LGA_RNG_STREAM);
    (*l)->settle_skip = -1; // not drawn yet
    return GF_OK;
}

gf_status gf_lga_create(const gf_config *cfg, gf_lga **out)
{
    gf_lga *l = NULL;
    gf_status st = gf_lga_begin(cfg, out, &l);
    if (st != GF_OK) return st;
    if ((st = gf_lga_scenario_build(l)) != GF_OK) {
        gf_lga_destroy(l);
        return st;
    }
    l->initial = l->particles;
    *out = l;
    return GF_OK;
}

gf_status gf_lga_create_empty(const gf_config *cfg, int width, int height, bool periodic, gf_lga **out)
{
    gf_lga *l = NULL;
    gf_status st = gf_lga_begin(cfg, out, &l);
    if (st != GF_OK) return st;
    if ((st = gf_lga_lattice_alloc(l, width, height, periodic)) != GF_OK ||
        (st = gf_lga_scenario_finish(l)) != GF_OK) {
        gf_lga_destroy(l);
        return st;
    }
    *out = l;
    return GF_OK;
}

void gf_lga_destroy(gf_lga *l)
{
    if (!l) return;
    gf_lga_lattice_free(l);
    gf_free(l, sizeof *l);
}

void gf_lga_step(gf_lga *l)
{
    gf_lga_feed(l);
    gf_lga_collide(l);
    gf_lga_scatter(l);
    gf_lga_settle(l);
    gf_lga_stream(l);
    gf_lga_drain(l);
    l->iteration++;
}

void gf_lga_run(gf_lga *l, int64_t iterations, volatile sig_atomic_t *stop)
{
    for (int64_t k = 0; k < iterations && !(stop && *stop); k++) gf_lga_step(l);
}

gf_lga_stats gf_lga_get_stats(const gf_lga *l)
{
    gf_lga_stats s = {
        .iteration = l->iteration,
        .particles = l->particles,
        .initial = l->initial,
        .added = l->added,
        .removed = l->removed,
        .last_outflow = l->last_outflow,
        .to_add = l->feed_total,
        .width = l->w,
        .height = l->h,
        .fluid_sites = l->fluid_sites,
    };
    return s;
}

int64_t gf_lga_moving(const gf_lga *l)
{
    int64_t n = 0;
    for (int j = 0; j < l->h; j++)
        for (int i = 0; i < l->w; i++) n += l->table->count[l->state[gf_lga_index(l, i, j)] & GF_LGA_MOVERS];
    return n;
}

int gf_lga_width(const gf_lga *l) { return l->w; }
int gf_lga_height(const gf_lga *l) { return l->h; }

uint16_t gf_lga_site(const gf_lga *l, int i, int j)
{
    if (i < 0 || j < 0 || i >= l->w || j >= l->h) return 0;
    return l->state[gf_lga_index(l, i, j)] & (GF_LGA_PARTICLES | GF_LGA_WALL | GF_LGA_SINK);
}

gf_status gf_lga_set_site(gf_lga *l, int i, int j, uint16_t state)
{
    if (i < 0 || j < 0 || i >= l->w || j >= l->h)
        return gf_error_set(GF_ERR_PARAM, "gf_lga_set_site: (%d, %d) is outside the %d x %d lattice", i, j, l->w, l->h);
    if (state & ~(GF_LGA_PARTICLES | GF_LGA_WALL | GF_LGA_SINK))
        return gf_error_set(GF_ERR_PARAM, "gf_lga_set_site: unknown bits 0x%x", (unsigned)state);
    if ((state & GF_LGA_WALL) && (state & (GF_LGA_PARTICLES | GF_LGA_SINK)))
        return gf_error_set(GF_ERR_PARAM, "gf_lga_set_site: a wall site holds no particles and is no sink");
    size_t idx = gf_lga_index(l, i, j);
    uint16_t old = l->state[idx];
    l->state[idx] = state;
    if ((old ^ state) & (GF_LGA_WALL | GF_LGA_SINK)) return gf_lga_scenario_finish(l);
    l->particles += gf_lga_count(l, state) - gf_lga_count(l, old);
    if (state & GF_LGA_PARTICLES) gf_lga_mark_busy(l, idx);
    return GF_OK;
}
