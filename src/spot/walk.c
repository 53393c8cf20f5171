// SPDX-License-Identifier: MIT
// The spot step kernel (2009 paper Sec. 2-3 pseudocode; SPEC 1.3): spot
// insertion, the (biased) walk with wall truncation and the removal test, one
// spot's move, compaction of removed spots, the workers that do it, and the
// opening and closing of a fixed step shared by the serial driver (drivers.c)
// and the spatial one (parallel.c). Calls down into the mechanism (mechanism.c: spot(), relax())
// and the bookkeeping (particles.c); never up into the drivers.
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/alloc.h"
#include "core/clock.h"
#include "core/error.h"
#include "spot/sim_internal.h"

// A worker: the scratch of one step (serial: sim->w0; parallel.c: one per thread).
gf_status gf_work_init(const gf_sim *sim, gf_work *w)
{
    // A gather keeps the particles within r_e: GF_GATHER_DENSITY per d^3 of
    // the ball of r_e + 1 at most (gf_gather checks), and never more than all.
    // Spheres smaller than the papers' pack more centres per d^3: by (0.5 / r_min)^3.
    double r = sim->re + 1.0, rmin = 0.5;
    if (sim->part && sim->rmin_all < rmin) rmin = sim->rmin_all; // (a rank's window: the whole packing's)
    for (size_t i = 0; i < sim->n && !sim->part; i++)
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
    for (int k = 0; k < GF_TOUCH_KINDS; k++) GF_DELETE(w->touched[k].v, w->touched[k].cap);
    *w = (gf_work){0};
}

bool gf_touch_grow(gf_touch *t)
{
    size_t cap = t->cap ? t->cap + t->cap / 2 : 1024;
    uint32_t *v = gf_realloc(t->v, t->cap * sizeof(uint32_t), cap * sizeof(uint32_t));
    if (!v) return false;
    t->v = v;
    t->cap = cap;
    return true;
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
        double *tn = gf_realloc(sim->snext, old * sizeof(double), cap * sizeof(double));
        if (tn) sim->snext = tn;
        if (!x || !y || !z || !b || !n || !tn) return gf_error_set(GF_ERR_NOMEM, "out of memory for spots");
        sim->ns_cap = cap;
    }
    // SPEC 1.3 insertion: uniform on the orifice shrunk by the margin.
    // The outlet centre (ox, oy) is container.orifice_x, orifice_y.
    double x, y;
    if (sim->box.shape == GF_ORIFICE_SLIT) {
        x = sim->box.ox + (2.0 * gf_rng_uniform(&sim->rng) - 1.0) * sim->spot_ins_r;
        double ylo = sim->box.ylo + sim->d.wall_distance, yhi = sim->box.yhi - sim->d.wall_distance;
        y = ylo + (yhi - ylo) * gf_rng_uniform(&sim->rng);
    } else {
        double rad = sim->spot_ins_r * sqrt(gf_rng_uniform(&sim->rng));
        double ang = 2.0 * 3.14159265358979323846 * gf_rng_uniform(&sim->rng);
        x = sim->box.ox + rad * cos(ang);
        y = sim->box.oy + rad * sin(ang);
    }
    size_t k = sim->ns++;
    sim->sx[k] = x;
    sim->sy[k] = y;
    sim->sz[k] = sim->spot_birth_z;
    sim->sbirth[k] = sim->next_birth++;
    sim->scount[k] = 0;
    sim->snext[k] = 0.0;
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
    sim->snext[k] = sim->snext[last];
    sim->st.spots_deleted++;
}

// Candidate `dir` of a move from s: the BCC walk (+-dx, 0, dz), (0, +-dy, dz)
// (2009 paper Sec. 2), truncated d_w from each side wall (0 with reflection,
// Sec. 4) and, below the base, kept over the region spots are born in.
static void gf_walk_finish(const gf_sim *sim, double n[3]);

