// SPDX-License-Identifier: MIT
// gf_bench: the spot engine on a silo in steady flow (2009 paper Sec. 2: the
// cost of spot() and relax()), the silo ten times larger, and the lattice-gas
// automaton's site updates per second (SPEC 2).
#include "granflow/bench.h"

#include <math.h>
#include <string.h>
#include <sys/resource.h>

#include "core/clock.h"
#include "core/error.h"
#include "core/stop.h"
#include "granflow/defs.h"
#include "granflow/lga.h"
#include "spot/sim_internal.h"

// Per rank: peak resident set, particles in its region and slab, particle records held.
#define GF_BENCH_FIGURES 4
#ifdef GF_MPI
#include "spot/par_mpi.h"
#endif

gf_bench_opts gf_bench_opts_default(void)
{
    return (gf_bench_opts){.warmup = 40.0, .window = 1.0, .large = true, .lga_iters = 1000};
}

// The paper's channel in its density-wave regime, timed over `iterations`
// after a warm-up of 200.
static gf_status gf_bench_lga_run(const gf_config *cfg_in, int64_t iterations, volatile sig_atomic_t *stop,
                                  gf_bench_lga *out)
{
    gf_config cfg = *cfg_in;
    gf_lga *l = NULL;
    gf_status st = gf_config_set_key(&cfg, "lga.scenario", "channel");
    if (st == GF_OK) st = gf_lga_create(&cfg, &l);
    if (st != GF_OK) return st;
    gf_lga_run(l, 200, stop);
    double t0 = gf_clock_now();
    gf_lga_run(l, iterations, stop);
    double dt = gf_clock_now() - t0;
    gf_lga_stats s = gf_lga_get_stats(l);
    gf_lga_destroy(l);
    if ((st = gf_stop_check(stop, "bench")) != GF_OK) return st;
    out->sites = s.fluid_sites;
    out->iterations = iterations;
    out->particles = s.particles;
    out->seconds = dt;
    out->site_updates_per_second = dt > 0 ? (double)s.fluid_sites * (double)iterations / dt : 0;
    return GF_OK;
}

// Runs `window` tau more and returns the steps per second of it.
static gf_status gf_bench_window(gf_sim *sim, double *until, double window, const gf_sim_hooks *hooks, double *sps,
                                 gf_sim_stats *a, gf_sim_stats *b)
{
    *a = gf_sim_get_stats(sim);
    double t0 = gf_clock_now();
    *until += window;
    gf_status st = gf_sim_run(sim, *until, hooks);
    double wall = gf_clock_now() - t0;
    *b = gf_sim_get_stats(sim);
    *sps = wall > 0 ? (double)(b->spot_moves - a->spot_moves) / wall : 0;
    return st;
}

// Wall seconds to drain what is left: the flow rate Q does not depend on the
// fill height (Beverloo), so the height falls linearly to 0 over N / Q, and
// the moves per tau, spots rising from the orifice to the surface, fall with
// it: about half the steady figure on average.
static double gf_bench_drain_seconds(const gf_bench_spot *b)
{
    if (b->flow <= 0 || b->sps_all <= 0) return 0;
    return 0.5 * b->moves_per_tau * ((double)b->remaining / b->flow) / b->sps_all;
}

static double gf_bench_peak_rss(void)
{
    struct rusage ru;
    return getrusage(RUSAGE_SELF, &ru) == 0 ? 1024.0 * (double)ru.ru_maxrss : 0;
}

// Every rank's peak resident set, bytes sent per phase and particles in its
// region and slab, gathered on rank 0 (one process: its own). A collective
// under MPI: every rank calls it.
static void gf_bench_ranks(gf_bench_spot *b, const gf_sim *sim)
{
    uint64_t region = 0, owned = 0;
    gf_dom_region_particles(sim, &region, &owned);
    const double rss = gf_bench_peak_rss(); // (before the count below reads the pages never written)
    const double mine[GF_BENCH_FIGURES] = {rss, (double)region, (double)owned, (double)gf_sim_held_particles(sim)};
#ifdef GF_MPI
    enum { F = GF_MPI_FIGURES + 2 };
    double all[GF_BENCH_RANKS * F];
    b->ranks = gf_mpi_rank_figures(mine, all, GF_BENCH_RANKS);
    for (int r = 0; r < b->ranks && r < GF_BENCH_RANKS; r++) {
        b->rank_peak_rss_bytes[r] = all[r * F];
        b->rank_region_particles[r] = all[r * F + 1];
        b->rank_slab_particles[r] = all[r * F + 2];
        b->rank_held_particles[r] = all[r * F + 3];
        b->rank_exchange_bytes_per_phase[r] = all[r * F + GF_MPI_FIGURES];
    }
#else
    b->ranks = 1;
    b->rank_peak_rss_bytes[0] = mine[0];
    b->rank_region_particles[0] = mine[1];
    b->rank_slab_particles[0] = mine[2];
    b->rank_held_particles[0] = mine[3];
    b->rank_exchange_bytes_per_phase[0] = 0;
#endif
}

