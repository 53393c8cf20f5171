// SPDX-License-Identifier: MIT
// The time drivers (2009 paper Sec. 2, 2.1; SPEC 1.4): the event-driven
// engine (exponential waiting times) and the fixed timestep (random, newest
// or spatial order, the last in parallel.c), gf_sim_step and gf_sim_run with
// their snapshot and checkpoint hooks. The top of the engine: calls the
// spatial step (parallel.c) and the kernel (walk.c), nothing calls back.
#ifdef GF_MPI
#include <mpi.h>
#endif
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/alloc.h"
#include "core/clock.h"
#include "core/error.h"
#include "spot/par_mpi.h"
#include "spot/sim_internal.h"

// Time of the next global relaxation (relax.method = global, event mode):
// every k/mu, counted rather than summed so no rounding accumulates.
static double gf_sim_global_time(const gf_sim *sim)
{
    return (double)(sim->st.global_relaxations + 1) * sim->d.k / sim->d.move_rate;
}

// The time of whatever happens next: the pending event, or a global
// relaxation due before it.
static double gf_sim_next_time(const gf_sim *sim)
{
    if (sim->d.method == GF_RELAX_GLOBAL && sim->d.mode == GF_MODE_EVENT)
        return fmin(sim->t_pending, gf_sim_global_time(sim));
    return sim->t_pending;
}