static void gf_walk_candidate(const gf_sim *sim, const double s[3], uint64_t dir, double n[3])
{
    const gf_engine_defs *c = &sim->d;
    double h = c->step_xy;
    n[0] = s[0] + (dir == 0 ? h : dir == 1 ? -h : 0.0);
    n[1] = s[1] + (dir == 2 ? h : dir == 3 ? -h : 0.0);
    n[2] = s[2] + c->step_z;
    gf_walk_finish(sim, n);
}

// A candidate's wall truncation and, below the base, the birth region.
static void gf_walk_finish(const gf_sim *sim, double n[3])
{
    const gf_engine_defs *c = &sim->d;
    const gf_container *b = &sim->box;
    double dw = c->walls == GF_WALLS_REFLECT ? 0.0 : c->wall_distance;
    b->ops->spot_clamp(b, n, dw);
    double nx = n[0], ny = n[1], nz = n[2];
    if (nz < 0.0) { // kept over the birth region around the outlet centre (ox, oy)
        if (b->shape == GF_ORIFICE_SLIT) {
            double lo = b->ox - sim->spot_ins_r, hi = b->ox + sim->spot_ins_r;
            nx = nx < lo ? lo : (nx > hi ? hi : nx);
        } else {
            double qx = nx - b->ox, qy = ny - b->oy, rho2 = qx * qx + qy * qy, R = sim->spot_ins_r;
            if (rho2 > R * R) {
                double f = R / sqrt(rho2);
                nx = b->ox + qx * f;
                ny = b->oy + qy * f;
            }
        }
    }
    n[0] = nx;
    n[1] = ny;
    n[2] = nz;
}

// The in-plane (u) and out-of-plane (v) horizontal directions of the field at s.
static void gf_walk_sfr_axes(const gf_stress_field *f, const double s[3], double u, double eu[2], double ev[2])
{
    eu[0] = 1.0, eu[1] = 0.0, ev[0] = 0.0, ev[1] = 1.0;
    if (!f->axisym) return;
    if (u > 1e-9) {
        eu[0] = s[0] / u;
        eu[1] = s[1] / u;
    }
    ev[0] = -eu[1];
    ev[1] = eu[0];
}

// Where a flow-rule step (du, dz, dv) from s ends: a slip step that would
// end below the floor (not over the outlet) goes the other way along its
// line; a steady one is clamped as the papers' walk's are.
static void gf_walk_sfr_end(const gf_sim *sim, const double s[3], const double eu[2], const double ev[2], double du,
                            double dz, double dv, bool steady, double n[3])
{
    const gf_container *b = &sim->box;
    for (int t = 0; t < 2; t++) {
        n[0] = s[0] + du * eu[0] + dv * ev[0];
        n[1] = s[1] + du * eu[1] + dv * ev[1];
        n[2] = s[2] + dz;
        if (t == 1 || steady || gf_container_over_hole(b, n[0], n[1]) ||
            n[2] >= gf_container_floor_z(b, n[0], n[1], 0.0))
            break;
        du = -du;
        dz = -dz;
    }
    gf_walk_finish(sim, n);
}

// The stochastic flow rule's step (sfr.c; docs/stress.md): along a slip line
// of the stress at s, biased against the out-of-balance force, plus an
// out-of-plane step (y, or the hoop direction about the axis); with
// spot.sfr_rise = steady, up by step_z instead of the line's own rise.
// Outside the field (below the base, on the way up from its birth) the
// papers' walk. (gf_walk_sfr_end: the floor.)
static void gf_walk_sfr(const gf_sim *sim, gf_work *w, const double s[3], double n[3])
{
    const gf_stress_field *f = &sim->stress;
    gf_stress_point p;
    double u = gf_stress_u(f, s[0], s[1]);
    if (s[2] < f->zstop || !gf_stress_at(f, u, s[2], &p)) {
        gf_walk_candidate(sim, s, gf_rng_below(w->rng, 4), n);
        return;
    }
    double du, dz, dv;
    gf_sfr_draw(&sim->sfr_walk, p.psi, p.f, w->rng, &du, &dz, &dv);
    double eu[2], ev[2];
    gf_walk_sfr_axes(f, s, u, eu, ev);
    gf_walk_sfr_end(sim, s, eu, ev, du, dz, dv, sim->sfr_walk.rise > 0.0, n); // docs/stress.md, "The rise"
}

