// SPDX-License-Identifier: MIT
// The LGA's update rules (paper Sec. 2) one by one: the collision table's
// conservation laws, hand-worked single-site cases of collision, gravity g
// and h, friction k, wall roughness b and both propagation steps on tiny
// lattices, and the statistics of the p and q draws.
#include "support.h"
#include "lga_support.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "granflow/granflow.h"
#include "lga/step.h"

#define B(e) ((uint16_t)(1u << (e)))

// Default parameters with p, q, g, h, k, b set as given.
static gf_config params(double p, double q, double g, double h, double k, double b)
{
    gf_config c = gf_config_default();
    c.lga_p = p;
    c.lga_q = q;
    c.lga_g = g;
    c.lga_h = h;
    c.lga_k = k;
    c.lga_b = b;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    return c;
}

static gf_lga *empty_lattice(const gf_config *c, int w, int h, bool periodic)
{
    gf_lga *l = NULL;
    assert_int_equal(gf_lga_create_empty(c, w, h, periodic, &l), GF_OK);
    return l;
}

// ---- the table ---------------------------------------------------------------

// Every state the table offers has the particle count, set and energy cap of
// its key; where a state of that count and energy carries the target momentum
// exactly, every offered state does. Exhaustive over all keys.
// Issue 16: the limit the message states ("at most 100000000 sites") is the
// one applied, to the lattice's own sites (the halo was counted before, so a
// lattice of exactly the maximum was refused).
static void lattice_limit_is_the_stated_one(void **state)
{
    (void)state;
    assert_true(gf_lga_lattice_fits(10000, 10000));
    assert_true(gf_lga_lattice_fits(1, 100000000));
    assert_false(gf_lga_lattice_fits(10000, 10001));
    assert_false(gf_lga_lattice_fits(100000, 100000));
}

static void table_candidates_are_consistent(void **state)
{
    (void)state;
    gf_lga_table *t = NULL;
    assert_int_equal(gf_lga_table_create(&t), GF_OK);
    // the least energy of a state of each (set, count, momentum), and of each (set, count)
    static int emin_exact[2][14][GF_LGA_NA * GF_LGA_NB];
    int emin[2][14];
    for (int set = 0; set < 2; set++)
        for (int m = 0; m < 14; m++) {
            emin[set][m] = 99;
            for (int k = 0; k < GF_LGA_NA * GF_LGA_NB; k++) emin_exact[set][m][k] = 99;
        }
    for (int s = 0; s < GF_LGA_STATES; s++)
        for (int set = 0; set < 2; set++) {
            if (set == GF_LGA_SET_MOVING && (s & 1)) continue;
            int m = t->count[s], key = gf_lga_table_key(t->ma[s], t->mb[s]);
            if (t->energy[s] < emin[set][m]) emin[set][m] = t->energy[s];
            if (t->energy[s] < emin_exact[set][m][key]) emin_exact[set][m][key] = t->energy[s];
        }
    for (int set = 0; set < 2; set++)
        for (int m = 0; m <= (set ? 12 : 13); m++)
            for (int a = -GF_LGA_AMAX; a <= GF_LGA_AMAX; a++)
                for (int b = -GF_LGA_BMAX; b <= GF_LGA_BMAX; b++)
                    for (int cap = 0; cap <= GF_LGA_EMAX; cap++) {
                        int key = gf_lga_table_key(a, b);
                        size_t len = t->len[set][m][key][cap], start = t->start[set][m][key][cap];
                        assert_true(len > 0);
                        int eff = cap > emin[set][m] ? cap : emin[set][m];
                        bool exact_possible = emin_exact[set][m][key] <= eff;
                        for (size_t k = 0; k < len; k++) {
                            uint16_t s = t->list[start + k];
                            assert_int_equal(t->count[s], m);
                            if (set == GF_LGA_SET_MOVING) assert_false(s & GF_LGA_REST);
                            assert_true(t->energy[s] <= eff);
                            if (exact_possible) {
                                assert_int_equal(t->ma[s], a);
                                assert_int_equal(t->mb[s], b);
                            }
                        }
                    }
    gf_lga_table_destroy(t);
}

