// SPDX-License-Identifier: MIT
// `granflow run`: drain a silo into a run directory, or resume one.
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "mpi_app.h"

typedef struct gf_progress_ctx {
    bool quiet, tty;
    double last_wall;
} gf_progress_ctx;

static void gf_fmt_duration(char *buf, size_t n, double s)
{
    if (!(s >= 0) || s > 1e7) snprintf(buf, n, "--");
    else if (s >= 3600) snprintf(buf, n, "%dh%02dm", (int)(s / 3600), (int)(s / 60) % 60);
    else if (s >= 60) snprintf(buf, n, "%dm%02ds", (int)(s / 60), (int)s % 60);
    else snprintf(buf, n, "%.0fs", s);
}

static void gf_show_progress(void *ctx, const gf_run_progress *p)
{
    gf_progress_ctx *pc = ctx;
    if (p->phase == GF_RUN_PHASE_STALLED) { // said even with --quiet: the run ends before run.duration
        fprintf(stderr, "%sgranflow run: %s\n", pc->tty ? "\r\033[K" : "", p->note);
        return;
    }
    if (pc->quiet) return;
    if (p->phase == GF_RUN_PHASE_PACKING || p->phase == GF_RUN_PHASE_READING) {
        fprintf(stderr, "granflow run: %s the initial packing...\n", p->phase == GF_RUN_PHASE_PACKING ? "building" : "reading");
        return;
    }
    if (p->phase == GF_RUN_PHASE_IMPORTED) {
        fprintf(stderr, "granflow run: imported %s\n", p->note ? p->note : "the packing");
        return;
    }
    if (p->phase == GF_RUN_PHASE_DONE) {
        if (pc->tty) fputs("\r\033[K", stderr);
        return;
    }
    if (!pc->tty || p->wall_seconds - pc->last_wall < 0.25) return;
    pc->last_wall = p->wall_seconds;
    // Simulated tau per wall second so far in this invocation. Steps per tau
    // grow as spots fill the packing, so early ETAs are optimistic.
    double rate = p->wall_seconds > 0 ? (p->time - p->start) / p->wall_seconds : 0;
    char eta[32];
    gf_fmt_duration(eta, sizeof eta, rate > 0 ? (p->until - p->time) / rate : -1);
    fprintf(stderr, "\r\033[Kt = %.2f / %.2f tau | %zu of %zu particles left | %.0fk steps/s | ETA %s", p->time,
            p->until, p->remaining, p->initial, p->steps_per_second / 1000.0, eta);
    fflush(stderr);
}

int gf_cmd_run(int argc, char **argv)
{
    gf_cli cli;
    int rc = gf_cli_parse(argc, argv, "run", &cli);
    if (rc != GF_CLI_GO) return rc;
    gf_config cfg;
    char base[GF_PATH_MAX + 16];
    const char *dir = cli.out ? cli.out : "runs/silo";
    if (cli.resume) {
        if (cli.config_path) {
            fprintf(stderr, "granflow run: error: --resume takes its configuration from %s/config.ini; "
                            "change run keys with --set\n", cli.resume);
            return GF_EXIT_USAGE;
        }
        dir = cli.resume;
        snprintf(base, sizeof base, "%s/config.ini", cli.resume);
        char ck[GF_PATH_MAX + 32];
        snprintf(ck, sizeof ck, "%s/checkpoint.bin", cli.resume);
        if (access(base, R_OK) != 0 || access(ck, R_OK) != 0) {
            // A run that holds the directory (before its first checkpoint) is
            // what to say, not "no run to resume".
            gf_status busy = gf_run_dir_check_free(cli.resume);
            if (busy != GF_OK) return gf_cli_fail("run", busy);
            fprintf(stderr, "granflow run: error: %s: no run to resume (cannot read %s)\n", cli.resume,
                    access(base, R_OK) != 0 ? base : ck);
            return GF_EXIT_USAGE;
        }
        if (!gf_cli_config(&cli, base, &cfg)) return GF_EXIT_USAGE;
    } else if (!gf_cli_config(&cli, NULL, &cfg)) {
        return GF_EXIT_USAGE;
    }
#ifdef GF_MPI
    // The ranks run the same settings, version and checkpoint, or all stop
    // here. Only rank 0 writes the run directory: the others run in step
    // with it and write nothing (no scratch copy to leave behind if killed).
    if (gf_mpi_app_agree(&cfg, cli.resume ? dir : NULL) != 0) return GF_EXIT_USAGE;
    if (gf_mpi_app_check(&cfg) != 0) return GF_EXIT_USAGE;
    const bool replica = gf_mpi_app_rank() > 0;
    if (replica) cli.quiet = true;
#else
    const bool replica = false;
#endif
    volatile sig_atomic_t *stop = gf_cli_catch_stop();

    gf_progress_ctx pc = {.quiet = cli.quiet, .tty = !cli.quiet && isatty(STDERR_FILENO), .last_wall = -1.0};
    gf_run_opts opts = {
        .dir = dir,
        .resume = cli.resume != NULL,
        .force = cli.force,
        .stop = stop,
        .progress = gf_show_progress,
        .ctx = &pc,
        .replica = replica,
    };
    gf_sim_stats s;
    gf_status st = gf_run_dir(&cfg, &opts, &s);
    if (st == GF_ERR_INTERRUPTED) {
        if (replica) return GF_EXIT_INTERRUPTED; // rank 0 says where the run stopped
        fprintf(stderr, "\ngranflow run: %s\n", gf_last_error());
        if (s.particles_initial > 0) // the run had begun: its checkpoint is on disk
            fprintf(stderr, "granflow run: continue with: granflow run --resume %s\n", dir);
        return GF_EXIT_INTERRUPTED;
    }
    if (st != GF_OK) {
        char hint[4200] = "";
        if (st == GF_ERR_EXISTS) // the library's kind, not its wording
            snprintf(hint, sizeof hint, "(resume it with --resume %s, overwrite it with --force, or choose another -o)", dir);
        return gf_cli_fail_hint("run", st, *hint ? hint : NULL);
    }
    if (!cli.quiet)
        fprintf(stderr, "granflow run: t = %.4g tau, %zu of %zu particles exited, %llu spot moves -> %s/\n", s.time,
                s.particles_exited, s.particles_initial, (unsigned long long)s.spot_moves, dir);
    return GF_EXIT_OK;
}
