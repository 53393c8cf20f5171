// SPDX-License-Identifier: MIT
// The event-driven spot simulation (2009 paper Sec. 2, its pseudocode; SPEC 1.4).
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/alloc.h"
#include "core/clock.h"
#include "core/error.h"
#include "spot/sim_internal.h"

void gf_sim_derive(gf_sim *sim)
{
    const gf_config *c = &sim->cfg;
    sim->box = gf_container_make(c);
    sim->rs = c->spot_radius;
    sim->rs2 = c->spot_radius * c->spot_radius;
    sim->re = c->relax_radius;
    sim->re2 = c->relax_radius * c->relax_radius;
    sim->alpha = c->relax_alpha;
    sim->inv_w = 1.0 / c->spot_w;
    sim->ball_frac = c->spot_ball_centre == GF_BALL_END ? 1.0 : 0.5;
    sim->spot_ins_r = fmax(0.0, 0.5 * c->orifice_diameter - c->spot_insertion_margin);
    // SPEC 1.3 mass balance: a spot is born one radius below the exit, so its
    // ball sweeps its whole volume past the exit plane as it rises.
    sim->spot_birth_z = gf_config_exit_plane(c) - c->spot_radius;
    sim->no_relax = c->relax_method == GF_RELAX_NONE;
    sim->use_nlist = c->relax_method != GF_RELAX_NONE;
}

gf_status gf_sim_alloc_particles(gf_sim *sim, size_t n)
{
    sim->cap = n;
    sim->p = GF_NEW(gf_pos, n);
    sim->p0 = GF_NEW(gf_ref, n);
    sim->id = GF_NEW(int64_t, n);
    sim->layer = GF_NEW(int32_t, n);
    sim->alive = GF_NEW(uint8_t, n);
    sim->mark = GF_NEW(uint32_t, n);
    sim->hist = GF_NEW(gf_hist, n);
    if (!sim->p || !sim->p0 || !sim->id || !sim->layer || !sim->alive || !sim->mark || !sim->hist)
        return gf_error_set(GF_ERR_NOMEM, "out of memory for %zu particles", n);
    return GF_OK;
}

bool gf_sim_exits_reserve(gf_sim *sim, size_t extra)
{
    if (sim->nexit + extra <= sim->exit_cap) return true;
    size_t cap = sim->exit_cap ? sim->exit_cap + sim->exit_cap / 2 : 1024;
    if (cap < sim->nexit + extra) cap = sim->nexit + extra;
    gf_exit *x = gf_realloc(sim->exits, sim->exit_cap * sizeof(gf_exit), cap * sizeof(gf_exit));
    if (!x) return false;
    sim->exits = x;
    sim->exit_cap = cap;
    return true;
}

gf_status gf_work_init(const gf_sim *sim, gf_work *w)
{
    // A gather keeps the particles within r_e: GF_GATHER_DENSITY per d^3 of
    // the ball of r_e + 1 at most (gf_gather checks), and never more than all.
    // Spheres smaller than the papers' pack more centres per d^3: by (0.5 / r_min)^3.
    double r = sim->re + 1.0, rmin = 0.5;
    for (size_t i = 0; i < sim->n; i++)
        if (sim->alive[i] && sim->p[i].r < rmin) rmin = sim->p[i].r;
    double dens = GF_GATHER_DENSITY * pow(0.5 / rmin, 3.0);
    size_t cap = (size_t)ceil(dens * 4.0 / 3.0 * 3.14159265358979 * r * r * r) + GF_CELL_CAP;
    if (cap > sim->cap) cap = sim->cap ? sim->cap : 1;
    w->scratch_cap = cap;
    w->inside = GF_NEW(uint32_t, cap);
    w->in_ball = GF_NEW(uint8_t, cap);
    w->disp = gf_alloc(sizeof(double[3]) * cap);
    w->cross = GF_NEW(uint32_t, cap);
    w->ip = GF_NEW(gf_pos, cap);
    if (!w->inside || !w->in_ball || !w->disp || !w->cross || !w->ip)
        return gf_error_set(GF_ERR_NOMEM, "out of memory");
    return GF_OK;
}