// Mass: for every one of the 8192 states, whatever p, q, k, g and the random
// draws, the particles out (velocity bits + stacked at rest) equal those in.
static void collision_conserves_mass(void **state)
{
    (void)state;
    const double sets[4][4] = {{0.2, 0.2, 0.05, 0.2}, {1, 1, 1, 1}, {0.9, 0.5, 0.5, 1}, {0, 0, 0, 0}};
    for (int ps = 0; ps < 4; ps++) {
        gf_config c = params(sets[ps][0], sets[ps][1], sets[ps][3], 0.05, sets[ps][2], 0.05);
        gf_lga *l = empty_lattice(&c, 4, 4, false);
        for (int s = 1; s < GF_LGA_STATES; s++)
            for (int rep = 0; rep < 3; rep++) {
                int ex = -1;
                uint16_t out = gf_lga_collide_state(l, (uint16_t)s, rep != 1, &ex);
                assert_int_equal(out & ~GF_LGA_PARTICLES, 0); // one particle per velocity, no flags
                assert_true(ex >= 0);
                assert_int_equal(__builtin_popcount(out) + ex, __builtin_popcount((unsigned)s));
                if (ex > 0) assert_true(out & GF_LGA_REST); // a stack only on a resting particle
            }
        gf_lga_destroy(l);
    }
}

// Momentum and energy: with p = q = 0 (and no gravity g or friction k, which
// add momentum by design) every collision is elastic, for all 8192 states.
static void collision_elastic_without_p_q(void **state)
{
    (void)state;
    gf_config c = params(0, 0, 0.7, 0.05, 0, 0.05); // g on, but the sites are supported (gravity = false)
    gf_lga *l = empty_lattice(&c, 4, 4, false);
    const gf_lga_table *t = l->table;
    int changed = 0;
    for (int s = 1; s < GF_LGA_STATES; s++)
        for (int rep = 0; rep < 4; rep++) {
            int ex = -1;
            uint16_t out = gf_lga_collide_state(l, (uint16_t)s, false, &ex);
            assert_int_equal(ex, 0);
            assert_int_equal(t->count[out], t->count[s]);
            assert_int_equal(t->ma[out], t->ma[s]);
            assert_int_equal(t->mb[out], t->mb[s]);
            assert_int_equal(t->energy[out], t->energy[s]);
            changed += out != s;
        }
    assert_true(changed > 1000); // the collisions do scatter (not the identity)
    gf_lga_destroy(l);
}

// Head-on pair v1 + v4 (p = q = g = k = 0): the FHP rotation, each of the
// three zero-momentum pairs {v1,v4}, {v2,v5}, {v3,v6} with probability 1/3.
// 3000 draws: binomial sd sqrt(3000/3 * 2/3) = 25.8; 5 sd = 130.
static void head_on_pair_rotates(void **state)
{
    (void)state;
    gf_config c = params(0, 0, 0, 0.05, 0, 0);
    gf_lga *l = empty_lattice(&c, 4, 4, false);
    int hits[3] = {0, 0, 0};
    for (int k = 0; k < 3000; k++) {
        int ex;
        uint16_t out = gf_lga_collide_state(l, B(1) | B(4), false, &ex);
        if (out == (B(1) | B(4))) hits[0]++;
        else if (out == (B(2) | B(5))) hits[1]++;
        else if (out == (B(3) | B(6))) hits[2]++;
        else fail_msg("head-on pair became 0x%x", out);
    }
    for (int k = 0; k < 3; k++) gf_assert_near(hits[k], 1000, 130);
    gf_lga_destroy(l);
}

