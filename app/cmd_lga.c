// SPDX-License-Identifier: MIT
// `granflow lga`: the lattice-gas automaton's pile, channel or silo into a directory.
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"

typedef struct gf_lga_progress_ctx {
    double t0, last;
} gf_lga_progress_ctx;

static double gf_lga_clock(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void gf_lga_progress(void *ctx, const gf_lga_stats *s, int64_t until)
{
    gf_lga_progress_ctx *pc = ctx;
    double now = gf_lga_clock();
    if (now - pc->last < 0.25) return;
    pc->last = now;
    double rate = now > pc->t0 ? (double)s->iteration / (now - pc->t0) : 0;
    if (until > 0)
        fprintf(stderr, "\r\033[Kiteration %lld / %lld | %lld particles | %lld out | %.0f it/s", (long long)s->iteration,
                (long long)until, (long long)s->particles, (long long)s->removed, rate);
    else
        fprintf(stderr, "\r\033[Kiteration %lld | %lld particles | %lld out | %.0f it/s", (long long)s->iteration,
                (long long)s->particles, (long long)s->removed, rate);
    fflush(stderr);
}

int gf_cmd_lga(int argc, char **argv)
{
    gf_cli cli;
    int rc = gf_cli_parse(argc, argv, "lga", &cli);
    if (rc != GF_CLI_GO) return rc;
    if (cli.resume) {
        fprintf(stderr, "granflow lga: error: --resume is not supported for LGA runs\n");
        return GF_EXIT_USAGE;
    }
    gf_config cfg;
    if (!gf_cli_config(&cli, NULL, &cfg)) return GF_EXIT_USAGE;
    volatile sig_atomic_t *stop = gf_cli_catch_stop();

    const char *dir = cli.out ? cli.out : "runs/lga";
    bool tty = !cli.quiet && isatty(STDERR_FILENO);
    gf_lga_progress_ctx pc = {gf_lga_clock(), 0};
    gf_lga_run_opts opts = {
        .dir = dir,
        .force = cli.force,
        .stop = stop,
        .progress = tty ? gf_lga_progress : NULL,
        .ctx = &pc,
    };
    gf_lga_summary s;
    gf_status st = gf_lga_run_dir(&cfg, &opts, &s);
    if (tty) fputs("\r\033[K", stderr);
    if (st == GF_ERR_INTERRUPTED) {
        fprintf(stderr, "granflow lga: %s\n", gf_last_error());
        return GF_EXIT_INTERRUPTED;
    }
    if (st != GF_OK)
        return gf_cli_fail_hint("lga", st,
                                st == GF_ERR_EXISTS
                                    ? "(choose another -o, or overwrite it with --force)"
                                    : NULL);
    if (!cli.quiet) {
        fprintf(stderr, "granflow lga: %lld iterations, %lld particles in, %lld out, %lld left", (long long)s.iterations,
                (long long)(s.particles_initial + s.particles_added), (long long)s.particles_removed,
                (long long)s.particles_final);
        if (s.scenario == GF_LGA_PILE) fprintf(stderr, ", slope %.1f degrees", s.slope_angle);
        if (s.scenario == GF_LGA_SILO && s.iterations_to_empty >= 0)
            fprintf(stderr, ", empty after %lld iterations", (long long)s.iterations_to_empty);
        if (s.scenario == GF_LGA_CHANNEL)
            fprintf(stderr, ", density-wave variance x%.1f", s.wave_variance_final / s.wave_variance_initial);
        fprintf(stderr, " (%.1f s, %.0fM site updates/s) -> %s/\n", s.wall_seconds, s.site_updates_per_second / 1e6, dir);
    }
    return GF_EXIT_OK;
}