void gf_work_free(gf_work *w)
{
    GF_DELETE(w->inside, w->scratch_cap);
    GF_DELETE(w->in_ball, w->scratch_cap);
    GF_DELETE(w->cross, w->scratch_cap);
    GF_DELETE(w->ip, w->scratch_cap);
    gf_free(w->disp, sizeof(double[3]) * w->scratch_cap);
    GF_DELETE(w->exits, w->exit_cap);
    GF_DELETE(w->exit_slot, w->exit_cap);
    *w = (gf_work){0};
}

gf_status gf_sim_alloc_scratch(gf_sim *sim)
{
    gf_status st = gf_work_init(sim, &sim->w0);
    sim->w0.rng = &sim->rng;
    sim->w0.st = &sim->st;
    return st;
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
        if (sim->cfg.run_recirculate) sim->grid_ztop += 0.5 * top + 8.0;
    }
    double lo[3], hi[3];
    gf_container_bounds(&sim->box, sim->grid_ztop, lo, hi);
    return gf_grid_init(&sim->grid, lo, hi, GF_CELL_SIZE, sim->cap);
}

static void gf_sim_free_all(gf_sim *sim)
{
    GF_DELETE(sim->p, sim->cap);
    GF_DELETE(sim->p0, sim->cap);
    GF_DELETE(sim->id, sim->cap);
    GF_DELETE(sim->layer, sim->cap);
    GF_DELETE(sim->alive, sim->cap);
    GF_DELETE(sim->mark, sim->cap);
    GF_DELETE(sim->hist, sim->cap);
    GF_DELETE(sim->reins, sim->reins_cap);
    GF_DELETE(sim->exits, sim->exit_cap);
    GF_DELETE(sim->nl, sim->cap << sim->nl_shift);
    GF_DELETE(sim->sx, sim->ns_cap);
    GF_DELETE(sim->sy, sim->ns_cap);
    GF_DELETE(sim->sz, sim->ns_cap);
    GF_DELETE(sim->sbirth, sim->ns_cap);
    GF_DELETE(sim->scount, sim->ns_cap);
    gf_work_free(&sim->w0);
    gf_par_free(sim);
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
    if ((st = gf_sim_make_grid(sim)) != GF_OK) goto fail;
    if ((st = gf_sim_alloc_scratch(sim)) != GF_OK) goto fail;
    if ((st = gf_nlist_build(sim, true)) != GF_OK) goto fail;
    gf_rng_seed(&sim->rng, cfg->run_seed, 0x5350u /* "SP": the spot stream */);
    sim->st.particles_initial = sim->n_initial;
    sim->next_ckpt = cfg->run_checkpoint_interval;
    *out = sim;
    return GF_OK;
fail:
    gf_sim_free_all(sim);
    return st;
}

bool gf_sim_exit_slow(gf_sim *sim, gf_work *w, uint32_t i)
{
    gf_pos *q = &sim->p[i];
    if (!gf_container_exited(&sim->box, q->x, q->y, q->z)) return false;
    const gf_hist *h = &sim->hist[i];
    gf_exit e = {sim->id[i], sim->t, q->x, q->y, h->pass, h->t_entry, h->r_entry};
    const bool back = gf_sim_recirculates(sim, h->pass);
    if (w->defer_exits) {
        // The parallel step: kept by the worker, merged (sorted by id) after the phase.
        if (w->nexit == w->exit_cap) {
            size_t cap = w->exit_cap ? 2 * w->exit_cap : 64;
            gf_exit *x = gf_realloc(w->exits, w->exit_cap * sizeof(gf_exit), cap * sizeof(gf_exit));
            if (x) w->exits = x;
            uint32_t *sl = gf_realloc(w->exit_slot, w->exit_cap * sizeof(uint32_t), cap * sizeof(uint32_t));
            if (sl) w->exit_slot = sl;
            if (!x || !sl) { // out of memory: the particle stays, and the step reports it
                w->exit_failed = true;
                return false;
            }
            w->exit_cap = cap;
        }
        w->exit_slot[w->nexit] = back ? i : UINT32_MAX;
        w->exits[w->nexit++] = e;
    } else {
        if (back && !gf_sim_reinsert_queue(sim, i)) {
            w->exit_failed = true;
            return false;
        }
        // Exits of one step share its time; keep them ordered by id so the list
        // does not depend on the order particles were found in.
        if (!gf_sim_exits_reserve(sim, 1)) {
            w->exit_failed = true;
            return false;
        }
        size_t k = sim->nexit++;
        while (k > 0 && sim->exits[k - 1].time == sim->t && sim->exits[k - 1].id > sim->id[i]) {
            sim->exits[k] = sim->exits[k - 1];
            k--;
        }
        sim->exits[k] = e;
        sim->n_alive--;
    }
    gf_grid_remove(&sim->grid, i);
    gf_nlist_drop(sim, i);
    sim->alive[i] = 0;
    q->x = q->y = q->z = GF_PARK_COORD;
    return true;
}