// p: the number of particles stopped is n with probability p^n (1 - p),
// capped at the moving ones. Three movers, p = 0.5, q = 0: P(n) = 1/2, 1/4,
// 1/8, 1/8 for n = 0..3; 20000 draws: sd <= sqrt(0.25/20000) = 0.0035, 5 sd = 0.018.
// A stopped particle sits at v0 (the first) or in the stack (the others).
static void p_stops_geometric_numbers(void **state)
{
    (void)state;
    gf_config c = params(0.5, 0, 0, 0.05, 0, 0.05);
    gf_lga *l = empty_lattice(&c, 4, 4, false);
    const int N = 20000;
    int count[4] = {0, 0, 0, 0};
    for (int k = 0; k < N; k++) {
        int ex;
        uint16_t out = gf_lga_collide_state(l, B(1) | B(3) | B(5), false, &ex); // sum zero: any n is possible
        int n = (out & GF_LGA_REST) ? 1 + ex : 0;
        assert_true(n <= 3);
        count[n]++;
    }
    const double want[4] = {0.5, 0.25, 0.125, 0.125};
    for (int n = 0; n < 4; n++) gf_assert_near((double)count[n] / N, want[n], 0.018);
    gf_lga_destroy(l);
}

// q: l particles are sent off in random nearest-neighbour directions with
// probability q^l (1 - q). Two particles v1 + v4 with p = 0, q = 0.5: l = 0
// (probability 1/2) keeps zero momentum. l = 1 (1/4): the other keeps its
// velocity, the randomised one takes one of the 5 free unit velocities, and
// the sum is zero only for the one opposite (1/5). l = 2 (1/4): two distinct
// random unit velocities, opposite with probability 1/5. So P(non-zero) =
// (1/4 + 1/4) * 4/5 = 0.4; 20000 draws: sd 0.0035, 5 sd = 0.018.
static void q_randomises_geometric_numbers(void **state)
{
    (void)state;
    gf_config c = params(0, 0.5, 0, 0.05, 0, 0.05);
    gf_lga *l = empty_lattice(&c, 4, 4, false);
    const gf_lga_table *t = l->table;
    const int N = 20000;
    int nonzero = 0;
    for (int k = 0; k < N; k++) {
        int ex;
        uint16_t out = gf_lga_collide_state(l, B(1) | B(4), false, &ex);
        assert_int_equal(t->count[out] + ex, 2);
        if (t->ma[out] != 0 || t->mb[out] != 0) nonzero++;
    }
    gf_assert_near((double)nonzero / N, 0.4, 0.018);
    gf_lga_destroy(l);
}

// ---- single particles: gravity g, friction k -----------------------------------

// Hand-worked single-particle steps with g = 1 (gravity always applied to an
// unsupported site): v4 is added to the momentum, and up to 2 units of energy.
static void gravity_on_single_particles(void **state)
{
    (void)state;
    gf_config c = params(0.2, 0.2, 1, 0.05, 0.05, 0.05);
    gf_lga *l = empty_lattice(&c, 4, 4, false);
    struct {
        uint16_t in, out;
    } cases[] = {
        {GF_LGA_REST, B(4)}, // at rest, nothing below: starts to fall (v0 + v4 = v4)
        {B(1), GF_LGA_REST}, // thrown up: stops at the top (v1 + v4 = 0)
        {B(7), B(2)},        // 120 degrees, speed sqrt 3: (-1, 3) + (0, -2) = (-1, 1) = v2
        {B(2), B(3)},        // (-1, 1) + (0, -2) = (-1, -1) = v3
        {B(3), B(9)},        // (-1, -1) + (0, -2) = (-1, -3) = v9: falls faster (energy 1 -> 3)
        {B(9), B(9)},        // (-1, -5) cannot be reached: v9 is nearest (terminal velocity)
        {B(4), B(4)},        // (0, -4): v4, v9, v10 equally near; v4 points the same way
        {B(8), B(3)},        // (-2, -2): v3, v8, v9 equally near; v3 points the same way (210 degrees)
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++)
        for (int rep = 0; rep < 20; rep++) {
            int ex;
            uint16_t out = gf_lga_collide_state(l, cases[k].in, true, &ex);
            if (out != cases[k].out) fail_msg("case %zu: 0x%x -> 0x%x, expected 0x%x", k, cases[k].in, out, cases[k].out);
            assert_int_equal(ex, 0);
        }
    // Without gravity (supported) a lone particle keeps its velocity.
    for (int e = 0; e < 13; e++) {
        int ex;
        assert_int_equal(gf_lga_collide_state(l, B(e), false, &ex), B(e));
    }
    gf_lga_destroy(l);
}