// Packs cfg's silo the way a run does, warms it up, then times three windows:
// all threads, one thread, one thread with spot() and relax() clocked call by call.
static gf_status gf_bench_silo(const gf_config *cfg, const gf_bench_opts *o, gf_bench_spot *out)
{
    *out = (gf_bench_spot){0};
    double t0 = gf_clock_now();
    gf_sim *sim = NULL;
    gf_status st = gf_sim_create_from_config(cfg, &(gf_packing_opts){.stop = o->stop}, &sim); // gf_packing_for_config, as a run
    if (st != GF_OK) return st;
    out->particles = gf_sim_get_stats(sim).particles_initial;
    sim->keep_part = true; // (a rank that read its region keeps to it: only counters are read)
    out->pack_s = gf_clock_now() - t0;
    gf_engine_defs ed;
    gf_config_engine_defs(cfg, &ed);
    out->threads = ed.spatial ? ed.threads : 1;
    if (o->packed) o->packed(o->ctx, out, sim, o->warmup);
    t0 = gf_clock_now();
    double until = o->warmup;
    gf_sim_hooks hooks = gf_sim_hooks_default();
    hooks.stop = o->stop;
    st = gf_sim_run(sim, until, &hooks);
    out->warm_s = gf_clock_now() - t0;
    gf_sim_stats a, b, c, d;
    if (st == GF_OK) st = gf_bench_window(sim, &until, o->window, &hooks, &out->sps_all, &a, &b);
    out->bytes_per_particle = out->particles ? (double)gf_bytes_allocated() / (double)out->particles : 0;
    gf_sim_set_threads(sim, 1);
    double sps_one = out->sps_all;
    if (st == GF_OK && out->threads > 1) st = gf_bench_window(sim, &until, o->window, &hooks, &sps_one, &c, &d);
    out->sps_one = sps_one;
    gf_sim_set_timing(sim, 1);
    if (ed.spatial) gf_sim_set_par_profiling(sim, 1);
    double dummy;
    if (st == GF_OK) st = gf_bench_window(sim, &until, o->window, &hooks, &dummy, &c, &d);
    out->prof = gf_sim_par_profile(sim);
    gf_bench_ranks(out, sim); // (before the engine goes: its exchange counters go with it)
    gf_sim_destroy(sim);
    if (st == GF_ERR_INTERRUPTED) return gf_error_set(st, "bench: interrupted");
    if (st != GF_OK) return st;
    out->spot_us = d.spot_moves > c.spot_moves ? 1e6 * (d.spot_seconds - c.spot_seconds) / (double)(d.spot_moves - c.spot_moves) : 0;
    out->relax_us = d.relax_calls > c.relax_calls ? 1e6 * (d.relax_seconds - c.relax_seconds) / (double)(d.relax_calls - c.relax_calls) : 0;
    double span = until - o->warmup;
    out->flow = (double)(d.particles_exited - a.particles_exited) / span;
    out->moves_per_tau = (double)(d.spot_moves - a.spot_moves) / span;
    out->spots = d.spots_active;
    out->remaining = d.particles_remaining;
    out->drain_s = gf_bench_drain_seconds(out);
    return GF_OK;
}

// A key of the timed configuration, through config/ (the bench edits a copy).
static gf_status gf_bench_set(gf_config *cfg, const char *key, double value)
{
    char text[64];
    snprintf(text, sizeof text, "%.17g", value);
    return gf_config_set_key(cfg, key, text);
}

gf_status gf_bench(const gf_config *cfg_in, const gf_bench_opts *o, gf_bench_report *out)
{
    if (!cfg_in || !o || !out) return gf_error_set(GF_ERR_PARAM, "gf_bench: NULL argument");
    if (!(o->warmup >= 0 && isfinite(o->warmup)) || !(o->window > 0 && isfinite(o->window)))
        return gf_error_set(GF_ERR_PARAM, "bench: the warm-up (%g tau) must be >= 0 and the window (%g tau) > 0",
                            o->warmup, o->window);
    if (o->lga_iters < 1)
        return gf_error_set(GF_ERR_PARAM, "bench: %lld LGA iterations (at least 1)", (long long)o->lga_iters);
    *out = (gf_bench_report){.lga_only = o->lga_only, .large = o->large && !o->lga_only,
                             .engine = o->event ? "event" : o->spatial ? "spatial" : o->sweep ? "sweep" : "domains", .warmup = o->warmup, .window = o->window};
    gf_config cfg = *cfg_in;
    if (o->lga_only) return gf_bench_lga_run(&cfg, o->lga_iters, o->stop, &out->lga);
    gf_status st = o->particles > 0 ? gf_bench_set(&cfg, "packing.particles", (double)o->particles) : GF_OK;
    if (st == GF_OK) st = gf_config_set_key(&cfg, "run.mode", o->event ? "event" : "fixed");
    if (st == GF_OK && !o->event) st = gf_config_set_key(&cfg, "run.order", out->engine);
    if (st == GF_OK) st = gf_config_set_key(&cfg, "run.checkpoint_interval", "0");
    if (st == GF_OK) st = gf_bench_silo(&cfg, o, &out->silo);
    if (st != GF_OK) return st;
    out->peak_rss_bytes = gf_bench_peak_rss();
    const gf_bench_spot *sb = &out->silo;
    out->step_us = sb->sps_one > 0 ? 1e6 / sb->sps_one : 0;
    out->efficiency = sb->sps_one > 0 ? sb->sps_all / (sb->sps_one * sb->threads) : 0;
    // Ten times the particles in ten times the cross-section: the same height,
    // orifice and spots, so the cost per step shows how it grows with size.
    if (out->large) {
        gf_config big = cfg;
        double f = sqrt(10.0);
        gf_container_defs cd;
        gf_packing_defs pd;
        gf_config_container_defs(&cfg, &cd);
        gf_config_packing_defs(&cfg, &pd);
        st = gf_bench_set(&big, "container.width", cd.width * f);
        if (st == GF_OK) st = gf_bench_set(&big, "container.depth", cd.depth * f);
        if (st == GF_OK) st = gf_bench_set(&big, "packing.particles", (double)(pd.particles * 10));
        if (st == GF_OK && (st = gf_config_validate(&big)) == GF_OK) st = gf_bench_silo(&big, o, &out->big);
        if (st != GF_OK) return st;
    }
    return gf_bench_lga_run(&cfg, o->lga_iters, o->stop, &out->lga);
}
