// SPDX-License-Identifier: MIT
// `granflow bench`: parses its options and runs gf_bench (granflow/bench.h):
// the spot engine on the papers' silo in steady flow, a silo ten times
// larger, and the lattice-gas automaton (--lga-only: just that).
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "granflow/bench.h"
#ifdef GF_MPI
#include "mpi_app.h"
#endif

static void gf_bench_on_packed(void *ctx, const gf_bench_spot *b, const gf_sim *sim, double warmup)
{
    (void)ctx;
    (void)sim;
    fprintf(stderr, "bench: %zu particles packed in %.1f s; warming up %.3g tau on %d thread%s...\n", b->particles,
            b->pack_s, warmup, b->threads, b->threads > 1 ? "s" : "");
}

int gf_cmd_bench(int argc, char **argv)
{
    // --lga-only: time only the lattice-gas automaton (no packing, no spots).
    // --event: the event-driven engine (one thread), --spatial: the spatial
    // fixed step, --sweep: the sweep engine, instead of the domain engine. --no-large: skip the silo ten
    // times larger.
    gf_bench_opts o = gf_bench_opts_default();
    gf_cli cli;
    int rc = gf_cli_parse(argc, argv, "bench", &cli);
    if (rc != GF_CLI_GO) return rc;
    o.lga_only = cli.lga_only;
    o.event = cli.event;
    o.spatial = cli.spatial;
    o.sweep = cli.sweep;
    if (cli.no_large) o.large = false;
    gf_config cfg;
    if (!gf_cli_config(&cli, NULL, &cfg)) return GF_EXIT_USAGE;
    if (cli.bench_particles > 0) o.particles = (size_t)cli.bench_particles;
    if (cli.bench_warmup > 0) o.warmup = cli.bench_warmup;
    if (cli.bench_window > 0) o.window = cli.bench_window;
    // Under mpirun every rank runs the silo (the domain engine's ranks share
    // each phase) and rank 0 alone speaks, with every rank's figures.
#ifdef GF_MPI
    const bool speaks = gf_mpi_app_rank() == 0;
#else
    const bool speaks = true;
#endif
    if (!cli.json && speaks) o.packed = gf_bench_on_packed;
    gf_bench_report r;
    o.stop = gf_cli_catch_stop();
    gf_status st = gf_bench(&cfg, &o, &r);
    if (st == GF_ERR_INTERRUPTED) return gf_cli_interrupted("bench", "no figures");
    if (st != GF_OK) return gf_cli_fail("bench", st);
    if (speaks) gf_bench_write(stdout, &r, cli.json);
    return GF_EXIT_OK;
}