gf_status gf_sim_track_moves(gf_sim *sim, gf_work *w, size_t m, const uint8_t *moved)
{
    const uint32_t *inside = w->inside;
    const gf_pos *p = sim->p;
    gf_grid *g = &sim->grid;
    uint32_t *cross = w->cross;
    size_t nc = 0;
    // Cells first, so that the refreshes below search a grid that is current.
    // (Exited particles are not flagged in moved[]; they left the grid.)
    for (size_t k = 0; k < m; k++) {
        if (!moved[k]) continue;
        uint32_t i = inside[k];
        const gf_pos *q = &p[i];
        const gf_ref *a = &sim->p0[i];
        double dx = q->x - a->x, dy = q->y - a->y, dz = q->z - a->z, lim = a->h - GF_SKIN_SLACK;
        cross[nc] = i;
        nc += dx * dx + dy * dy + dz * dz > lim * lim;
        uint32_t c = gf_grid_cell(g, q->x, q->y, q->z);
        if (c != g->cell_of[i]) {
            gf_grid_remove(g, i);
            gf_status st = gf_grid_insert(g, i, c);
            if (st != GF_OK) return st;
        }
    }
    for (size_t k = 0; sim->use_nlist && k < nc; k++) {
        gf_status st = gf_nlist_refresh(sim, cross[k]);
        if (st != GF_OK) return st;
    }
    return GF_OK;
}

gf_status gf_spot_insert(gf_sim *sim)
{
    if (sim->ns == sim->ns_cap) {
        size_t old = sim->ns_cap, cap = old ? 2 * old : 1024;
        double *x = gf_realloc(sim->sx, old * sizeof(double), cap * sizeof(double));
        if (x) sim->sx = x;
        double *y = gf_realloc(sim->sy, old * sizeof(double), cap * sizeof(double));
        if (y) sim->sy = y;
        double *z = gf_realloc(sim->sz, old * sizeof(double), cap * sizeof(double));
        if (z) sim->sz = z;
        uint64_t *b = gf_realloc(sim->sbirth, old * sizeof(uint64_t), cap * sizeof(uint64_t));
        if (b) sim->sbirth = b;
        uint32_t *n = gf_realloc(sim->scount, old * sizeof(uint32_t), cap * sizeof(uint32_t));
        if (n) sim->scount = n;
        if (!x || !y || !z || !b || !n) return gf_error_set(GF_ERR_NOMEM, "out of memory for spots");
        sim->ns_cap = cap;
    }
    // SPEC 1.3 insertion: uniform on the orifice shrunk by the margin.
    double x, y;
    if (sim->box.shape == GF_ORIFICE_SLIT) {
        x = (2.0 * gf_rng_uniform(&sim->rng) - 1.0) * sim->spot_ins_r;
        double ylo = sim->box.ylo + sim->cfg.spot_wall_distance, yhi = sim->box.yhi - sim->cfg.spot_wall_distance;
        y = ylo + (yhi - ylo) * gf_rng_uniform(&sim->rng);
    } else {
        double rad = sim->spot_ins_r * sqrt(gf_rng_uniform(&sim->rng));
        double ang = 2.0 * 3.14159265358979323846 * gf_rng_uniform(&sim->rng);
        x = rad * cos(ang);
        y = rad * sin(ang);
    }
    size_t k = sim->ns++;
    sim->sx[k] = x;
    sim->sy[k] = y;
    sim->sz[k] = sim->spot_birth_z;
    sim->sbirth[k] = sim->next_birth++;
    sim->scount[k] = 0;
    sim->st.spots_inserted++;
    return GF_OK;
}

