// SPDX-License-Identifier: MIT
// The spot engine's lifecycle (2009 paper Sec. 2; SPEC 1.4): create a
// simulation from a config and a packing, derive its constants, make its
// grid and workers, destroy it, and the small public queries. Layer: the top
// of the engine beside the drivers (drivers.c); it frees what parallel.c made.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/alloc.h"
#include "core/clock.h"
#include "core/error.h"
#include "packing/blame.h"
#include "spot/sim_internal.h"

void gf_sim_derive(gf_sim *sim)
{
    gf_config_engine_defs(&sim->cfg, &sim->d);
    const gf_engine_defs *c = &sim->d;
    sim->box = gf_container_make(&sim->cfg);
    sim->rs = c->radius;
    sim->rs2 = c->radius * c->radius;
    sim->re = c->r_e;
    sim->re2 = c->r_e * c->r_e;
    sim->alpha = c->alpha;
    sim->inv_w = 1.0 / c->w;
    sim->ball_frac = c->ball_centre == GF_BALL_END ? 1.0 : 0.5;
    sim->spot_ins_r = c->insertion_radius;
    sim->spot_birth_z = c->birth_z;
    sim->no_relax = c->method == GF_RELAX_NONE;
    sim->use_nlist = c->method != GF_RELAX_NONE;
}

gf_status gf_sim_alloc_scratch(gf_sim *sim)
{
    gf_status st = gf_work_init(sim, &sim->w0);
    sim->w0.rng = &sim->rng;
    sim->w0.st = &sim->st;
    return st;
}

void gf_sim_grid_bounds(const gf_sim *sim, double lo[3], double hi[3])
{
    gf_container_bounds(&sim->box, sim->grid_ztop, lo, hi);
}

gf_status gf_sim_make_grid(gf_sim *sim)
{
    if (sim->grid_ztop == 0.0) {
        double top = 0.0;
        for (size_t i = 0; i < sim->n; i++)
            if (sim->alive[i] && sim->p[i].z > top) top = sim->p[i].z;
        sim->grid_ztop = top + 2.0;
        // Recirculation keeps the surface near where it began, but a flowing
        // packing dilates and the re-inserted top is loose: room above it.
        if (sim->d.recirculate) sim->grid_ztop += 0.5 * top + 8.0;
    }
    double lo[3], hi[3];
    gf_sim_grid_bounds(sim, lo, hi);
    return sim->part ? gf_grid_init_part(&sim->grid, lo, hi, GF_CELL_SIZE, sim->cap, sim->win_lo, sim->win_hi)
                     : gf_grid_init(&sim->grid, lo, hi, GF_CELL_SIZE, sim->cap);
}

gf_status gf_sim_make_stress(gf_sim *sim)
{
    sim->sfr = sim->d.flow_rule == GF_FLOW_SFR;
    if (!sim->sfr) return GF_OK;
    // The surface the run began with, as gf_sim_make_grid recorded it in
    // grid_ztop (a checkpoint keeps that, so a resumed run solves the same field).
    double top = sim->grid_ztop - 2.0;
    if (sim->d.recirculate) top = (top - 8.0) / 1.5;
    top += 0.5; // centres to the surface
    gf_stress_def def = gf_config_stress_def(&sim->cfg);
    gf_status st = gf_stress_solve(&def, &sim->box, top, &sim->stress);
    if (st != GF_OK) return st;
    sim->sfr_walk = gf_sfr_walk_make(sim->d.step_xy, sim->d.step_z, sim->stress.eps, sim->d.sfr_rise);
    return GF_OK;
}

gf_status gf_sim_write_stress(const gf_sim *sim, const char *dir)
{
    if (!sim->sfr) return GF_OK;
    char path[GF_PATH_MAX + 32];
    snprintf(path, sizeof path, "%s/stress.csv", dir);
    return gf_stress_write_csv(&sim->stress, path);
}

static void gf_sim_free_all(gf_sim *sim)
{
    gf_stress_free(&sim->stress);
    GF_DELETE_PAGES(sim->p, sim->cap);
    GF_DELETE_PAGES(sim->p0, sim->cap);
    GF_DELETE_PAGES(sim->id, sim->cap);
    GF_DELETE_PAGES(sim->layer, sim->cap);
    GF_DELETE_PAGES(sim->alive, sim->cap);
    GF_DELETE_PAGES(sim->mark, sim->cap);
    GF_DELETE_PAGES(sim->hist, sim->cap);
    GF_DELETE(sim->reins, sim->reins_cap);
    GF_DELETE(sim->exits, sim->exit_cap);
    GF_DELETE_PAGES(sim->nl, sim->cap << sim->nl_shift);
    GF_DELETE(sim->sx, sim->ns_cap);
    GF_DELETE(sim->sy, sim->ns_cap);
    GF_DELETE(sim->sz, sim->ns_cap);
    GF_DELETE(sim->sbirth, sim->ns_cap);
    GF_DELETE(sim->scount, sim->ns_cap);
    GF_DELETE(sim->snext, sim->ns_cap);
    gf_work_free(&sim->w0);
    gf_par_free(sim);
    gf_dom_free(sim);
    gf_sweep_free(sim);
    gf_grid_free(&sim->grid);
    gf_free(sim, sizeof *sim);
}