static gf_status gf_sim_fixed_step(gf_sim *sim)
{
    const gf_engine_defs *c = &sim->d;
    gf_status st = gf_sim_fixed_begin(sim);
    if (st != GF_OK) return st;
    size_t ns = sim->ns, cap = ns ? ns : 1;
    uint32_t *order = GF_NEW(uint32_t, cap);
    uint8_t *dead = GF_NEW(uint8_t, cap);
    if (!order || !dead) st = gf_error_set(GF_ERR_NOMEM, "out of memory for a fixed step");
    for (size_t k = 0; st == GF_OK && k < ns; k++) order[k] = c->order == GF_ORDER_NEWEST ? (uint32_t)(ns - 1 - k) : (uint32_t)k;
    if (st == GF_OK && c->order == GF_ORDER_RANDOM)
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

#ifdef GF_MPI
// Whether any rank holds its window only (window.c): every rank learns it.
static bool gf_sim_any_part(const gf_sim *sim)
{
    int part = sim->part, any = part;
    if (gf_mpi_size() > 1) MPI_Allreduce(&part, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    return any != 0;
}

// A rank holding its window, maybe before any phase: the state is partial
// over the slabs the engine makes (NULL when it has none: not over slabs).
static const gf_slabs *gf_sim_partial(gf_sim *sim, gf_status *st)
{
    const gf_slabs *s = gf_dom_slabs_made(sim, st);
    if (*st == GF_OK && !s) *st = gf_error_set(GF_ERR_STATE, "a rank holds its region only, but the engine has no slabs");
    if (*st == GF_OK) *st = gf_mpi_slabs_partial(s);
    return *st == GF_OK ? s : NULL;
}
#endif

// MPI ranks over slabs (the domain engine) hold their regions only, as of
// the last phase: before anything reads the rest, every rank's state is made
// whole again (par_mpi_slabs.c; nothing to do otherwise).
static gf_status gf_sim_whole(gf_sim *sim)
{
#ifdef GF_MPI
    gf_status st = GF_OK;
    if (sim->part && !gf_sim_partial(sim, &st)) return st;
    return gf_mpi_whole(sim);
#else
    (void)sim;
    return GF_OK;
#endif
}

// Before a snapshot, a checkpoint or the end of gf_sim_run, which rank 0
// alone writes: ranks that read only their regions of packing.file
// (window.c) gather the state on rank 0 and keep their regions (issue 23);
// otherwise as gf_sim_whole.
static gf_status gf_sim_gather(gf_sim *sim)
{
#ifdef GF_MPI
    if (!gf_sim_any_part(sim)) return gf_sim_whole(sim);
    gf_status st = GF_OK;
    return gf_sim_partial(sim, &st) ? gf_mpi_gather0(sim) : st;
#else
    return gf_sim_whole(sim);
#endif
}

// The full re-sort (every run.reorder_interval): it moves every particle.
// Ranks that hold their regions along z re-sort their windows and keep
// them (par_mpi_slabs.c gf_mpi_resort); otherwise the state is made whole.
static gf_status gf_sim_resort(gf_sim *sim)
{
    gf_status st = GF_OK;
#ifdef GF_MPI
    if (gf_sim_any_part(sim)) {
        const gf_slabs *s = gf_dom_slabs_made(sim, &st);
        if (st != GF_OK) return st;
        if (s && s->axis == 2) return gf_mpi_resort(sim, s);
    }
#endif
    if ((st = gf_sim_whole(sim)) != GF_OK) return st;
    return gf_nlist_build(sim, true);
}

// Work done, in the units of run.reorder_interval: events, or spot moves in
// fixed mode (where one step is thousands of moves).
static uint64_t gf_sim_work(const gf_sim *sim)
{
    return sim->d.mode == GF_MODE_FIXED ? sim->st.spot_moves : sim->st.events;
}

// The action of the next event: a fixed step, a global relaxation due, an
// insertion or a spot move.
static gf_status gf_sim_action(gf_sim *sim)
{
    if (sim->d.mode == GF_MODE_FIXED)
        return sim->d.order == GF_ORDER_SPATIAL   ? gf_sim_spatial_step(sim)
               : sim->d.order == GF_ORDER_DOMAINS ? gf_sim_domains_cycle(sim)
               : sim->d.order == GF_ORDER_SWEEP   ? gf_sim_sweep_window(sim)
                                                        : gf_sim_fixed_step(sim);
    if (sim->d.method == GF_RELAX_GLOBAL) {
        double tg = gf_sim_global_time(sim);
        if (tg <= sim->t_pending) {
            sim->t = tg;
            return gf_sim_global(sim);
        }
    }
    sim->t = sim->t_pending;
    sim->pending = false;
    sim->st.events++;
    double lambda = sim->d.insertion_rate;
    double rate = lambda + (double)sim->ns * sim->d.move_rate;
    if (gf_rng_uniform(&sim->rng) * rate < lambda) return gf_spot_insert(sim);
    return gf_spot_move(sim, (size_t)gf_rng_below(&sim->rng, sim->ns));
}

// Applies whatever comes next: a global relaxation due, or the pending event.
static gf_status gf_sim_event(gf_sim *sim)
{
    gf_status st;
    if (gf_sim_work(sim) - sim->nl_built_at >= (uint64_t)sim->d.reorder_interval) {
        if ((st = gf_sim_resort(sim)) != GF_OK) return st;
        sim->nl_built_at = gf_sim_work(sim);
    }
    st = gf_sim_action(sim);
    // Recirculation: whatever exited in this event or step goes back on the
    // surface before the next one (one place for every engine).
    if (st == GF_OK && sim->nreins > 0 && (st = gf_sim_whole(sim)) == GF_OK) st = gf_sim_reinsert(sim);
    return st;
}

static void gf_sim_draw_pending(gf_sim *sim)
{
    if (sim->pending) return;
    if (sim->d.mode == GF_MODE_FIXED && (sim->d.order == GF_ORDER_DOMAINS || sim->d.order == GF_ORDER_SWEEP)) {
        sim->t_pending = (double)(sim->fstep + 1) * sim->d.window; // cycles of one window
    } else if (sim->d.mode == GF_MODE_FIXED) {
        sim->t_pending = (double)(sim->fstep + 1) / sim->d.move_rate;
    } else {
        double rate = sim->d.insertion_rate + (double)sim->ns * sim->d.move_rate;
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

// Whether the run is to stop here. MPI ranks agree (any rank's flag stops
// all of them at the same point: every rank asks at the same points).
static bool gf_sim_stopping(const gf_sim_hooks *hooks)
{
#ifdef GF_MPI
    return gf_mpi_stop(hooks->stop);
#else
    return hooks->stop && *hooks->stop;
#endif
}

gf_sim_hooks gf_sim_hooks_default(void) { return (gf_sim_hooks){.ctx = NULL}; }

static gf_status gf_sim_run_loop(gf_sim *sim, double until, const gf_sim_hooks *hooks);

gf_status gf_sim_run(gf_sim *sim, double until, const gf_sim_hooks *hooks)
{
    gf_status st = gf_sim_run_loop(sim, until, hooks);
    // What the caller reads next (a checkpoint after a stop, the summary)
    // is the whole state, unless it reads counters only (the bench: its
    // ranks' peak resident sets are those of their regions). (An error
    // ends the job: mpi_app aborts it.)
    gf_status sw = (st == GF_OK || st == GF_ERR_INTERRUPTED) && !sim->keep_part ? gf_sim_gather(sim) : GF_OK;
    return sw != GF_OK ? sw : st;
}

static gf_status gf_sim_run_loop(gf_sim *sim, double until, const gf_sim_hooks *hooks)
{
    static const gf_sim_hooks none = {0};
    if (!hooks) hooks = &none;
    if (isnan(until)) return gf_error_set(GF_ERR_PARAM, "gf_sim_run: the end time is NaN"); // would do nothing
    const double dsnap = sim->d.snapshot_interval, dck = sim->d.checkpoint_interval;
    const double last_snap = until + 1e-9 * dsnap; // k * dsnap may round just above until
    uint64_t every = hooks->progress_every ? hooks->progress_every : UINT64_MAX;
    uint64_t countdown = every;
    gf_status st = GF_OK;
#ifdef GF_MPI
    if ((st = gf_mpi_agree(sim)) != GF_OK) return st; // the ranks start from one state, or not at all
#endif
    for (;;) {
        if (gf_sim_stopping(hooks)) return GF_ERR_INTERRUPTED;
        gf_sim_draw_pending(sim);
        const double tn = gf_sim_next_time(sim);
        for (double ts; (ts = (double)sim->next_snap * dsnap) <= tn && ts <= last_snap;) {
            if (gf_sim_stopping(hooks)) return GF_ERR_INTERRUPTED; // many snapshots may be due at once
            if (ts > sim->t_reached) sim->t_reached = ts;
            // (whole on every rank, whether it writes or not: a collective)
            // (no hook, nothing reads the state: the bench's ranks keep their regions)
            if (hooks->snapshot && ((st = gf_sim_gather(sim)) != GF_OK ||
                                    (st = hooks->snapshot(hooks->ctx, sim, sim->next_snap, ts)) != GF_OK))
                return st;
            sim->next_snap++;
        }
        while (dck > 0 && sim->next_ckpt <= tn && sim->next_ckpt <= until) {
            if (gf_sim_stopping(hooks)) return GF_ERR_INTERRUPTED;
            if (sim->next_ckpt > sim->t_reached) sim->t_reached = sim->next_ckpt;
            if (hooks->checkpoint &&
                ((st = gf_sim_gather(sim)) != GF_OK || (st = hooks->checkpoint(hooks->ctx, sim)) != GF_OK))
                return st;
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
        uint64_t done = sim->d.mode == GF_MODE_FIXED ? sim->st.spot_moves - moves0 + 1 : 1;
        if (countdown <= done) {
            countdown = every;
            if (hooks->progress) hooks->progress(hooks->ctx, sim);
        } else {
            countdown -= done;
        }
    }
}
