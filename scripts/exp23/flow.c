// SPDX-License-Identifier: MIT
// Issue 23 experiment: the outflow of the sweep engine against the serial
// engines, free of the run directory (scripts/exp23/run.sh builds and runs it).
// A 20 x 8 silo of 4000 spheres with the papers' spots, 6 tau of flow, then
// 6 tau measured: particles out per tau and the spots' and relaxations'
// summed z displacements per move.
// usage: flow ENGINE SEED [WINDOW]   ENGINE: event, fixed, domains, sweepN (N sweeps)
//        WIDTH=40 NPART=8000: a silo twice as wide (the same orifice), twice the spheres
//        NORELAX=1 in the environment: relax.method = none
//        GLOBALK=k: relax.method = global, relax.k = k (the whole packing every k/mu, Sec. 5)
//        ALPHA=a: relax.alpha = a
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "granflow/granflow.h"

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: flow event|fixed|domains|sweepN SEED [WINDOW]\n");
        return 2;
    }
    const char *engine = argv[1];
    gf_config c = gf_config_default();
    c.container_width = getenv("WIDTH") ? atof(getenv("WIDTH")) : 20; // (a wider silo: the same orifice, fewer moves per volume)
    c.packing_particles = getenv("NPART") ? atoll(getenv("NPART")) : 4000;
    c.run_seed = (uint64_t)atoll(argv[2]);
    c.run_threads = 1;
    if (strcmp(engine, "event") == 0) {
        c.run_mode = GF_MODE_EVENT;
    } else if (strcmp(engine, "fixed") == 0) {
        c.run_mode = GF_MODE_FIXED;
    } else if (strcmp(engine, "domains") == 0) {
        c.run_mode = GF_MODE_FIXED;
        c.run_order = GF_ORDER_DOMAINS;
    } else if (strncmp(engine, "sweep", 5) == 0) {
        c.run_mode = GF_MODE_FIXED;
        c.run_order = GF_ORDER_SWEEP;
        c.parallel_sweeps = atoi(engine + 5);
        c.parallel_window = argc > 3 ? atof(argv[3]) : 1.0 / 28.0;
    } else {
        fprintf(stderr, "flow: unknown engine %s\n", engine);
        return 2;
    }
    if (getenv("NORELAX")) c.relax_method = GF_RELAX_NONE;
    if (getenv("ALPHA")) c.relax_alpha = atof(getenv("ALPHA"));
    if (getenv("GLOBALK")) {
        c.relax_method = GF_RELAX_GLOBAL;
        c.relax_k = atof(getenv("GLOBALK"));
    }
    gf_packing pk = {0};
    gf_sim *sim = NULL;
    if (gf_config_validate(&c) != GF_OK || gf_packing_generate(&c, NULL, &pk) != GF_OK ||
        gf_sim_create(&c, &pk, &sim) != GF_OK || gf_sim_run(sim, 6.0, NULL) != GF_OK) {
        fprintf(stderr, "flow: %s\n", gf_last_error());
        return 1;
    }
    gf_sim_stats a = gf_sim_get_stats(sim);
    if (gf_sim_run(sim, 12.0, NULL) != GF_OK) {
        fprintf(stderr, "flow: %s\n", gf_last_error());
        return 1;
    }
    gf_sim_stats z = gf_sim_get_stats(sim);
    double mv = (double)(z.spot_moves - a.spot_moves);
    printf("%s %s %s moves_per_tau %.0f spot_dz_per_move %.6f relax_dz_per_move %.6f out_per_tau %.2f\n", engine,
           argv[2], argc > 3 ? argv[3] : "-", mv / 6.0, (z.spot_dz - a.spot_dz) / mv, (z.relax_dz - a.relax_dz) / mv,
           (double)(z.particles_exited - a.particles_exited) / 6.0);
    gf_sim_destroy(sim);
    gf_packing_free(&pk);
    return 0;
}