// The candidate of weights wgt[0..n) (some positive, summing to q) that
// target = u q in [0, q) falls on; rounding at the top end gives the last
// candidate with weight.
static int gf_walk_pick(const double *wgt, int n, double target)
{
    double acc = 0.0;
    int pick = n - 1;
    for (int k = 0; k < n; k++) {
        acc += wgt[k];
        if (target < acc && wgt[k] > 0.0) {
            pick = k;
            break;
        }
    }
    while (wgt[pick] == 0.0) pick--;
    return pick;
}

// Sec. 3 biased walk: candidate i with probability p_i^beta / sum_j p_j^beta,
// p_i the particles a step to i would move. Returns false when every p_i is
// 0 above the base (the spot is to be removed).
static bool gf_walk_biased(gf_sim *sim, gf_work *w, const double s[3], double n[3])
{
    double cand[4][3], wgt[4], q = 0.0;
    const double f = sim->ball_frac, beta = sim->d.bias_exponent;
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
        pick = (uint64_t)gf_walk_pick(wgt, 4, u * q);
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

// The flow rule's step with the Sec. 3 free-surface bias (spot.flow_rule =
// sfr, spot.bias_exponent = beta > 0; docs/stress.md "The free surface"):
// each of the eight steps (a slip-line direction times an out-of-plane
// sign) keeps its flow-rule probability times p^beta, p the particles the
// step would move, as gf_walk_biased weights the papers' four. Below the
// field, the papers' biased walk. Returns false when every p is 0 above the
// base (the spot is to be removed).
static bool gf_walk_sfr_biased(gf_sim *sim, gf_work *w, const double s[3], double n[3])
{
    const gf_stress_field *fld = &sim->stress;
    gf_stress_point p;
    double u = gf_stress_u(fld, s[0], s[1]);
    if (s[2] < fld->zstop || !gf_stress_at(fld, u, s[2], &p)) return gf_walk_biased(sim, w, s, n);
    double e[4][2], prob[4];
    const gf_sfr_walk *wk = &sim->sfr_walk;
    gf_sfr_probs(wk, p.psi, p.f, e, prob);
    double eu[2], ev[2];
    gf_walk_sfr_axes(fld, s, u, eu, ev);
    const double f = sim->ball_frac, beta = sim->d.bias_exponent;
    double cand[8][3], wgt[8], q = 0.0;
    for (int k = 0; k < 8; k++) {
        const int line = k >> 1;
        const double du = wk->L * e[line][0], dv = (k & 1) ? -wk->hperp : wk->hperp;
        const double dz = wk->rise > 0.0 ? wk->rise : wk->L * e[line][1];
        gf_walk_sfr_end(sim, s, eu, ev, du, dz, dv, wk->rise > 0.0, cand[k]);
        double c[3] = {s[0] + f * (cand[k][0] - s[0]), s[1] + f * (cand[k][1] - s[1]), s[2] + f * (cand[k][2] - s[2])};
        double cnt = (double)gf_ball_count(sim, c, sim->rs);
        wgt[k] = cnt > 0.0 ? 0.5 * prob[line] * pow(cnt, beta) : 0.0;
        q += wgt[k];
    }
    if (!(q > 0.0)) return cand[0][2] > 0.0 ? false : gf_walk_biased(sim, w, s, n); // as the papers' walk
    const int pick = gf_walk_pick(wgt, 8, gf_rng_uniform(w->rng) * q);
    n[0] = cand[pick][0];
    n[1] = cand[pick][1];
    n[2] = cand[pick][2];
    return true;
}

// Whether this move relaxes (2009 paper Sec. 5).
static bool gf_relax_due(gf_sim *sim, gf_work *w, uint32_t *count)
{
    const gf_engine_defs *c = &sim->d;
    if (sim->no_relax) return false;
    switch (c->method) {
    case GF_RELAX_FULL: return true;
    case GF_RELAX_RANDOM: return gf_rng_uniform(w->rng) * c->k < 1.0; // method 1: probability 1/k
    case GF_RELAX_COUNTER:                                                   // method 2: every k-th own move
        if (++*count < (uint32_t)llround(c->k)) return false;
        *count = 0;
        return true;
    default: return false; // none; global relaxes the whole packing on its own schedule
    }
}

bool gf_spot_walk(gf_sim *sim, gf_work *w, const double s[3], double n[3])
{
    if (sim->d.bias_exponent > 0.0)
        return sim->sfr ? gf_walk_sfr_biased(sim, w, s, n) : gf_walk_biased(sim, w, s, n);
    // The BCC walk, each candidate with probability 1/4; or the flow rule's.
    if (sim->sfr)
        gf_walk_sfr(sim, w, s, n);
    else
        gf_walk_candidate(sim, s, gf_rng_below(w->rng, 4), n);
    // SPEC 1.3 removal: above the highest particle of its column (in the
    // parallel engines: as the column was when the step or window began).
    double top = w->coltop ? w->coltop[gf_grid_column(&sim->grid, n[0], n[1])]
                           : gf_grid_column_top(&sim->grid, n[0], n[1], &sim->p[0].z, 4);
    return !(n[2] > top);
}

// One step of a spot at s (2009 paper Sec. 2 pseudocode; SPEC 1.3): the
// walk, wall truncation, removal test, spot() and relax().
gf_status gf_spot_step(gf_sim *sim, gf_work *w, double s[3], uint32_t *count, bool *deleted, long *ball)
{
    *deleted = false;
    *ball = 0;
    double n[3];
    if (!gf_spot_walk(sim, w, s, n)) {
        *deleted = true;
        return GF_OK;
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

gf_status gf_spot_move(gf_sim *sim, size_t k)
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
        sim->snext[w] = sim->snext[k];
        w++;
    }
    sim->st.spots_deleted += ns - w;
    sim->ns = w;
}

gf_status gf_spots_insert_window(gf_sim *sim, double t_end, double window)
{
    const gf_engine_defs *c = &sim->d;
    uint64_t nins = gf_rng_poisson(&sim->rng, c->insertion_rate * window);
    for (uint64_t k = 0; k < nins; k++) {
        gf_status st = gf_spot_insert(sim);
        if (st != GF_OK) return st;
        double born = t_end - window * gf_rng_uniform(&sim->rng);
        sim->snext[sim->ns - 1] = born + gf_rng_exp(&sim->rng, c->move_rate);
    }
    return GF_OK;
}

gf_status gf_sim_global(gf_sim *sim)
{
    double t0 = gf_clock_now();
    gf_status st = gf_relax_global(sim);
    sim->st.relax_seconds += gf_clock_now() - t0;
    if (st == GF_OK && sim->w0.exit_failed) st = gf_error_set(GF_ERR_NOMEM, "out of memory for the exits");
    return st;
}

// Fixed timestep (2009 paper Sec. 2.1; SPEC 1.4): at t = k / mu insert
// Poisson(lambda / mu) spots, then move every spot once, in a fresh random
// order or newest first. Spots removed during the step are compacted away
// afterwards, keeping the array in birth order.
gf_status gf_sim_fixed_begin(gf_sim *sim)
{
    const gf_engine_defs *c = &sim->d;
    sim->t = sim->t_pending;
    sim->pending = false;
    sim->fstep++;
    sim->st.events++;
    gf_status st = GF_OK;
    uint64_t nins = gf_rng_poisson(&sim->rng, c->insertion_rate / c->move_rate);
    for (uint64_t k = 0; k < nins && st == GF_OK; k++) st = gf_spot_insert(sim);
    return st;
}

gf_status gf_sim_fixed_end(gf_sim *sim)
{
    // Method 3: the whole packing every k steps (every k / mu).
    const gf_engine_defs *c = &sim->d;
    if (c->method == GF_RELAX_GLOBAL && sim->fstep % (uint64_t)llround(c->k) == 0)
        return gf_sim_global(sim);
    return GF_OK;
}
