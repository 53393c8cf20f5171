// SPDX-License-Identifier: MIT
// spot() and relax() on hand-built configurations whose results were worked
// out by hand (SPEC 1.3): pairs, a particle at a wall, inside and shell.
#include "support.h"

#include <math.h>
#include <string.h>

#include "granflow/granflow.h"
#include "spot/sim_internal.h"

// A config for a 20 x 8 box with the papers' spot parameters.
static gf_config small_box(void)
{
    gf_config c = gf_config_default();
    c.container_width = 20;
    c.container_depth = 8;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    return c;
}

// Particles with ids 1..n at pos[], of radius r[i] (0.5 when r is NULL).
static gf_sim *make_sim_radii(const gf_config *cfg, const double (*pos)[3], const double *r, size_t n)
{
    gf_config c = *cfg;
    gf_packing pk = {0};
    for (size_t i = 0; i < n; i++)
        assert_int_equal(gf_packing_push(&pk, (int64_t)i + 1, 1, pos[i][0], pos[i][1], pos[i][2], r ? r[i] : 0.5),
                         GF_OK);
    gf_sim *sim = NULL;
    assert_int_equal(gf_sim_create(&c, &pk, &sim), GF_OK);
    gf_packing_free(&pk);
    return sim;
}

static gf_sim *make_sim_cfg(const gf_config *cfg, const double (*pos)[3], size_t n)
{
    return make_sim_radii(cfg, pos, NULL, n);
}

static gf_sim *make_sim(const double (*pos)[3], size_t n)
{
    gf_config c = small_box();
    return make_sim_cfg(&c, pos, n);
}

// Position of the particle with id (index order changes when lists are built).
static const gf_pos *by_id(const gf_sim *sim, int64_t id)
{
    for (size_t i = 0; i < sim->n; i++)
        if (sim->id[i] == id) return &sim->p[i];
    fail_msg("no particle with id %lld", (long long)id);
    return NULL;
}

static void spot_moves_exactly_the_ball(void **state)
{
    (void)state;
    // Centre (0,0,10), r_s = 2.6: ids 1-3 inside the ball, 4-5 outside it.
    const double pos[][3] = {{0, 0, 10}, {2.5, 0, 10}, {0, 1.5, 11.5}, {2.7, 0, 10}, {0, 0, 12.61}};
    gf_sim *sim = make_sim(pos, 5);
    const double c[3] = {0, 0, 10}, u[3] = {1e-3, -2e-3, -2.5e-4};
    long moved = gf_spot_apply(sim, &sim->w0, c, u);
    gf_spot_unmark(sim, &sim->w0);
    assert_int_equal(moved, 3);
    for (int id = 1; id <= 5; id++) {
        const gf_pos *q = by_id(sim, id);
        double k = id <= 3 ? 1.0 : 0.0;
        gf_assert_near(q->x, pos[id - 1][0] + k * u[0], 1e-15);
        gf_assert_near(q->y, pos[id - 1][1] + k * u[1], 1e-15);
        gf_assert_near(q->z, pos[id - 1][2] + k * u[2], 1e-15);
    }
    gf_sim_destroy(sim);
}

static void relax_pair_both_inside(void **state)
{
    (void)state;
    // Two spheres 0.9 apart, both inside r_e = 3.6: overlap 0.1, each moves
    // apart by alpha * 0.1 / 2 = 0.04 along x.
    const double pos[][3] = {{-0.45, 0, 10}, {0.45, 0, 10}};
    gf_sim *sim = make_sim(pos, 2);
    const double c[3] = {0, 0, 10};
    assert_int_equal(gf_relax_at(sim, &sim->w0, c), GF_OK);
    gf_assert_near(by_id(sim, 1)->x, -0.49, 1e-12);
    gf_assert_near(by_id(sim, 2)->x, 0.49, 1e-12);
    gf_assert_near(by_id(sim, 1)->z, 10.0, 1e-15);
    gf_sim_destroy(sim);
}