// Friction k: with probability k the outgoing momentum becomes that of
// min(m, 6) distinct horizontal-ish velocities (v2 v3 v5 v6 v8 v11), whose
// vertical components are +-1/2 or 0. Three particles flying up, v1 + v7 +
// v12 (momentum (0, 4), energy 7; p = q = g = 0): without friction they keep
// their momentum; with k = 1 the vertical momentum drops to at most 1.5
// (|b| <= 3 half units); with k = 0.5 half of the collisions keep it
// (2000 draws: sd sqrt(2000/4) = 22.4, 5 sd = 112).
static void friction_makes_momentum_horizontal(void **state)
{
    (void)state;
    const uint16_t up = B(1) | B(7) | B(12);
    for (int run = 0; run < 3; run++) {
        double k = run == 0 ? 0 : run == 1 ? 1 : 0.5;
        gf_config c = params(0, 0, 0, 0.05, k, 0.05);
        gf_lga *l = empty_lattice(&c, 4, 4, false);
        const gf_lga_table *t = l->table;
        assert_int_equal(t->mb[up], 8);
        int kept = 0;
        for (int n = 0; n < 2000; n++) {
            int ex;
            uint16_t out = gf_lga_collide_state(l, up, false, &ex);
            assert_int_equal(t->count[out] + ex, 3);
            assert_true(t->energy[out] <= 7); // no energy from nowhere
            if (t->mb[out] == 8) kept++;
            else assert_true(abs(t->mb[out]) <= 3);
        }
        if (run == 0) assert_int_equal(kept, 2000);
        if (run == 1) assert_int_equal(kept, 0);
        if (run == 2) gf_assert_near(kept, 1000, 112);
        gf_lga_destroy(l);
    }
}

// ---- the lattice steps on tiny lattices ------------------------------------------

// Second propagation: a single particle with velocity e moves to the
// neighbour in direction e, keeping e, from an even and from an odd column;
// the neighbour positions are those of Fig. 1 (unit or sqrt 3 away).
static void streaming_moves_to_the_neighbour(void **state)
{
    (void)state;
    gf_config c = params(0.2, 0.2, 0.2, 0.05, 0.05, 0.05);
    gf_lga *l = empty_lattice(&c, 9, 9, false);
    const double step[13] = {0, 1, 1, 1, 1, 1, 1, 1.7320508075688772, 1.7320508075688772, 1.7320508075688772,
                             1.7320508075688772, 1.7320508075688772, 1.7320508075688772};
    for (int i0 = 4; i0 <= 5; i0++)
        for (int e = 1; e < 13; e++) {
            assert_int_equal(gf_lga_set_site(l, i0, 4, B(e)), GF_OK);
            gf_lga_stream(l);
            int found = 0;
            for (int j = 0; j < 9; j++)
                for (int i = 0; i < 9; i++) {
                    uint16_t s = gf_lga_site(l, i, j);
                    if (!(s & GF_LGA_SITE_PARTICLES)) continue;
                    found++;
                    assert_int_equal(s, B(e));
                    double x0, y0, x1, y1;
                    gf_lga_site_position(i0, 4, &x0, &y0);
                    gf_lga_site_position(i, j, &x1, &y1);
                    gf_assert_near(x1 - x0, 0.8660254037844386 * gf_lga_da[e], 1e-12);
                    gf_assert_near(y1 - y0, 0.5 * gf_lga_db[e], 1e-12);
                    gf_assert_near(hypot(x1 - x0, y1 - y0), step[e], 1e-12);
                    assert_int_equal(gf_lga_set_site(l, i, j, 0), GF_OK);
                }
            assert_int_equal(found, 1);
        }
    gf_lga_destroy(l);
}

