// SPDX-License-Identifier: MIT
// Embedding granflow: drain a small silo through the public API only, set by
// key name, and print its outflow. Builds against the installed library:
//   cmake -S examples/embed -B build-embed -DCMAKE_PREFIX_PATH=PREFIX   (find_package)
//   cc embed.c $(pkg-config --cflags --libs granflow)                    (pkg-config)
#include <granflow/granflow.h>

#include <stdio.h>
#include <stdlib.h>

static void print_warning(void *ctx, const char *message)
{
    (void)ctx;
    fprintf(stderr, "embed: granflow warning: %s\n", message);
}

static int fail(const char *what, gf_status st)
{
    fprintf(stderr, "embed: %s: %s: %s\n", what, gf_status_str(st), gf_last_error());
    return 1;
}

int main(void)
{
    gf_set_warning_fn(print_warning, NULL);
    gf_config *cfg = gf_config_create();
    if (!cfg) return fail("gf_config_create", GF_ERR_NOMEM);
    // A silo 12 d wide, 6 d deep, 1,500 particles, orifice 5 d.
    const char *keys[][2] = {{"container.width", "12"},   {"container.depth", "6"},
                             {"container.orifice_diameter", "5"}, {"packing.particles", "1500"},
                             {"run.seed", "11"}};
    for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++) {
        gf_status st = gf_config_set_key(cfg, keys[i][0], keys[i][1]);
        if (st != GF_OK) return fail(keys[i][0], st);
    }
    char radius[64];
    gf_config_get_key(cfg, "spot.radius", radius, sizeof radius);
    gf_sim *sim = NULL;
    gf_status st = gf_sim_create_from_config(cfg, NULL, &sim);
    gf_config_destroy(cfg);
    if (st != GF_OK) return fail("gf_sim_create_from_config", st);
    printf("granflow %s, spot.radius = %s d, %zu particles\n", gf_version(), radius, gf_sim_particle_count(sim));
    printf("time_tau,exited\n");
    for (int k = 1; k <= 5; k++) {
        if ((st = gf_sim_run(sim, k, NULL)) != GF_OK) return fail("gf_sim_run", st);
        printf("%d,%zu\n", k, gf_sim_exit_count(sim));
    }
    size_t left = gf_sim_particle_count(sim), gone = gf_sim_exit_count(sim);
    gf_sim_destroy(sim);
    if (gone == 0 || left + gone != 1500) {
        fprintf(stderr, "embed: %zu left + %zu exited != 1500 (or nothing drained)\n", left, gone);
        return 1;
    }
    printf("ok: %zu exited, %zu left\n", gone, left);
    return 0;
}