static void relax_unequal_radii(void **state)
{
    (void)state;
    // Radii 0.7 and 0.5 with centres 1.0 apart: contact 1.2, overlap 0.2, both
    // inside r_e, so each moves alpha * 0.2 / 2 = 0.08 apart. A third sphere
    // of radius 0.5 sits 1.05 beyond the second, within its neighbour list
    // but not in contact (1.0), so it stays; it would not if the contact
    // distance were taken from one radius for all.
    gf_config cfg = small_box();
    const double pos[][3] = {{-0.5, 0, 10}, {0.5, 0, 10}, {1.55, 0, 10}}, r[] = {0.7, 0.5, 0.5};
    gf_sim *sim = make_sim_radii(&cfg, pos, r, 3);
    const double c[3] = {0, 0, 10};
    assert_int_equal(gf_relax_at(sim, &sim->w0, c), GF_OK);
    gf_assert_near(by_id(sim, 1)->x, -0.58, 1e-12);
    gf_assert_near(by_id(sim, 2)->x, 0.58, 1e-12);
    gf_assert_near(by_id(sim, 3)->x, 1.55, 0.0);
    gf_sim_destroy(sim);
}

static void relax_coincident_centres_do_not_push(void **state)
{
    (void)state;
    // Two centres at the same point have no direction to push along: relax()
    // leaves them (and produces no NaN); a third sphere 0.9 away pushes both.
    const double pos[][3] = {{0, 0, 10}, {0, 0, 10}, {0.9, 0, 10}};
    gf_sim *sim = make_sim(pos, 3);
    const double c[3] = {0, 0, 10};
    assert_int_equal(gf_relax_at(sim, &sim->w0, c), GF_OK);
    // Each of ids 1 and 2 is pushed by id 3 alone: alpha * 0.1 / 2 = 0.04.
    gf_assert_near(by_id(sim, 1)->x, -0.04, 1e-12);
    gf_assert_near(by_id(sim, 2)->x, -0.04, 1e-12);
    gf_assert_near(by_id(sim, 3)->x, 0.98, 1e-12);
    gf_sim_destroy(sim);
}

static void relax_pair_inside_and_shell(void **state)
{
    (void)state;
    // A at 3.4 from c (inside r_e = 3.6), B at 4.2 (shell r_e < r < r_e + 1):
    // overlap 0.2, only A moves, by alpha * 0.2 = 0.16 towards c.
    const double pos[][3] = {{3.4, 0, 10}, {4.2, 0, 10}};
    gf_sim *sim = make_sim(pos, 2);
    const double c[3] = {0, 0, 10};
    assert_int_equal(gf_relax_at(sim, &sim->w0, c), GF_OK);
    gf_assert_near(by_id(sim, 1)->x, 3.4 - 0.16, 1e-12);
    gf_assert_near(by_id(sim, 2)->x, 4.2, 0.0);
    gf_sim_destroy(sim);
}

static void relax_ignores_pairs_outside(void **state)
{
    (void)state;
    // Both members in the shell: neither moves, though they overlap by 0.3.
    const double pos[][3] = {{3.7, 0, 10}, {4.4, 0, 10}};
    gf_sim *sim = make_sim(pos, 2);
    const double c[3] = {0, 0, 10};
    assert_int_equal(gf_relax_at(sim, &sim->w0, c), GF_OK);
    gf_assert_near(by_id(sim, 1)->x, 3.7, 0.0);
    gf_assert_near(by_id(sim, 2)->x, 4.4, 0.0);
    gf_sim_destroy(sim);
}

static void relax_wall_and_base(void **state)
{
    (void)state;
    // Wall x = -10: a centre 0.3 from it moves away by alpha (0.5 - 0.3) = 0.16.
    // Wall y = 4 at the same time: gap 0.4 -> -0.08 in y. Base (outside the
    // hole, x = -9.7): z = 0.45 -> +0.04.
    const double pos[][3] = {{-9.7, 3.6, 0.45}};
    gf_sim *sim = make_sim(pos, 1);
    const double c[3] = {-8, 2, 1};
    assert_int_equal(gf_relax_at(sim, &sim->w0, c), GF_OK);
    gf_assert_near(by_id(sim, 1)->x, -9.7 + 0.16, 1e-12);
    gf_assert_near(by_id(sim, 1)->y, 3.6 - 0.08, 1e-12);
    gf_assert_near(by_id(sim, 1)->z, 0.45 + 0.04, 1e-12);
    gf_sim_destroy(sim);
}

static void relax_orifice_rim(void **state)
{
    (void)state;
    // Over the hole (radius 4), centre at rho = 3.8, z = 0.2: the rim point is
    // (4, 0, 0), at distance sqrt(0.2^2 + 0.2^2) = 0.28284; the sphere moves
    // away from it by alpha (0.5 - 0.28284) along (-0.2, 0, 0.2) / 0.28284.
    const double pos[][3] = {{3.8, 0, 0.2}};
    gf_sim *sim = make_sim(pos, 1);
    const double c[3] = {2, 0, 1};
    assert_int_equal(gf_relax_at(sim, &sim->w0, c), GF_OK);
    double d = sqrt(0.08), push = 0.8 * (0.5 - d) / d;
    gf_assert_near(by_id(sim, 1)->x, 3.8 - push * 0.2, 1e-12);
    gf_assert_near(by_id(sim, 1)->z, 0.2 + push * 0.2, 1e-12);
    gf_sim_destroy(sim);
}