static void gf_spot_delete(gf_sim *sim, size_t k)
{
    size_t last = --sim->ns;
    sim->sx[k] = sim->sx[last];
    sim->sy[k] = sim->sy[last];
    sim->sz[k] = sim->sz[last];
    sim->sbirth[k] = sim->sbirth[last];
    sim->scount[k] = sim->scount[last];
    sim->st.spots_deleted++;
}

// Candidate `dir` of a move from s: the BCC walk (+-dx, 0, dz), (0, +-dy, dz)
// (2009 paper Sec. 2), truncated d_w from each side wall (0 with reflection,
// Sec. 4) and, below the base, kept over the region spots are born in.
static void gf_walk_candidate(const gf_sim *sim, const double s[3], uint64_t dir, double n[3])
{
    const gf_config *c = &sim->cfg;
    const gf_container *b = &sim->box;
    double h = c->spot_step_xy;
    n[0] = s[0] + (dir == 0 ? h : dir == 1 ? -h : 0.0);
    n[1] = s[1] + (dir == 2 ? h : dir == 3 ? -h : 0.0);
    n[2] = s[2] + c->spot_step_z;
    double dw = c->spot_walls == GF_WALLS_REFLECT ? 0.0 : c->spot_wall_distance;
    b->ops->spot_clamp(b, n, dw);
    double nx = n[0], ny = n[1], nz = n[2];
    if (nz < 0.0) {
        if (b->shape == GF_ORIFICE_SLIT) {
            nx = nx < -sim->spot_ins_r ? -sim->spot_ins_r : (nx > sim->spot_ins_r ? sim->spot_ins_r : nx);
        } else {
            double rho2 = nx * nx + ny * ny, R = sim->spot_ins_r;
            if (rho2 > R * R) {
                double f = R / sqrt(rho2);
                nx *= f;
                ny *= f;
            }
        }
    }
    n[0] = nx;
    n[1] = ny;
    n[2] = nz;
}

// Sec. 3 biased walk: candidate i with probability p_i^beta / sum_j p_j^beta,
// p_i the particles a step to i would move. Returns false when every p_i is
// 0 above the base (the spot is to be removed).
static bool gf_walk_biased(gf_sim *sim, gf_work *w, const double s[3], double n[3])
{
    double cand[4][3], wgt[4], q = 0.0;
    const double f = sim->ball_frac, beta = sim->cfg.spot_bias_exponent;
    for (uint64_t d = 0; d < 4; d++) {
        gf_walk_candidate(sim, s, d, cand[d]);
        double c[3] = {s[0] + f * (cand[d][0] - s[0]), s[1] + f * (cand[d][1] - s[1]), s[2] + f * (cand[d][2] - s[2])};
        double p = (double)gf_ball_count(sim, c, sim->rs);
        wgt[d] = p > 0.0 ? pow(p, beta) : 0.0;
        q += wgt[d];
    }
    double u = gf_rng_uniform(w->rng);
    uint64_t pick = 3;
    if (q > 0.0) {
        double acc = 0.0, target = u * q;
        for (uint64_t d = 0; d < 4; d++) {
            acc += wgt[d];
            if (target < acc && wgt[d] > 0.0) {
                pick = d;
                break;
            }
        }
        while (wgt[pick] == 0.0) pick--; // rounding at the top end: the last candidate with weight
    } else if (cand[0][2] > 0.0) {
        return false;
    } else {
        pick = (uint64_t)(u * 4.0); // below the base, on the way up: the plain walk
        if (pick > 3) pick = 3;
    }
    n[0] = cand[pick][0];
    n[1] = cand[pick][1];
    n[2] = cand[pick][2];
    return true;
}

