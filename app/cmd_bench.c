// SPDX-License-Identifier: MIT
// `granflow bench`: parses its options and runs gf_bench (granflow/bench.h):
// the spot engine on the papers' silo in steady flow, a silo ten times
// larger, and the lattice-gas automaton (--lga-only: just that).
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "granflow/bench.h"

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
    // fixed step, instead of the domain engine. --no-large: skip the silo ten
    // times larger.
    gf_bench_opts o = gf_bench_opts_default();
    char *args[256];
    int nargs = 0;
    for (int i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--lga-only")) o.lga_only = true;
        else if (!strcmp(argv[i], "--event")) o.event = true;
        else if (!strcmp(argv[i], "--spatial")) o.spatial = true;
        else if (!strcmp(argv[i], "--no-large")) o.large = false;
        else if (nargs < (int)(sizeof args / sizeof args[0])) args[nargs++] = argv[i];
    }
    gf_cli cli;
    if (!gf_cli_parse(nargs, args, "bench", &cli)) return GF_EXIT_USAGE;
    gf_config cfg;
    if (!gf_cli_config(&cli, NULL, &cfg)) return GF_EXIT_USAGE;
    if (cli.bench_particles > 0) o.particles = (size_t)cli.bench_particles;
    if (cli.bench_warmup > 0) o.warmup = cli.bench_warmup;
    if (cli.bench_window > 0) o.window = cli.bench_window;
    if (!cli.json) o.packed = gf_bench_on_packed;
    gf_bench_report r;
    o.stop = gf_cli_catch_stop();
    gf_status st = gf_bench(&cfg, &o, &r);
    if (st == GF_ERR_INTERRUPTED) return gf_cli_interrupted("bench", "no figures");
    if (st != GF_OK) return gf_cli_fail("bench", st);
    gf_bench_write(stdout, &r, cli.json);
    return GF_EXIT_OK;
}
