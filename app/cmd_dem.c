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

/// What --continue went on from and dropped (c filled), said once.
typedef struct gf_dem_cont_show {
    gf_dem_show show;
    const char *dir;
    const gf_dem_cont *c;
    bool said;
} gf_dem_cont_show;

static void gf_dem_cont_say(gf_dem_cont_show *s)
{
    const gf_dem_cont *c = s->c;
    if (s->said || !c->restart[0]) return;
    s->said = true;
    if (c->unreadable[0]) fprintf(stderr, "granflow dem: warning: %s; went on from the other one\n", c->unreadable);
    fprintf(stderr, "granflow dem: went on from %s/%s at t = %g tau (of %g); kept %zu snapshots up to it", s->dir,
            c->restart, (double)c->step * c->dt, (double)c->total * c->dt, c->kept_snaps);
    if (c->dropped_snaps)
        fprintf(stderr, ", removed %zu after it (to t = %g tau: the continued drain writes its own)", c->dropped_snaps,
                c->dropped_until);
    if (c->kept_reins || c->dropped_reins)
        fprintf(stderr, "; reinserted.txt: kept %zu reinsertions before it, removed %zu at or after it", c->kept_reins,
                c->dropped_reins);
    fputs("\n", stderr);
}

/// The progress line, after saying (at the first report, LAMMPS running) where the drain went on from.
static void gf_dem_cont_progress(void *ctx, const gf_dem_progress *p)
{
    gf_dem_cont_show *s = ctx;
    gf_dem_cont_say(s);
    gf_dem_show_progress(&s->show, p);
}

/// granflow dem -o DIR --continue: the interrupted drain of DIR goes on
/// from its newer restart file, with DIR/config.ini (whose run.duration
/// --set may lengthen; dem.mpi_ranks may change: nothing else).
static int gf_dem_cmd_continue(const gf_cli *cli)
{
    if (cli->config_path || cli->drain_only) {
        fprintf(stderr, "granflow dem: error: --continue goes on with %s/config.ini%s: %s\n", cli->out,
                cli->config_path ? ", not another CONFIG" : "",
                cli->config_path ? "a drain under way keeps its configuration (change run.duration with --set)"
                                 : "it does not take --drain-only");
        return GF_EXIT_USAGE;
    }
    static const char *const may[] = {"run.duration=", "dem.mpi_ranks="};
    for (int k = 0; k < cli->nsets; k++) {
        bool ok = false;
        for (size_t j = 0; j < sizeof may / sizeof may[0]; j++) ok = ok || !strncmp(cli->sets[k], may[j], strlen(may[j]));
        if (!ok) {
            fprintf(stderr,
                    "granflow dem: error: --set %s: a drain under way keeps the configuration it ran with "
                    "(%s/config.ini); --continue changes only run.duration (longer) and dem.mpi_ranks\n",
                    cli->sets[k], cli->out);
            return GF_EXIT_USAGE;
        }
    }
    char base[4096];
    snprintf(base, sizeof base, "%s/config.ini", cli->out);
    if (access(base, R_OK) != 0) {
        fprintf(stderr, "granflow dem: error: %s: no DEM run to continue (cannot read %s)\n", cli->out, base);
        return GF_EXIT_USAGE;
    }
    gf_config cfg;
    if (!gf_cli_config(cli, base, &cfg)) return GF_EXIT_USAGE;
    gf_dem_defs dd;
    gf_config_dem_defs(&cfg, &dd);
    volatile sig_atomic_t *stop = gf_cli_catch_stop();
    gf_dem_cont c = {0};
    gf_dem_cont_show show = {.show = {.tty = !cli->quiet && isatty(STDERR_FILENO), .last_wall = -1.0},
                             .dir = cli->out, .c = &c};
    gf_dem_run_opts o = {.ranks = (int)dd.mpi_ranks, .progress = cli->quiet ? NULL : gf_dem_cont_progress,
                         .ctx = &show, .stop = stop, .force = cli->force};
    if (!cli->quiet) fprintf(stderr, "granflow dem: continuing the drain of %s (log: log.continue)\n", cli->out);
    gf_status st = gf_dem_continue(cli->out, &cfg, &o, &c);
    if (show.show.tty && show.show.last_phase != GF_DEM_PHASE_NONE) fputs("\n", stderr);
    if (!cli->quiet) gf_dem_cont_say(&show); // if LAMMPS reported nothing: what the directory now holds
    if (st == GF_ERR_INTERRUPTED) return gf_cli_interrupted("dem", NULL);
    if (st == GF_ERR_EXISTS) return gf_cli_fail_hint("dem", st, "(--force if you know it is not)");
    if (st != GF_OK) return gf_cli_fail("dem", st);
    if (!cli->quiet) fprintf(stderr, "granflow dem: done: %s/snapshots/ (the whole drainage)\n", cli->out);
    return GF_EXIT_OK;
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
    if (cli.dem_continue) return gf_dem_cmd_continue(&cli);
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