// Whether this move relaxes (2009 paper Sec. 5).
static bool gf_relax_due(gf_sim *sim, gf_work *w, uint32_t *count)
{
    const gf_config *c = &sim->cfg;
    if (sim->no_relax) return false;
    switch (c->relax_method) {
    case GF_RELAX_FULL: return true;
    case GF_RELAX_RANDOM: return gf_rng_uniform(w->rng) * c->relax_k < 1.0; // method 1: probability 1/k
    case GF_RELAX_COUNTER:                                                   // method 2: every k-th own move
        if (++*count < (uint32_t)llround(c->relax_k)) return false;
        *count = 0;
        return true;
    default: return false; // none; global relaxes the whole packing on its own schedule
    }
}

// One step of a spot at s (2009 paper Sec. 2 pseudocode; SPEC 1.3): the
// walk, wall truncation, removal test, spot() and relax().
gf_status gf_spot_step(gf_sim *sim, gf_work *w, double s[3], uint32_t *count, bool *deleted, long *ball)
{
    *deleted = false;
    *ball = 0;
    double n[3];
    if (sim->cfg.spot_bias_exponent > 0.0) {
        if (!gf_walk_biased(sim, w, s, n)) {
            *deleted = true;
            return GF_OK;
        }
    } else {
        // The BCC walk, each candidate with probability 1/4.
        gf_walk_candidate(sim, s, gf_rng_below(w->rng, 4), n);
        // SPEC 1.3 removal: above the highest particle of its column (in the
        // parallel step: as the column was when the step began).
        double top = w->coltop ? w->coltop[gf_grid_column(&sim->grid, n[0], n[1])]
                               : gf_grid_column_top(&sim->grid, n[0], n[1], &sim->p[0].z, 4);
        if (n[2] > top) {
            *deleted = true;
            return GF_OK;
        }
    }
    double v[3] = {n[0] - s[0], n[1] - s[1], n[2] - s[2]};
    double f = sim->ball_frac;
    double centre[3] = {s[0] + f * v[0], s[1] + f * v[1], s[2] + f * v[2]};
    double u[3] = {-v[0] * sim->inv_w, -v[1] * sim->inv_w, -v[2] * sim->inv_w};

    double t0 = sim->timing ? gf_clock_now() : 0.0;
    long moved = gf_spot_apply(sim, w, centre, u);
    if (sim->timing) w->st->spot_seconds += gf_clock_now() - t0;
    if (moved < 0) return GF_ERR_STATE;
    w->st->spot_moves++;
    *ball = moved;
    gf_status st;
    if (moved == 0) {
        if ((st = gf_spot_unmark(sim, w)) != GF_OK) return st;
        // SPEC 1.3 removal: no particle in reach; never keep moving in empty
        // space (below the base, on the way up from its birth, it may).
        if (n[2] > 0.0) {
            *deleted = true;
            return GF_OK;
        }
    } else if (!gf_relax_due(sim, w, count)) {
        if ((st = gf_spot_unmark(sim, w)) != GF_OK) return st;
    } else {
        double t1 = gf_clock_now(); // t_relax is always measured (the summary reports it)
        st = gf_relax_apply(sim, w, centre);
        w->st->relax_seconds += gf_clock_now() - t1;
        if (st != GF_OK) return st;
        w->st->relax_calls++;
    }
    if (w->exit_failed) return gf_error_set(GF_ERR_NOMEM, "out of memory for the exits");
    s[0] = n[0];
    s[1] = n[1];
    s[2] = n[2];
    return GF_OK;
}

static gf_status gf_spot_move(gf_sim *sim, size_t k)
{
    double s[3] = {sim->sx[k], sim->sy[k], sim->sz[k]};
    bool deleted;
    long ball;
    gf_status st = gf_spot_step(sim, &sim->w0, s, &sim->scount[k], &deleted, &ball);
    if (st != GF_OK) return st;
    if (deleted) {
        gf_spot_delete(sim, k);
        return GF_OK;
    }
    sim->sx[k] = s[0];
    sim->sy[k] = s[1];
    sim->sz[k] = s[2];
    return GF_OK;
}