static void relax_displacements_applied_together(void **state)
{
    (void)state;
    // A chain 1 - 2 - 3 on the x axis, gaps 0.9 and 0.8, all inside. From the
    // original positions: 1 moves -0.04, 3 moves +0.08, and 2 gets +0.04 from
    // pair (1,2) and -0.08 from pair (2,3): net -0.04.
    const double pos[][3] = {{-0.9, 0, 10}, {0, 0, 10}, {0.8, 0, 10}};
    gf_sim *sim = make_sim(pos, 3);
    const double c[3] = {0, 0, 10};
    assert_int_equal(gf_relax_at(sim, &sim->w0, c), GF_OK);
    gf_assert_near(by_id(sim, 1)->x, -0.94, 1e-12);
    gf_assert_near(by_id(sim, 2)->x, -0.04, 1e-12);
    gf_assert_near(by_id(sim, 3)->x, 0.88, 1e-12);
    gf_sim_destroy(sim);
}

static void spot_exit_through_orifice(void **state)
{
    (void)state;
    // A particle just above the exit over the hole leaves when pushed below
    // z = 0; one over the plate at the same height stays (the plate holds it).
    const double pos[][3] = {{0, 0, 0.0001}, {6, 0, 0.5}};
    gf_sim *sim = make_sim(pos, 2);
    const double c[3] = {0, 0, 0}, u[3] = {0, 0, -0.001};
    assert_int_equal(gf_spot_apply(sim, &sim->w0, c, u), 1);
    gf_spot_unmark(sim, &sim->w0);
    gf_sim_stats s = gf_sim_get_stats(sim);
    assert_int_equal(s.particles_exited, 1);
    assert_int_equal(s.particles_remaining, 1);
    size_t n;
    const gf_exit *e = gf_sim_exits(sim, &n);
    assert_int_equal(n, 1);
    assert_int_equal(e[0].id, 1);
    gf_sim_destroy(sim);
}

static void create_rejects_particle_outside(void **state)
{
    (void)state;
    gf_config c = small_box();
    gf_packing pk = {0};
    assert_int_equal(gf_packing_push(&pk, 7, 1, 10.5, 0, 5, 0.5), GF_OK);
    gf_sim *sim = NULL;
    assert_int_equal(gf_sim_create(&c, &pk, &sim), GF_ERR_PARAM);
    assert_null(sim);
    assert_non_null(strstr(gf_last_error(), "id 7"));
    gf_packing_free(&pk);
}

// Sec. 3 influence weighting: a ball of 3 particles above z_min moves them by
// u * p_bulk / max(3, 20) = u * 81.7 / 20; below z_min by u.
static void weighting_scales_by_population(void **state)
{
    (void)state;
    gf_config c = small_box();
    c.spot_weighting = 1;
    c.spot_weighting_zmin = 30;
    const double pos[][3] = {{0, 0, 40}, {1, 0, 40}, {0, 1, 40}, {0, 0, 10}, {1, 0, 10}};
    gf_sim *sim = make_sim_cfg(&c, pos, 5);
    const double hi[3] = {0, 0, 40}, lo[3] = {0, 0, 10}, u[3] = {1e-3, -2e-3, -2.5e-4};
    assert_int_equal(gf_spot_apply(sim, &sim->w0, hi, u), 3);
    gf_spot_unmark(sim, &sim->w0);
    assert_int_equal(gf_spot_apply(sim, &sim->w0, lo, u), 2);
    gf_spot_unmark(sim, &sim->w0);
    const double f = 81.7 / 20.0;
    for (int id = 1; id <= 5; id++) {
        const gf_pos *q = by_id(sim, id);
        double k = id <= 3 ? f : 1.0;
        gf_assert_near(q->x, pos[id - 1][0] + k * u[0], 1e-15);
        gf_assert_near(q->z, pos[id - 1][2] + k * u[2], 1e-15);
    }
    gf_sim_destroy(sim);
}