void gf_sim_destroy(gf_sim *sim)
{
    if (sim) gf_sim_free_all(sim);
}

gf_status gf_sim_create(const gf_config *cfg, const gf_packing *packing, gf_sim **out)
{
    *out = NULL;
    if (packing->n == 0) return gf_error_set(GF_ERR_PARAM, "the packing has no particles");
    if (packing->n > GF_MAX_PARTICLES)
        return gf_error_set(GF_ERR_PARAM, "%zu particles: more than the engine's limit of %d",
                            packing->n, GF_MAX_PARTICLES);
    gf_sim *sim = gf_alloc(sizeof *sim);
    if (!sim) return gf_error_set(GF_ERR_NOMEM, "out of memory");
    sim->cfg = *cfg;
    gf_status st = gf_config_validate(&sim->cfg);
    if (st == GF_OK) st = gf_sim_check_config(&sim->cfg);
    if (st != GF_OK) goto fail;
    gf_sim_derive(sim);
    if ((st = gf_sim_alloc_particles(sim, packing->n)) != GF_OK) goto fail;
    sim->n = sim->n_alive = sim->n_initial = packing->n;
    for (size_t i = 0; i < packing->n; i++) {
        sim->p[i] = (gf_pos){packing->x[i], packing->y[i], packing->z[i], packing->r[i]};
        sim->id[i] = packing->id[i];
        sim->layer[i] = packing->layer[i];
        sim->alive[i] = 1;
        sim->hist[i] = (gf_hist){0.0, hypot(packing->x[i], packing->y[i]), 1, 0};
        if (packing->r[i] > sim->rmax) sim->rmax = packing->r[i];
    }
    if ((st = gf_packing_check(packing, &sim->cfg)) != GF_OK) goto fail;
    if ((st = gf_nlist_slots(sim)) != GF_OK) goto fail;
    if ((st = gf_sim_make_grid(sim)) != GF_OK) {
        // The grid spans the packing's height: name the particle that set it
        // (issue 26: z = 1e300 gave "grid too large" and nothing else).
        if (st == GF_ERR_PARAM) st = gf_packing_blame_highest(packing, &sim->cfg, st);
        goto fail;
    }
    if ((st = gf_sim_finish(sim)) != GF_OK) goto fail;
    *out = sim;
    return GF_OK;
fail:
    gf_sim_free_all(sim);
    return st;
}

gf_status gf_sim_finish(gf_sim *sim)
{
    gf_status st;
    if ((st = gf_sim_alloc_scratch(sim)) != GF_OK) return st;
    if ((st = gf_sim_make_stress(sim)) != GF_OK) return st;
    if ((st = gf_nlist_build(sim, true)) != GF_OK) return st;
    gf_rng_seed(&sim->rng, sim->d.seed, 0x5350u /* "SP": the spot stream */);
    sim->st.particles_initial = sim->n_initial;
    sim->next_ckpt = sim->d.checkpoint_interval;
    return GF_OK;
}

gf_sim *gf_sim_new(const gf_config *cfg, gf_status *st)
{
    gf_sim *sim = gf_alloc(sizeof *sim);
    if (!sim) {
        *st = gf_error_set(GF_ERR_NOMEM, "out of memory");
        return NULL;
    }
    sim->cfg = *cfg;
    *st = gf_config_validate(&sim->cfg);
    if (*st == GF_OK) *st = gf_sim_check_config(&sim->cfg);
    if (*st != GF_OK) {
        gf_sim_free_all(sim);
        return NULL;
    }
    gf_sim_derive(sim);
    return sim;
}

void gf_sim_discard(gf_sim *sim)
{
    if (sim) gf_sim_free_all(sim);
}

uint64_t gf_sim_held_particles(const gf_sim *sim)
{
    // (Reading a page never written maps the zero page: nothing becomes resident.)
    uint64_t held = 0;
    for (size_t i = 0; i < sim->n; i++) held += sim->id[i] != 0;
    return held;
}

gf_sim_stats gf_sim_get_stats(const gf_sim *sim)
{
    gf_sim_stats s = sim->st;
    s.time = sim->t_reached;
    s.particles_remaining = sim->n_alive;
    s.particles_exited = sim->nexit;
    s.spots_active = sim->ns;
    return s;
}

const gf_config *gf_sim_config(const gf_sim *sim) { return &sim->cfg; }

void gf_sim_set_timing(gf_sim *sim, int on) { sim->timing = on != 0; }

void gf_sim_set_threads(gf_sim *sim, int threads)
{
    gf_config_set_threads(&sim->cfg, threads);
    gf_config_engine_defs(&sim->cfg, &sim->d);
}