void gf_spots_compact(gf_sim *sim, const uint8_t *dead)
{
    size_t w = 0, ns = sim->ns;
    for (size_t k = 0; k < ns; k++) {
        if (dead[k]) continue;
        sim->sx[w] = sim->sx[k];
        sim->sy[w] = sim->sy[k];
        sim->sz[w] = sim->sz[k];
        sim->sbirth[w] = sim->sbirth[k];
        sim->scount[w] = sim->scount[k];
        w++;
    }
    sim->st.spots_deleted += ns - w;
    sim->ns = w;
}

gf_status gf_sim_global(gf_sim *sim)
{
    double t0 = gf_clock_now();
    gf_status st = gf_relax_global(sim);
    sim->st.relax_seconds += gf_clock_now() - t0;
    if (st == GF_OK && sim->w0.exit_failed) st = gf_error_set(GF_ERR_NOMEM, "out of memory for the exits");
    return st;
}

// Time of the next global relaxation (relax.method = global, event mode):
// every k/mu, counted rather than summed so no rounding accumulates.
static double gf_sim_global_time(const gf_sim *sim)
{
    return (double)(sim->st.global_relaxations + 1) * sim->cfg.relax_k / sim->cfg.spot_move_rate;
}

// The time of whatever happens next: the pending event, or a global
// relaxation due before it.
static double gf_sim_next_time(const gf_sim *sim)
{
    if (sim->cfg.relax_method == GF_RELAX_GLOBAL && sim->cfg.run_mode == GF_MODE_EVENT)
        return fmin(sim->t_pending, gf_sim_global_time(sim));
    return sim->t_pending;
}

// Fixed timestep (2009 paper Sec. 2.1; SPEC 1.4): at t = k / mu insert
// Poisson(lambda / mu) spots, then move every spot once, in a fresh random
// order or newest first. Spots removed during the step are compacted away
// afterwards, keeping the array in birth order.
gf_status gf_sim_fixed_begin(gf_sim *sim)
{
    const gf_config *c = &sim->cfg;
    sim->t = sim->t_pending;
    sim->pending = false;
    sim->fstep++;
    sim->st.events++;
    gf_status st = GF_OK;
    uint64_t nins = gf_rng_poisson(&sim->rng, c->spot_insertion_rate / c->spot_move_rate);
    for (uint64_t k = 0; k < nins && st == GF_OK; k++) st = gf_spot_insert(sim);
    return st;
}

gf_status gf_sim_fixed_end(gf_sim *sim)
{
    // Method 3: the whole packing every k steps (every k / mu).
    const gf_config *c = &sim->cfg;
    if (c->relax_method == GF_RELAX_GLOBAL && sim->fstep % (uint64_t)llround(c->relax_k) == 0)
        return gf_sim_global(sim);
    return GF_OK;
}

static gf_status gf_sim_fixed_step(gf_sim *sim)
{
    const gf_config *c = &sim->cfg;
    gf_status st = gf_sim_fixed_begin(sim);
    if (st != GF_OK) return st;
    size_t ns = sim->ns, cap = ns ? ns : 1;
    uint32_t *order = GF_NEW(uint32_t, cap);
    uint8_t *dead = GF_NEW(uint8_t, cap);
    if (!order || !dead) st = gf_error_set(GF_ERR_NOMEM, "out of memory for a fixed step");
    for (size_t k = 0; st == GF_OK && k < ns; k++) order[k] = c->run_order == GF_ORDER_NEWEST ? (uint32_t)(ns - 1 - k) : (uint32_t)k;
    if (st == GF_OK && c->run_order == GF_ORDER_RANDOM)
        for (size_t k = ns; k > 1; k--) { // Fisher-Yates
            size_t j = (size_t)gf_rng_below(&sim->rng, k);
            uint32_t tmp = order[k - 1];
            order[k - 1] = order[j];
            order[j] = tmp;
        }
    for (size_t o = 0; st == GF_OK && o < ns; o++) {
        size_t k = order[o];
        double s[3] = {sim->sx[k], sim->sy[k], sim->sz[k]};
        bool deleted;
        long ball;
        st = gf_spot_step(sim, &sim->w0, s, &sim->scount[k], &deleted, &ball);
        if (deleted) {
            dead[k] = 1;
            continue;
        }
        sim->sx[k] = s[0];
        sim->sy[k] = s[1];
        sim->sz[k] = s[2];
    }
    if (st == GF_OK) gf_spots_compact(sim, dead);
    if (order) GF_DELETE(order, cap);
    if (dead) GF_DELETE(dead, cap);
    if (st == GF_OK) st = gf_sim_fixed_end(sim);
    return st;
}