// Walls reflect: at a vertical wall column the horizontal velocity component
// flips (v6 -> v2, v11 -> v8), on the floor the vertical one (v4 -> v1,
// v5 -> v6); nothing is lost, and with b = 1 the particle stops at the wall.
static void walls_reflect_and_roughness_stops(void **state)
{
    (void)state;
    gf_config c = params(0, 0, 0, 0, 0, 0);
    gf_lga *l = empty_lattice(&c, 12, 12, false);
    for (int j = 0; j < 12; j++) assert_int_equal(gf_lga_set_site(l, 11, j, GF_LGA_SITE_WALL), GF_OK);
    for (int i = 0; i < 11; i++) assert_int_equal(gf_lga_set_site(l, i, 0, GF_LGA_SITE_WALL), GF_OK);
    struct {
        int i, j;
        int in, out;
    } cases[] = {
        {10, 6, 6, 2},   // up-right into the right wall: up-left
        {10, 6, 5, 3},   // down-right: down-left
        {10, 6, 11, 8},  // right (speed sqrt 3): left
        {9, 6, 11, 8},   // two columns away, a sqrt 3 move still hits it
        {5, 1, 4, 1},    // down into the floor: up
        {4, 1, 5, 6},    // down-right into the floor (even column): up-right
        {4, 1, 10, 12},  // 300 degrees into the floor: 60 degrees
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        assert_int_equal(gf_lga_set_site(l, cases[k].i, cases[k].j, B(cases[k].in)), GF_OK);
        gf_lga_stream(l);
        uint16_t s = gf_lga_site(l, cases[k].i, cases[k].j);
        if (s != B(cases[k].out)) fail_msg("case %zu: v%d at (%d, %d) came back as 0x%x, expected v%d", k, cases[k].in,
                                           cases[k].i, cases[k].j, s, cases[k].out);
        assert_int_equal(recount(l), 1);
        assert_int_equal(gf_lga_set_site(l, cases[k].i, cases[k].j, 0), GF_OK);
    }
    gf_lga_destroy(l);

    // b = 1: a particle about to hit the wall stops there (at rest, on its site).
    c = params(0, 0, 0, 0, 0, 1);
    l = empty_lattice(&c, 12, 12, false);
    for (int j = 0; j < 12; j++) assert_int_equal(gf_lga_set_site(l, 11, j, GF_LGA_SITE_WALL), GF_OK);
    assert_int_equal(gf_lga_set_site(l, 10, 6, B(6)), GF_OK);
    assert_int_equal(gf_lga_set_site(l, 10, 5, GF_LGA_REST), GF_OK); // support, so no gravity question
    gf_lga_collide(l);
    assert_int_equal(gf_lga_site(l, 10, 6), GF_LGA_REST);
    gf_lga_destroy(l);
}

// Gravity h (first propagation): with h = 1 a resting particle in the air
// moves to one of the empty sites v3 v4 v5 v9 v10 below it, each with
// probability 1/5 (4000 trials: sd sqrt(4000 * 0.2 * 0.8) = 25.3, 5 sd = 126),
// and never anywhere else.
static void gravity_h_drops_resting_particles(void **state)
{
    (void)state;
    gf_config c = params(0.2, 0.2, 0, 1, 0.05, 0.05);
    gf_lga *l = empty_lattice(&c, 9, 9, false);
    const int dirs[5] = {3, 4, 5, 9, 10};
    int hits[5] = {0};
    for (int k = 0; k < 4000; k++) {
        int i0 = 4 + (k & 1); // both column parities
        assert_int_equal(gf_lga_set_site(l, i0, 5, GF_LGA_REST), GF_OK);
        gf_lga_settle(l);
        assert_int_equal(gf_lga_site(l, i0, 5), 0);
        int found = 0;
        for (int d = 0; d < 5; d++) {
            size_t t = gf_lga_neighbour(l, i0, 5, dirs[d]);
            if (l->state[t] & GF_LGA_REST) {
                hits[d]++;
                found++;
                l->state[t] = 0;
            }
        }
        assert_int_equal(found, 1);
        assert_int_equal(recount(l), 0);
        gf_lga_stream(l); // clears the scratch marks
    }
    for (int d = 0; d < 5; d++) gf_assert_near(hits[d], 800, 126);
    gf_lga_destroy(l);
}

