// SPDX-License-Identifier: MIT
// Two particle sizes: a generated packing with a second, smaller species
// (packing.radius2, packing.fraction2), and the engine on unequal radii:
// relax() and the walls separate pairs by r_i + r_j, so a packing of 0.5 and
// 0.75 spheres ends without overlaps, and the neighbour lists make room for
// the extra neighbours of the large ones.
#include "support.h"

#include <math.h>
#include <string.h>

#include "core/rng.h"
#include "granflow/granflow.h"
#include "spot/sim_internal.h"

// Smallest centre distance over r_i + r_j, over every pair (O(n^2)).
static double worst_gap(const gf_packing *p)
{
    double worst = INFINITY;
    for (size_t i = 0; i < p->n; i++)
        for (size_t j = i + 1; j < p->n; j++) {
            double dx = p->x[i] - p->x[j], dy = p->y[i] - p->y[j], dz = p->z[i] - p->z[j];
            worst = fmin(worst, sqrt(dx * dx + dy * dy + dz * dz) / (p->r[i] + p->r[j]));
        }
    return worst;
}

// 30% of 1500 get radius 0.3: their number within 5 sigma of the binomial
// mean, and the centres exactly those of the monodisperse packing.
static void generated_second_species(void **state)
{
    (void)state;
    gf_config c = gf_test_silo_config(10, 1500, 7), m = c;
    c.packing_fraction2 = 0.3;
    c.packing_radius2 = 0.3;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    gf_packing a = {0}, b = {0};
    assert_int_equal(gf_packing_generate(&c, NULL, &a), GF_OK);
    assert_int_equal(gf_packing_generate(&m, NULL, &b), GF_OK);
    size_t small = 0;
    for (size_t i = 0; i < a.n; i++) {
        assert_true(a.r[i] == 0.5 || a.r[i] == 0.3);
        small += a.r[i] == 0.3;
    }
    double mean = 0.3 * 1500, sd = sqrt(1500 * 0.3 * 0.7);
    assert_true(fabs((double)small - mean) < 5.0 * sd);
    assert_int_equal(a.n, b.n);
    assert_memory_equal(a.z, b.z, sizeof(double) * a.n);
    assert_true(worst_gap(&a) >= 0.99);
    gf_packing_free(&a);
    gf_packing_free(&b);
    // A larger second species is refused with a clear message.
    assert_int_equal(gf_config_set(&c, "packing.radius2=0.75", "--set"), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "packing.radius2"));
}

// A generated packing spread out 1.5 times (centres >= 1.485 apart), a
// random 30% of it given radius 0.75: pairs of large ones overlap by up to
// 1%. Global relaxations remove the overlaps; 2 tau of spot moves and local
// relaxations after that keep every pair >= 0.98 (r_i + r_j) apart and every
// sphere inside the walls.
static void two_sizes_relax_without_overlap(void **state)
{
    (void)state;
    gf_config g = gf_test_silo_config(10, 1200, 9);
    gf_packing pk = {0};
    assert_int_equal(gf_packing_generate(&g, NULL, &pk), GF_OK);
    gf_rng rng;
    gf_rng_seed(&rng, 11, 0);
    size_t big = 0;
    for (size_t i = 0; i < pk.n; i++) {
        pk.x[i] *= 1.5;
        pk.y[i] *= 1.5;
        pk.z[i] *= 1.5;
        if (gf_rng_uniform(&rng) < 0.3) {
            pk.r[i] = 0.75;
            big++;
        }
    }
    assert_true(big > 250);
    assert_true(worst_gap(&pk) < 0.999); // some large pairs do overlap
    gf_config c = gf_test_silo_config(15, 1200, 9);
    c.container_depth = 12;
    c.orifice_diameter = 9;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    gf_sim *sim = NULL;
    assert_int_equal(gf_sim_create(&c, &pk, &sim), GF_OK);
    assert_int_equal(1u << sim->nl_shift, 32); // radius ratio 1.5: rows of 32 slots
    for (int k = 0; k < 12; k++) assert_int_equal(gf_relax_global(sim), GF_OK);
    gf_packing out = {0};
    assert_int_equal(gf_sim_particles(sim, &out), GF_OK);
    assert_true(worst_gap(&out) >= 0.999);
    assert_int_equal(gf_sim_run(sim, 2.0, NULL), GF_OK);
    assert_true(gf_sim_get_stats(sim).relax_calls > 10000);
    assert_int_equal(gf_sim_particles(sim, &out), GF_OK);
    assert_true(worst_gap(&out) >= 0.98);
    for (size_t i = 0; i < out.n; i++)
        assert_true(gf_container_contains(&sim->box, out.x[i], out.y[i], out.z[i], out.r[i], 0.02));
    gf_packing_free(&out);
    gf_packing_free(&pk);
    gf_sim_destroy(sim);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(generated_second_species),
    cmocka_unit_test(two_sizes_relax_without_overlap),
};

GF_TEST_MAIN("bidisperse", tests)