// Work done, in the units of run.reorder_interval: events, or spot moves in
// fixed mode (where one step is thousands of moves).
static uint64_t gf_sim_work(const gf_sim *sim)
{
    return sim->cfg.run_mode == GF_MODE_FIXED ? sim->st.spot_moves : sim->st.events;
}

// The action of the next event: a fixed step, a global relaxation due, an
// insertion or a spot move.
static gf_status gf_sim_action(gf_sim *sim)
{
    if (sim->cfg.run_mode == GF_MODE_FIXED)
        return sim->cfg.run_order == GF_ORDER_SPATIAL ? gf_sim_spatial_step(sim) : gf_sim_fixed_step(sim);
    if (sim->cfg.relax_method == GF_RELAX_GLOBAL) {
        double tg = gf_sim_global_time(sim);
        if (tg <= sim->t_pending) {
            sim->t = tg;
            return gf_sim_global(sim);
        }
    }
    sim->t = sim->t_pending;
    sim->pending = false;
    sim->st.events++;
    double lambda = sim->cfg.spot_insertion_rate;
    double rate = lambda + (double)sim->ns * sim->cfg.spot_move_rate;
    if (gf_rng_uniform(&sim->rng) * rate < lambda) return gf_spot_insert(sim);
    return gf_spot_move(sim, (size_t)gf_rng_below(&sim->rng, sim->ns));
}

// Applies whatever comes next: a global relaxation due, or the pending event.
static gf_status gf_sim_event(gf_sim *sim)
{
    gf_status st;
    if (gf_sim_work(sim) - sim->nl_built_at >= (uint64_t)sim->cfg.run_reorder_interval) {
        if ((st = gf_nlist_build(sim, true)) != GF_OK) return st;
        sim->nl_built_at = gf_sim_work(sim);
    }
    st = gf_sim_action(sim);
    // Recirculation: whatever exited in this event or step goes back on the
    // surface before the next one (one place for every engine).
    if (st == GF_OK && sim->nreins > 0) st = gf_sim_reinsert(sim);
    return st;
}

static void gf_sim_draw_pending(gf_sim *sim)
{
    if (sim->pending) return;
    if (sim->cfg.run_mode == GF_MODE_FIXED) {
        sim->t_pending = (double)(sim->fstep + 1) / sim->cfg.spot_move_rate;
    } else {
        double rate = sim->cfg.spot_insertion_rate + (double)sim->ns * sim->cfg.spot_move_rate;
        sim->t_pending = sim->t + gf_rng_exp(&sim->rng, rate);
    }
    sim->pending = true;
}

gf_status gf_sim_step(gf_sim *sim)
{
    gf_sim_draw_pending(sim);
    gf_status st = gf_sim_event(sim);
    if (sim->t > sim->t_reached) sim->t_reached = sim->t;
    return st;
}