// Sec. 4 reflection: spot at y = 3 beside the wall y = 4 (mirror at y = 5),
// r_s = 2.6. A particle at y = 3.5 is within r_s of both: S = 2. One at
// y = 1 is 4 from the mirror: S = 1. One at y = 0.3, x = 0 is 2.7 from the
// spot: S = 0 (outside the ball, whatever the mirror).
static void reflection_doubles_the_wall_side(void **state)
{
    (void)state;
    gf_config c = small_box();
    c.spot_walls = GF_WALLS_REFLECT;
    const double pos[][3] = {{0, 3.4, 20}, {0, 1, 20}, {0, 0.3, 20}, {2.0, 3.4, 21}};
    gf_sim *sim = make_sim_cfg(&c, pos, 4);
    const double ctr[3] = {0, 3, 20}, u[3] = {0, 0, -1e-3};
    assert_int_equal(gf_spot_apply(sim, &sim->w0, ctr, u), 3);
    gf_spot_unmark(sim, &sim->w0);
    // id 4: |(2, 0.4, 1)| = 2.27 < r_s from the spot, |(2, -1.6, 1)| = 2.75 > r_s from the mirror: S = 1.
    const double S[4] = {2, 1, 0, 1};
    for (int id = 1; id <= 4; id++) gf_assert_near(by_id(sim, id)->z, pos[id - 1][2] + S[id - 1] * u[2], 1e-15);
    gf_sim_destroy(sim);
}

// Sec. 5 method 3: the whole packing relaxed at once. Two pairs far apart,
// each overlapping by 0.1 along one axis, both move apart by alpha 0.1 / 2.
static void global_relaxation_pushes_every_pair(void **state)
{
    (void)state;
    const double pos[][3] = {{-5, 0, 10}, {-4.1, 0, 10}, {5, 0, 30}, {5, 0, 30.9}, {0, 0, 50}};
    gf_sim *sim = make_sim(pos, 5);
    assert_int_equal(gf_relax_global(sim), GF_OK);
    const double h = 0.5 * 0.8 * 0.1;
    gf_assert_near(by_id(sim, 1)->x, -5 - h, 1e-12);
    gf_assert_near(by_id(sim, 2)->x, -4.1 + h, 1e-12);
    gf_assert_near(by_id(sim, 3)->z, 30 - h, 1e-12);
    gf_assert_near(by_id(sim, 4)->z, 30.9 + h, 1e-12);
    gf_assert_near(by_id(sim, 5)->z, 50, 0);
    assert_int_equal(gf_sim_get_stats(sim).global_relaxations, 1);
    gf_sim_destroy(sim);
}

// Sec. 5 method 2: a spot relaxes on every k-th of its own moves.
static void counter_method_relaxes_every_kth_move(void **state)
{
    (void)state;
    gf_config c = small_box();
    c.relax_method = GF_RELAX_COUNTER;
    c.relax_k = 4;
    // A 10 x 8 x 4 block of touching particles: every column under the walk is full.
    double pos[320][3];
    for (int i = 0; i < 320; i++) pos[i][0] = -4.5 + (i % 10), pos[i][1] = -3.5 + (i / 10 % 8), pos[i][2] = 10 + i / 80;
    gf_sim *sim = make_sim_cfg(&c, (const double (*)[3])pos, 320);
    double s[3] = {0, 0, 10};
    uint32_t count = 0;
    for (int k = 1; k <= 12; k++) {
        bool deleted;
        long ball;
        assert_int_equal(gf_spot_step(sim, &sim->w0, s, &count, &deleted, &ball), GF_OK);
        assert_false(deleted);
        assert_int_equal(gf_sim_get_stats(sim).relax_calls, (uint64_t)(k / 4));
    }
    gf_sim_destroy(sim);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(spot_moves_exactly_the_ball),
    cmocka_unit_test(relax_pair_both_inside),
    cmocka_unit_test(relax_unequal_radii),
    cmocka_unit_test(relax_coincident_centres_do_not_push),
    cmocka_unit_test(relax_pair_inside_and_shell),
    cmocka_unit_test(relax_ignores_pairs_outside),
    cmocka_unit_test(relax_wall_and_base),
    cmocka_unit_test(relax_orifice_rim),
    cmocka_unit_test(relax_displacements_applied_together),
    cmocka_unit_test(spot_exit_through_orifice),
    cmocka_unit_test(create_rejects_particle_outside),
    cmocka_unit_test(weighting_scales_by_population),
    cmocka_unit_test(reflection_doubles_the_wall_side),
    cmocka_unit_test(global_relaxation_pushes_every_pair),
    cmocka_unit_test(counter_method_relaxes_every_kth_move),
};

GF_TEST_MAIN("mechanism", tests)