// First propagation, the surplus: a site holding a resting particle and one
// more stopped there (excess 1) passes it to the nearest free site, the
// emptiest and then the lowest: here the empty site straight below (v4).
// With the six neighbours full it goes to the second ring, never stays.
static void surplus_goes_to_the_nearest_lowest_free_site(void **state)
{
    (void)state;
    gf_config c = params(0.2, 0.2, 0.2, 0.05, 0.05, 0.05);
    gf_lga *l = empty_lattice(&c, 9, 9, false);
    for (int rep = 0; rep < 10; rep++) {
        assert_int_equal(gf_lga_set_site(l, 4, 5, GF_LGA_REST), GF_OK);
        size_t idx = gf_lga_index(l, 4, 5);
        gf_lga_add_excess(l, idx, 1);
        gf_lga_scatter(l);
        assert_int_equal(l->excess[idx], 0);
        assert_int_equal(gf_lga_site(l, 4, 4), GF_LGA_REST); // straight below
        assert_int_equal(recount(l), 2);
        assert_int_equal(gf_lga_set_site(l, 4, 4, 0), GF_OK);
        assert_int_equal(gf_lga_set_site(l, 4, 5, 0), GF_OK);
    }
    // Neighbours all at rest: the second ring's lowest site takes it.
    assert_int_equal(gf_lga_set_site(l, 4, 5, GF_LGA_REST), GF_OK);
    for (int e = 1; e <= 6; e++) l->state[gf_lga_neighbour(l, 4, 5, e)] |= GF_LGA_REST;
    gf_lga_add_excess(l, gf_lga_index(l, 4, 5), 1);
    gf_lga_scatter(l);
    assert_int_equal(recount(l), 8);
    size_t two_below = gf_lga_neighbour(l, 4, 4, 4);
    assert_true(l->state[two_below] & GF_LGA_REST);
    gf_lga_destroy(l);
}

// Rolling: a resting particle on a resting one, with its lower-right
// neighbour (v5) empty and the lower-left (v3) full, starts to roll that way
// with g = 1; with both lower neighbours full it stays (the 30 degree slope holds).
static void resting_particle_rolls_off_an_edge(void **state)
{
    (void)state;
    gf_config c = params(0.2, 0.2, 1, 0, 0.05, 0.05);
    gf_lga *l = empty_lattice(&c, 9, 9, false);
    // a bed of resting particles, rows 0-3 (each held by the one below, or the
    // floor, and by both lower neighbours), with (5, 3) taken out; on top of
    // it (4, 4): below it (4, 3), lower-left (3, 3), lower-right (5, 3)
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 9; i++) assert_int_equal(gf_lga_set_site(l, i, j, GF_LGA_REST), GF_OK);
    assert_int_equal(gf_lga_set_site(l, 5, 3, 0), GF_OK);
    assert_int_equal(gf_lga_set_site(l, 4, 4, GF_LGA_REST), GF_OK);
    gf_lga_collide(l);
    assert_int_equal(gf_lga_site(l, 4, 4), B(5));
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 9; i++)
            if (i != 5 || j != 3) assert_int_equal(gf_lga_site(l, i, j), GF_LGA_REST);
    // Both sides held: nothing moves.
    assert_int_equal(gf_lga_set_site(l, 4, 4, GF_LGA_REST), GF_OK);
    assert_int_equal(gf_lga_set_site(l, 5, 3, GF_LGA_REST), GF_OK);
    gf_lga_collide(l);
    assert_int_equal(gf_lga_site(l, 4, 4), GF_LGA_REST);
    gf_lga_destroy(l);
}

