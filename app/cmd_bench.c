// SPDX-License-Identifier: MIT
// `granflow bench`: the spot engine on the papers' silo in steady flow:
// microseconds per spot() and relax() call (2009 paper Sec. 2: 7.15 us and
// 115 us), steps per second on one thread and on all, parallel efficiency,
// memory per particle, the projected wall time of a full drainage, the same
// on a silo ten times larger; and the lattice-gas automaton's site updates
// per second (--lga-only: just that).
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
static double gf_clock(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

// The LGA (SPEC 2): site updates per second of the paper's channel (35,000
// particles on 50 x 1000 sites, the lga.* parameters of cfg) in its density-wave
// regime, timed over `iterations` after a warm-up of 200.
typedef struct gf_bench_lga {
    double site_updates_per_second, seconds;
    int64_t sites, iterations, particles;
} gf_bench_lga;

static gf_status gf_bench_lga_run(const gf_config *cfg_in, int64_t iterations, gf_bench_lga *out)
{
    gf_config cfg = *cfg_in;
    cfg.lga_scenario = GF_LGA_CHANNEL;
    gf_lga *l = NULL;
    gf_status st = gf_lga_create(&cfg, &l);
    if (st != GF_OK) return st;
    gf_lga_run(l, 200, NULL);
    double t0 = gf_clock();
    gf_lga_run(l, iterations, NULL);
    double dt = gf_clock() - t0;
    gf_lga_stats s = gf_lga_get_stats(l);
    gf_lga_destroy(l);
    out->sites = s.fluid_sites;
    out->iterations = iterations;
    out->particles = s.particles;
    out->seconds = dt;
    out->site_updates_per_second = dt > 0 ? (double)s.fluid_sites * (double)iterations / dt : 0;
    return GF_OK;
}

static void gf_bench_lga_print(const gf_bench_lga *b)
{
    printf("  lga     %8.1f M site updates/s (channel, %lld particles on %lld sites, %lld iterations in %.2f s)\n",
           b->site_updates_per_second / 1e6, (long long)b->particles, (long long)b->sites, (long long)b->iterations,
           b->seconds);
}

// Figures of one silo in steady flow.
typedef struct gf_bench_spot {
    size_t particles, spots;
    int threads;                   ///< threads of the "all" window
    double pack_s, warm_s;         ///< packing and warm-up wall time
    double sps_all, sps_one;       ///< steps (spot moves) per second, all threads / one
    double spot_us, relax_us;      ///< per call, one thread
    double flow;                   ///< particles per tau over the windows
    double moves_per_tau;          ///< spot moves per tau over the windows
    double bytes_per_particle;     ///< the library's allocations / particles
    size_t remaining;
    gf_par_profile prof;           ///< the spatial step's blocks, over the timed one-thread window
} gf_bench_spot;

static int gf_bench_cores(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n > 0 ? (int)n : 1;
}

// Runs `window` tau more and returns the steps per second of it.
static gf_status gf_bench_window(gf_sim *sim, double *until, double window, double *sps, gf_sim_stats *a,
                                 gf_sim_stats *b)
{
    *a = gf_sim_get_stats(sim);
    double t0 = gf_clock();
    *until += window;
    gf_status st = gf_sim_run(sim, *until, NULL);
    double wall = gf_clock() - t0;
    *b = gf_sim_get_stats(sim);
    *sps = wall > 0 ? (double)(b->spot_moves - a->spot_moves) / wall : 0;
    return st;
}

// Packs cfg's silo, warms it up, then times three windows: all threads, one
// thread, one thread with spot() and relax() clocked call by call.
static gf_status gf_bench_silo(const gf_config *cfg, double warmup, double window, bool quiet, gf_bench_spot *out)
{
    *out = (gf_bench_spot){0};
    double t0 = gf_clock();
    gf_packing pk = {0};
    gf_status st = cfg->packing_file[0] ? gf_packing_read(cfg->packing_file, GF_FORMAT_AUTO, &pk)
                                        : gf_packing_generate(cfg, &pk);
    if (st == GF_OK) gf_packing_tag_layers(&pk, cfg->packing_layer_thickness);
    gf_sim *sim = NULL;
    if (st == GF_OK) st = gf_sim_create(cfg, &pk, &sim);
    gf_packing_free(&pk);
    if (st != GF_OK) return st;
    out->particles = gf_sim_get_stats(sim).particles_initial;
    out->pack_s = gf_clock() - t0;
    bool spatial = cfg->run_mode == GF_MODE_FIXED && cfg->run_order == GF_ORDER_SPATIAL;
    out->threads = spatial ? (cfg->run_threads > 0 ? (int)cfg->run_threads : gf_bench_cores()) : 1;
    if (!quiet)
        fprintf(stderr, "bench: %zu particles packed in %.1f s; warming up %.3g tau on %d thread%s...\n",
                out->particles, out->pack_s, warmup, out->threads, out->threads > 1 ? "s" : "");
    t0 = gf_clock();
    double until = warmup;
    st = gf_sim_run(sim, until, NULL);
    out->warm_s = gf_clock() - t0;
    gf_sim_stats a, b, c, d;
    if (st == GF_OK) st = gf_bench_window(sim, &until, window, &out->sps_all, &a, &b);
    out->bytes_per_particle = (double)gf_bytes_allocated() / (double)out->particles;
    gf_sim_set_threads(sim, 1);
    double sps_one = out->sps_all;
    if (st == GF_OK && out->threads > 1) st = gf_bench_window(sim, &until, window, &sps_one, &c, &d);
    out->sps_one = sps_one;
    gf_sim_set_timing(sim, 1);
    if (spatial) gf_sim_set_par_profiling(sim, 1);
    double dummy;
    if (st == GF_OK) st = gf_bench_window(sim, &until, window, &dummy, &c, &d);
    out->prof = gf_sim_par_profile(sim);
    gf_sim_destroy(sim);
    if (st != GF_OK) return st;
    out->spot_us = d.spot_moves > c.spot_moves ? 1e6 * (d.spot_seconds - c.spot_seconds) / (double)(d.spot_moves - c.spot_moves) : 0;
    out->relax_us = d.relax_calls > c.relax_calls ? 1e6 * (d.relax_seconds - c.relax_seconds) / (double)(d.relax_calls - c.relax_calls) : 0;
    double span = until - (warmup);
    out->flow = (double)(d.particles_exited - a.particles_exited) / span;
    out->moves_per_tau = (double)(d.spot_moves - a.spot_moves) / span;
    out->spots = d.spots_active;
    out->remaining = d.particles_remaining;
    return GF_OK;
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

// The spatial step's decomposition and projected speedups, as JSON members
// (prefix "" or "large_"): work over the sum of each colour phase's
// makespan on T threads, the blocks' times measured on one thread.
static void gf_bench_blocks_json(const char *prefix, const gf_par_profile *f)
{
    if (f->blocks == 0) return;
    printf(", \"%sblocks\": %zu, \"%sblocks_along_xyz\": [%d, %d, %d], \"%scolours\": %d, \"%sphases\": %d, "
           "\"%sblocks_per_colour\": %.2f, \"%sbusy_blocks_per_colour_phase\": %.2f, \"%swork_over_span\": %.2f",
           prefix, f->blocks, prefix, f->blocks_along[0], f->blocks_along[1], f->blocks_along[2], prefix, f->colours,
           prefix, f->phases, prefix, (double)f->blocks / f->colours, prefix,
           f->colour_phases ? (double)f->blocks_run / (double)f->colour_phases : 0.0, prefix,
           f->span_seconds > 0 ? f->work_seconds / f->span_seconds : 0.0);
    for (int i = 0; i < GF_PAR_NPROJ; i++)
        printf(", \"%sprojected_speedup_%d\": %.2f", prefix, f->proj_threads[i],
               f->makespan_seconds[i] > 0 ? f->work_seconds / f->makespan_seconds[i] : 0.0);
}

static void gf_bench_blocks_text(const char *what, const gf_par_profile *f)
{
    if (f->blocks == 0) return;
    printf("  blocks   %8zu (%d x %d x %d), %d colours x %d phases, %.1f busy per colour phase (%s)\n", f->blocks,
           f->blocks_along[0], f->blocks_along[1], f->blocks_along[2], f->colours, f->phases,
           f->colour_phases ? (double)f->blocks_run / (double)f->colour_phases : 0.0, what);
    printf("  projected speedup");
    for (int i = 0; i < GF_PAR_NPROJ; i++)
        printf(" %.1fx on %d threads%s", f->makespan_seconds[i] > 0 ? f->work_seconds / f->makespan_seconds[i] : 0.0,
               f->proj_threads[i], i + 1 < GF_PAR_NPROJ ? "," : "");
    printf(" (work/span %.1f)\n", f->span_seconds > 0 ? f->work_seconds / f->span_seconds : 0.0);
}

static double gf_bench_peak_rss(void)
{
    struct rusage ru;
    return getrusage(RUSAGE_SELF, &ru) == 0 ? 1024.0 * (double)ru.ru_maxrss : 0;
}

int gf_cmd_bench(int argc, char **argv)
{
    // --lga-only: time only the lattice-gas automaton (no packing, no spots).
    // --event: the event-driven engine (one thread) instead of the spatial
    // fixed step. --no-large: skip the silo ten times larger.
    bool lga_only = false, event = false, large = true;
    char *args[256];
    int nargs = 0;
    for (int i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--lga-only")) lga_only = true;
        else if (!strcmp(argv[i], "--event")) event = true;
        else if (!strcmp(argv[i], "--no-large")) large = false;
        else if (nargs < (int)(sizeof args / sizeof args[0])) args[nargs++] = argv[i];
    }
    gf_cli cli;
    if (!gf_cli_parse(nargs, args, "bench", &cli)) return GF_EXIT_USAGE;
    gf_config cfg;
    if (!gf_cli_config(&cli, NULL, &cfg)) return GF_EXIT_USAGE;
    gf_bench_lga lb;
    if (lga_only) {
        gf_status lst = gf_bench_lga_run(&cfg, 1000, &lb);
        if (lst != GF_OK) return gf_cli_fail("bench", lst);
        if (cli.json)
            printf("{\"lga_site_updates_per_second\": %.0f, \"lga_sites\": %lld, \"lga_particles\": %lld, "
                   "\"lga_iterations\": %lld, \"lga_seconds\": %.3f}\n",
                   lb.site_updates_per_second, (long long)lb.sites, (long long)lb.particles, (long long)lb.iterations,
                   lb.seconds);
        else {
            printf("granflow bench: the lattice-gas automaton only\n");
            gf_bench_lga_print(&lb);
        }
        return GF_EXIT_OK;
    }
    if (cli.bench_particles > 0) cfg.packing_particles = (int64_t)cli.bench_particles;
    if (event) {
        cfg.run_mode = GF_MODE_EVENT;
    } else {
        cfg.run_mode = GF_MODE_FIXED;
        cfg.run_order = GF_ORDER_SPATIAL;
    }
    double warmup = cli.bench_warmup > 0 ? cli.bench_warmup : 40.0; // spots reach the top of the 124 d packing
    double window = cli.bench_window > 0 ? cli.bench_window : 1.0;
    cfg.run_checkpoint_interval = 0;

    gf_bench_spot sb, lg = {0};
    gf_status st = gf_bench_silo(&cfg, warmup, window, cli.json, &sb);
    if (st != GF_OK) return gf_cli_fail("bench", st);
    double rss = gf_bench_peak_rss();
    // Ten times the particles in ten times the cross-section: the same height,
    // orifice and spots, so the cost per step shows how it grows with size.
    if (large) {
        gf_config big = cfg;
        double f = sqrt(10.0);
        big.container_width *= f;
        big.container_depth *= f;
        big.packing_particles *= 10;
        if ((st = gf_config_validate(&big)) == GF_OK) st = gf_bench_silo(&big, warmup, window, cli.json, &lg);
        if (st != GF_OK) return gf_cli_fail("bench", st);
    }
    if ((st = gf_bench_lga_run(&cfg, 1000, &lb)) != GF_OK) return gf_cli_fail("bench", st);

    double step_us = sb.sps_one > 0 ? 1e6 / sb.sps_one : 0;
    double eff = sb.sps_one > 0 ? sb.sps_all / (sb.sps_one * sb.threads) : 0;
    double drain = gf_bench_drain_seconds(&sb);
    const char *engine = event ? "event" : "spatial";
    if (cli.json) {
        printf("{\"engine\": \"%s\", \"particles\": %zu, \"threads\": %d, \"warmup_tau\": %g, \"window_tau\": %g, "
               "\"spot_us\": %.4f, \"relax_us\": %.4f, \"step_us\": %.4f, \"steps_per_second\": %.1f, "
               "\"steps_per_second_1thread\": %.1f, \"parallel_efficiency\": %.3f, "
               "\"spots_active\": %zu, \"flow_rate\": %.2f, \"moves_per_tau\": %.0f, "
               "\"memory_bytes_per_particle\": %.1f, \"peak_rss_bytes_per_particle\": %.1f, "
               "\"projected_drain_seconds\": %.0f, \"pack_seconds\": %.2f, \"warmup_seconds\": %.2f",
               engine, sb.particles, sb.threads, warmup, window, sb.spot_us, sb.relax_us, step_us, sb.sps_all,
               sb.sps_one, eff, sb.spots, sb.flow, sb.moves_per_tau, sb.bytes_per_particle,
               rss / (double)sb.particles, drain, sb.pack_s, sb.warm_s);
        gf_bench_blocks_json("", &sb.prof);
        if (large) {
            gf_bench_blocks_json("large_", &lg.prof);
            printf(", \"large_particles\": %zu, \"large_step_us\": %.4f, \"large_steps_per_second\": %.1f, "
                   "\"large_steps_per_second_1thread\": %.1f, \"large_memory_bytes_per_particle\": %.1f, "
                   "\"large_spot_us\": %.4f, \"large_relax_us\": %.4f",
                   lg.particles, lg.sps_one > 0 ? 1e6 / lg.sps_one : 0, lg.sps_all, lg.sps_one,
                   lg.bytes_per_particle, lg.spot_us, lg.relax_us);
        }
        printf(", \"lga_site_updates_per_second\": %.0f, \"lga_sites\": %lld, \"lga_iterations\": %lld}\n",
               lb.site_updates_per_second, (long long)lb.sites, (long long)lb.iterations);
    } else {
        printf("granflow bench: %zu particles, %s engine, steady flow after %.3g tau (%zu spots active)\n",
               sb.particles, engine, warmup, sb.spots);
        printf("  spot()   %8.3f us per call, one thread   (2009 paper: 7.15 us)\n", sb.spot_us);
        printf("  relax()  %8.3f us per call, one thread   (2009 paper: 115 us)\n", sb.relax_us);
        printf("  step     %8.3f us per spot move on one thread: %.0f steps/s\n", step_us, sb.sps_one);
        printf("  threads  %8d: %.0f steps/s, parallel efficiency %.2f\n", sb.threads, sb.sps_all, eff);
        printf("  flow     %8.2f particles per tau; %.0f spot moves per tau\n", sb.flow, sb.moves_per_tau);
        printf("  drainage %8.1f min projected for the %zu particles left (all threads)\n", drain / 60.0,
               sb.remaining);
        printf("  memory   %8.1f bytes per particle allocated by the engine; peak RSS %.1f bytes per particle\n",
               sb.bytes_per_particle, rss / (double)sb.particles);
        gf_bench_blocks_text("papers' silo", &sb.prof);
        if (large) {
            printf("  10x silo %8.3f us per step on one thread (%.2f x the papers' silo), %.0f steps/s on %d threads, "
                   "%.1f bytes per particle (%zu particles)\n",
                   lg.sps_one > 0 ? 1e6 / lg.sps_one : 0, sb.sps_one > 0 && lg.sps_one > 0 ? sb.sps_one / lg.sps_one : 0,
                   lg.sps_all, lg.threads, lg.bytes_per_particle, lg.particles);
            gf_bench_blocks_text("10x silo", &lg.prof);
        }
        printf("  packing %.1f s, warm-up %.1f s\n", sb.pack_s, sb.warm_s);
        gf_bench_lga_print(&lb);
    }
    return GF_EXIT_OK;
}
