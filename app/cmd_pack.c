// SPDX-License-Identifier: MIT
// `granflow pack`: build (or import and re-tag) the initial packing, write it.
#include <stdio.h>
#include <time.h>

#include "cli.h"
#include "granflow/defs.h"

int gf_cmd_pack(int argc, char **argv)
{
    gf_cli cli;
    int rc = gf_cli_parse(argc, argv, "pack", &cli);
    if (rc != GF_CLI_GO) return rc;
    if (!cli.out) {
        fprintf(stderr, "granflow pack: error: -o FILE is required (.dump, .xyz or .csv)\n");
        return GF_EXIT_USAGE;
    }
    gf_config cfg;
    if (!gf_cli_config(&cli, NULL, &cfg)) return GF_EXIT_USAGE;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    gf_packing pk = {0};
    gf_packing_defs pd;
    gf_config_packing_defs(&cfg, &pd);
    if (!cli.quiet && !pd.file[0] && pd.fill_height > 0.0)
        fprintf(stderr, "granflow pack: filling to z = %g...\n", pd.fill_height);
    else if (!cli.quiet && !pd.file[0])
        fprintf(stderr, "granflow pack: building %lld particles...\n", (long long)pd.particles);
    gf_packing_import_report rep;
    gf_status st = gf_packing_for_config(&cfg, &(gf_packing_opts){.stop = gf_cli_catch_stop()}, &pk, &rep);
    if (st == GF_OK && !cli.quiet && (rep.below_base || rep.other_types))
        fprintf(stderr, "granflow pack: kept %zu of %zu particles (%zu below the base, %zu of other atom types)\n",
                pk.n, rep.read, rep.below_base, rep.other_types);
    if (st == GF_OK) st = gf_packing_check(&pk, &cfg);
    if (st == GF_OK) st = gf_packing_write(&pk, cli.out, GF_FORMAT_AUTO, &cfg);
    if (st != GF_OK) {
        gf_packing_free(&pk);
        return gf_cli_fail("pack", st);
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    double top = 0;
    for (size_t i = 0; i < pk.n; i++)
        if (pk.z[i] > top) top = pk.z[i];
    double phi = gf_packing_bulk_fraction(&pk, &cfg); // away from walls and surfaces
    if (!cli.quiet)
        fprintf(stderr, "granflow pack: %zu particles, top at z = %.2f, bulk packing fraction %.4f, "
                        "min distance %.4f, %.1f s -> %s\n",
                pk.n, top, phi, gf_packing_min_distance(&pk),
                (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec), cli.out);
    gf_packing_free(&pk);
    return GF_EXIT_OK;
}
