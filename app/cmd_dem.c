// SPDX-License-Identifier: MIT
// `granflow dem`: LAMMPS inputs for a DEM run of the same container, and
// (--run) the LAMMPS run itself with a progress line (SPEC 1.8).
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "granflow/defs.h"
#include "granflow/dem.h"

typedef struct gf_dem_show {
    bool tty;
    gf_dem_phase last_phase;
    double last_wall;
} gf_dem_show;

static void gf_dem_show_progress(void *ctx, const gf_dem_progress *p)
{
    gf_dem_show *s = ctx;
    bool new_phase = p->phase != s->last_phase;
    if (new_phase) {
        if (s->tty && s->last_phase != GF_DEM_PHASE_NONE) fputs("\n", stderr);
        s->last_phase = p->phase;
        if (!s->tty) {
            if (p->phase == GF_DEM_PHASE_FILL) fprintf(stderr, "granflow dem: pouring %lld particles...\n", (long long)p->target);
            else if (p->phase == GF_DEM_PHASE_SETTLE) fprintf(stderr, "granflow dem: settling...\n");
            else if (p->phase == GF_DEM_PHASE_DRAIN)
                fprintf(stderr, "granflow dem: draining %lld particles for %g tau...\n", (long long)p->target, p->until);
            return;
        }
    }
    if (!s->tty || (!new_phase && p->wall_seconds - s->last_wall < 0.25)) return;
    s->last_wall = p->wall_seconds;
    if (p->phase == GF_DEM_PHASE_FILL)
        fprintf(stderr, "\r\033[K[fill]   t = %.1f tau | %lld of %lld particles | KE %.2e | %.0f s", p->time,
                (long long)p->particles, (long long)p->target, p->ke, p->wall_seconds);
    else if (p->phase == GF_DEM_PHASE_SETTLE)
        fprintf(stderr, "\r\033[K[settle] t = %.1f / %.0f tau at most | KE per particle %.2e | %.0f s", p->time, p->until,
                p->ke, p->wall_seconds);
    else if (p->phase == GF_DEM_PHASE_DRAIN) {
        double rate = p->time > 0 ? p->wall_seconds / p->time : 0; // not exact: includes the fill
        (void)rate;
        fprintf(stderr, "\r\033[K[drain]  t = %.2f / %g tau | %lld of %lld particles left | %.0f s", p->time, p->until,
                (long long)p->particles, (long long)p->target, p->wall_seconds);
    }
    fflush(stderr);
}

int gf_cmd_dem(int argc, char **argv)
{
    gf_cli cli;
    int rc = gf_cli_parse(argc, argv, "dem", &cli);
    if (rc != GF_CLI_GO) return rc;
    bool drain_only = cli.drain_only, run = cli.dem_run || drain_only;
    if (!cli.out) {
        fprintf(stderr, "granflow dem: error: -o DIR is required (where the LAMMPS inputs go)\n");
        return GF_EXIT_USAGE;
    }
    gf_config cfg;
    if (!gf_cli_config(&cli, NULL, &cfg)) return GF_EXIT_USAGE;
    gf_dem_defs dd;
    gf_config_dem_defs(&cfg, &dd);
    volatile sig_atomic_t *stop = gf_cli_catch_stop(); // the packing (fill_method generate), LAMMPS
    if (!drain_only) {
        char snap[4096];
        snprintf(snap, sizeof snap, "%s/settled.restart", cli.out);
        if (!cli.force && access(snap, F_OK) == 0) {
            fprintf(stderr,
                    "granflow dem: error: %s already holds a DEM run (%s exists): use --force to overwrite it, "
                    "or --drain-only to drain it again\n",
                    cli.out, snap);
            return GF_EXIT_USAGE;
        }
        gf_dem_plan plan;
        gf_status st = gf_dem_write_inputs(&cfg, cli.out, &(gf_packing_opts){.stop = stop}, &plan);
        if (st == GF_ERR_INTERRUPTED) return gf_cli_interrupted("dem", "nothing written");
        if (st != GF_OK) return gf_cli_fail("dem", st);
        if (!cli.quiet)
            fprintf(stderr,
                    "granflow dem: %s/in.fill (%s %lld particles to z ~ %.1f d, settle at most %g tau) and "
                    "%s/in.drain (%g tau, %lld steps of %g tau, a snapshot every %g tau)\n",
                    cli.out, dd.fill == GF_DEM_POUR ? "pour" : "settle granflow's packing of",
                    (long long)plan.particles, plan.fill_height, dd.settle_time, cli.out, dd.duration,
                    (long long)plan.drain_steps, dd.timestep, dd.snapshot_interval);
    }
    if (!run) {
        if (!cli.quiet)
            fprintf(stderr, "granflow dem: run them with `granflow dem ... --run`, or by hand: cd %s && lmp -in in.fill "
                            "&& lmp -in in.drain (mpirun -np N lmp ... in parallel)\n",
                    cli.out);
        return GF_EXIT_OK;
    }
    gf_dem_show show = {.tty = !cli.quiet && isatty(STDERR_FILENO), .last_wall = -1.0};
    int ranks = (int)dd.mpi_ranks;
    gf_dem_run_opts o = {.ranks = ranks, .drain_only = drain_only,
                         .progress = cli.quiet ? NULL : gf_dem_show_progress, .ctx = &show, .stop = stop};
    if (!cli.quiet)
        fprintf(stderr, "granflow dem: running LAMMPS in %s with %d MPI rank(s) (logs: log.fill, log.drain)\n", cli.out,
                ranks < 1 ? gf_cpu_count() : ranks);
    gf_status st = gf_dem_run(cli.out, &o);
    if (show.tty && show.last_phase != GF_DEM_PHASE_NONE) fputs("\n", stderr);
    if (st == GF_ERR_INTERRUPTED) return gf_cli_interrupted("dem", NULL); // the message names interrupted.txt
    if (st != GF_OK) return gf_cli_fail("dem", st);
    if (!cli.quiet) {
        char exits[4096];
        snprintf(exits, sizeof exits, "%s/exits.csv", cli.out);
        bool recirc = access(exits, F_OK) == 0; // run.recirculate: the particles put back (docs/dem.md)
        fprintf(stderr, "granflow dem: done: %s/packing.dump (settled packing), %s/snapshots/ (the drainage)%s%s\n",
                cli.out, cli.out, recirc ? ", " : "", recirc ? exits : "");
    }
    return GF_EXIT_OK;
}
