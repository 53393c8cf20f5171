// SPDX-License-Identifier: MIT
// `granflow bench`: microseconds per spot() and relax() call and whole steps
// on the papers' silo in flow (2009 paper Sec. 2: 7.15 us and 115 us), and
// the lattice-gas automaton's site updates per second (--lga-only: just that).
#include <stdio.h>
#include <string.h>
#include <time.h>

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

int gf_cmd_bench(int argc, char **argv)
{
    // --lga-only: time only the lattice-gas automaton (no packing, no spots).
    bool lga_only = false;
    char *args[256];
    int nargs = 0;
    for (int i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--lga-only")) lga_only = true;
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
    double warmup = cli.bench_warmup > 0 ? cli.bench_warmup : 40.0; // spots reach the top of the 110 d packing
    double window = cli.bench_window > 0 ? cli.bench_window : 2.0;
    cfg.run_checkpoint_interval = 0;

    double t0 = gf_clock();
    gf_packing pk = {0};
    gf_status st = cfg.packing_file[0] ? gf_packing_read(cfg.packing_file, GF_FORMAT_AUTO, &pk)
                                       : gf_packing_generate(&cfg, &pk);
    if (st == GF_OK) gf_packing_tag_layers(&pk, cfg.packing_layer_thickness);
    gf_sim *sim = NULL;
    if (st == GF_OK) st = gf_sim_create(&cfg, &pk, &sim);
    gf_packing_free(&pk);
    if (st != GF_OK) return gf_cli_fail("bench", st);
    double t_pack = gf_clock() - t0;
    if (!cli.json) fprintf(stderr, "bench: packing of %zu particles in %.1f s; warming up %.3g tau...\n",
                           gf_sim_get_stats(sim).particles_initial, t_pack, warmup);

    t0 = gf_clock();
    st = gf_sim_run(sim, warmup, NULL);
    double t_warm = gf_clock() - t0;
    // Window 1: plain steps (no per-call clocks).
    gf_sim_stats a = gf_sim_get_stats(sim);
    t0 = gf_clock();
    if (st == GF_OK) st = gf_sim_run(sim, warmup + window, NULL);
    double wall = gf_clock() - t0;
    gf_sim_stats b = gf_sim_get_stats(sim);
    // Window 2: the same length with spot() and relax() timed separately.
    gf_sim_set_timing(sim, 1);
    if (st == GF_OK) st = gf_sim_run(sim, warmup + 2 * window, NULL);
    gf_sim_stats c = gf_sim_get_stats(sim);
    gf_sim_destroy(sim);
    if (st != GF_OK) return gf_cli_fail("bench", st);
    if ((st = gf_bench_lga_run(&cfg, 1000, &lb)) != GF_OK) return gf_cli_fail("bench", st);

    double moves = (double)(b.spot_moves - a.spot_moves);
    double step_us = moves > 0 ? 1e6 * wall / moves : 0;
    double spot_us = c.spot_moves > b.spot_moves ? 1e6 * (c.spot_seconds - b.spot_seconds) / (double)(c.spot_moves - b.spot_moves) : 0;
    double relax_us = c.relax_calls > b.relax_calls ? 1e6 * (c.relax_seconds - b.relax_seconds) / (double)(c.relax_calls - b.relax_calls) : 0;
    double sps = wall > 0 ? moves / wall : 0;
    double flow = (double)(b.particles_exited - a.particles_exited) / window;
    if (cli.json) {
        printf("{\"particles\": %zu, \"threads\": 1, \"warmup_tau\": %g, \"window_tau\": %g, "
               "\"spot_us\": %.4f, \"relax_us\": %.4f, \"step_us\": %.4f, \"steps_per_second\": %.1f, "
               "\"spots_active\": %zu, \"flow_rate\": %.2f, \"nlist_builds\": %llu, \"pack_seconds\": %.2f, \"warmup_seconds\": %.2f, "
               "\"lga_site_updates_per_second\": %.0f, \"lga_sites\": %lld, \"lga_iterations\": %lld}\n",
               a.particles_initial, warmup, window, spot_us, relax_us, step_us, sps, b.spots_active, flow, (unsigned long long)(b.nlist_builds - a.nlist_builds), t_pack,
               t_warm, lb.site_updates_per_second, (long long)lb.sites, (long long)lb.iterations);
    } else {
        printf("granflow bench: %zu particles, 1 thread, steady flow after %.3g tau (%zu spots active)\n",
               a.particles_initial, warmup, b.spots_active);
        printf("  spot()  %8.3f us per call   (2009 paper: 7.15 us)\n", spot_us);
        printf("  relax() %8.3f us per call   (2009 paper: 115 us)\n", relax_us);
        printf("  step    %8.3f us per spot move (spot + relax + walk), %.0f steps/s\n", step_us, sps);
        printf("  flow    %8.2f particles per tau over the window\n", flow);
        printf("  lists   %8llu neighbour-list rebuilds in the first window\n",
               (unsigned long long)(b.nlist_builds - a.nlist_builds));
        printf("  packing %.1f s, warm-up %.1f s\n", t_pack, t_warm);
        gf_bench_lga_print(&lb);
    }
    return GF_EXIT_OK;
}