// One whole iteration of one particle, worked by hand: a particle at rest in
// the air with g = 1, h = 0 falls (v4) and moves one site down; a second
// iteration keeps v4 (terminal) and moves it again; on reaching the floor it
// bounces back up (v1).
static void single_particle_falls_and_bounces(void **state)
{
    (void)state;
    gf_config c = params(0, 0, 1, 0, 0, 0);
    gf_lga *l = empty_lattice(&c, 5, 6, false);
    for (int i = 0; i < 5; i++) assert_int_equal(gf_lga_set_site(l, i, 0, GF_LGA_SITE_WALL), GF_OK);
    assert_int_equal(gf_lga_set_site(l, 2, 3, GF_LGA_REST), GF_OK);
    gf_lga_step(l);
    assert_int_equal(gf_lga_site(l, 2, 2), B(4));
    gf_lga_step(l);
    // at (2, 2) the site below (2, 1) is empty: gravity again, v4 stays v4; it streams to (2, 1)
    assert_int_equal(gf_lga_site(l, 2, 1), B(4));
    gf_lga_step(l);
    // at (2, 1) the floor is below: no gravity; streaming reflects it off the floor
    assert_int_equal(gf_lga_site(l, 2, 1), B(1));
    assert_int_equal(gf_lga_get_stats(l).particles, 1);
    gf_lga_destroy(l);
}

// Periodic rows: a particle leaving the top row comes back at the bottom.
static void periodic_rows_wrap(void **state)
{
    (void)state;
    gf_config c = params(0, 0, 0, 0, 0, 0);
    gf_lga *l = empty_lattice(&c, 6, 8, true);
    assert_int_equal(gf_lga_set_site(l, 2, 7, B(1)), GF_OK);
    gf_lga_stream(l);
    assert_int_equal(gf_lga_site(l, 2, 0), B(1));
    assert_int_equal(gf_lga_set_site(l, 2, 0, B(12)), GF_OK); // 60 degrees: (3, 1) then (4, 3)...
    for (int k = 0; k < 8; k++) gf_lga_stream(l);
    assert_int_equal(recount(l), 1);
    gf_lga_destroy(l);
}

// The API refuses what cannot be.
static void api_errors(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    gf_lga *l = NULL;
    c.lga_outlet_width = 200;
    assert_int_equal(gf_lga_create(&c, &l), GF_ERR_PARAM);
    assert_null(l);
    assert_non_null(strstr(gf_last_error(), "outlet_width"));
    c = gf_config_default();
    c.lga_scenario = GF_LGA_CHANNEL;
    c.lga_width = 4;
    c.lga_height = 10;
    c.lga_particles = 1000; // more than 12 per site
    assert_int_equal(gf_lga_create(&c, &l), GF_ERR_PARAM);
    c = gf_config_default();
    c.lga_p = 2; // out of range: the config check catches it
    assert_int_equal(gf_lga_create(&c, &l), GF_ERR_PARAM);
    c = gf_config_default();
    l = empty_lattice(&c, 5, 5, false);
    assert_int_equal(gf_lga_set_site(l, 5, 0, GF_LGA_REST), GF_ERR_PARAM);
    assert_int_equal(gf_lga_set_site(l, 0, 0, GF_LGA_SITE_WALL | GF_LGA_REST), GF_ERR_PARAM);
    assert_int_equal(gf_lga_site(l, -1, 0), 0);
    gf_lga_destroy(l);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(lattice_limit_is_the_stated_one),
    cmocka_unit_test(table_candidates_are_consistent),
    cmocka_unit_test(collision_conserves_mass),
    cmocka_unit_test(collision_elastic_without_p_q),
    cmocka_unit_test(head_on_pair_rotates),
    cmocka_unit_test(p_stops_geometric_numbers),
    cmocka_unit_test(q_randomises_geometric_numbers),
    cmocka_unit_test(gravity_on_single_particles),
    cmocka_unit_test(friction_makes_momentum_horizontal),
    cmocka_unit_test(streaming_moves_to_the_neighbour),
    cmocka_unit_test(walls_reflect_and_roughness_stops),
    cmocka_unit_test(gravity_h_drops_resting_particles),
    cmocka_unit_test(surplus_goes_to_the_nearest_lowest_free_site),
    cmocka_unit_test(resting_particle_rolls_off_an_edge),
    cmocka_unit_test(single_particle_falls_and_bounces),
    cmocka_unit_test(periodic_rows_wrap),
    cmocka_unit_test(api_errors),
};

GF_TEST_MAIN("lga", tests)