gf_status gf_sim_run(gf_sim *sim, double until, const gf_run_hooks *hooks)
{
    static const gf_run_hooks none = {0};
    if (!hooks) hooks = &none;
    const double dsnap = sim->cfg.output_snapshot_interval, dck = sim->cfg.run_checkpoint_interval;
    const double last_snap = until + 1e-9 * dsnap; // k * dsnap may round just above until
    uint64_t every = hooks->progress_every ? hooks->progress_every : UINT64_MAX;
    uint64_t countdown = every;
    gf_status st = GF_OK;
    for (;;) {
        if (hooks->stop && *hooks->stop) return GF_ERR_INTERRUPTED;
        gf_sim_draw_pending(sim);
        const double tn = gf_sim_next_time(sim);
        for (double ts; (ts = (double)sim->next_snap * dsnap) <= tn && ts <= last_snap;) {
            if (hooks->stop && *hooks->stop) return GF_ERR_INTERRUPTED; // many snapshots may be due at once
            if (ts > sim->t_reached) sim->t_reached = ts;
            if (hooks->snapshot && (st = hooks->snapshot(hooks->ctx, sim, sim->next_snap, ts)) != GF_OK)
                return st;
            sim->next_snap++;
        }
        while (dck > 0 && sim->next_ckpt <= tn && sim->next_ckpt <= until) {
            if (hooks->stop && *hooks->stop) return GF_ERR_INTERRUPTED;
            if (sim->next_ckpt > sim->t_reached) sim->t_reached = sim->next_ckpt;
            if (hooks->checkpoint && (st = hooks->checkpoint(hooks->ctx, sim)) != GF_OK) return st;
            // Due times that no longer advance (an interval below the rounding
            // of the time; gf_config_validate refuses those) skip ahead.
            double next = sim->next_ckpt + dck;
            sim->next_ckpt = next > sim->next_ckpt ? next : nextafter(tn, INFINITY);
        }
        if (tn > until || sim->n_alive == 0) {
            if (until > sim->t_reached && tn > until) sim->t_reached = until;
            return GF_OK;
        }
        uint64_t moves0 = sim->st.spot_moves;
        if ((st = gf_sim_event(sim)) != GF_OK) return st;
        sim->t_reached = sim->t;
        // Progress counts events, or the moves of a fixed step (thousands each).
        uint64_t done = sim->cfg.run_mode == GF_MODE_FIXED ? sim->st.spot_moves - moves0 + 1 : 1;
        if (countdown <= done) {
            countdown = every;
            if (hooks->progress) hooks->progress(hooks->ctx, sim);
        } else {
            countdown -= done;
        }
    }
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

void gf_sim_set_threads(gf_sim *sim, int threads) { sim->cfg.run_threads = threads > 0 ? threads : 0; }

typedef struct gf_id_index {
    int64_t id;
    uint32_t index;
} gf_id_index;

static int gf_cmp_id(const void *a, const void *b)
{
    int64_t x = ((const gf_id_index *)a)->id, y = ((const gf_id_index *)b)->id;
    return (x > y) - (x < y);
}

gf_status gf_sim_particles(const gf_sim *sim, gf_packing *out)
{
    size_t m = 0, cap = sim->n_alive ? sim->n_alive : 1;
    gf_id_index *idx = GF_NEW(gf_id_index, cap);
    if (!idx) return gf_error_set(GF_ERR_NOMEM, "out of memory");
    for (size_t i = 0; i < sim->n; i++)
        if (sim->alive[i]) idx[m++] = (gf_id_index){sim->id[i], (uint32_t)i};
    qsort(idx, m, sizeof *idx, gf_cmp_id);
    out->n = 0;
    gf_status st = gf_packing_reserve(out, m);
    for (size_t k = 0; st == GF_OK && k < m; k++) {
        const gf_pos *q = &sim->p[idx[k].index];
        st = gf_packing_push(out, idx[k].id, sim->layer[idx[k].index], q->x, q->y, q->z, q->r);
    }
    GF_DELETE(idx, cap);
    return st;
}

gf_status gf_sim_passes(const gf_sim *sim, int32_t *pass, size_t n)
{
    if (n != sim->n_alive) return gf_error_set(GF_ERR_PARAM, "gf_sim_passes: %zu slots for %zu particles", n, sim->n_alive);
    gf_id_index *idx = GF_NEW(gf_id_index, n ? n : 1);
    if (!idx) return gf_error_set(GF_ERR_NOMEM, "out of memory");
    size_t m = 0;
    for (size_t i = 0; i < sim->n; i++)
        if (sim->alive[i]) idx[m++] = (gf_id_index){sim->id[i], (uint32_t)i};
    qsort(idx, m, sizeof *idx, gf_cmp_id);
    for (size_t k = 0; k < m; k++) pass[k] = sim->hist[idx[k].index].pass;
    GF_DELETE(idx, n ? n : 1);
    return GF_OK;
}

const gf_exit *gf_sim_exits(const gf_sim *sim, size_t *n)
{
    *n = sim->nexit;
    return sim->exits;
}
