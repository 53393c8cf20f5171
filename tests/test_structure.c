// SPDX-License-Identifier: MIT
// g(r), bond angles g3 and packing badness (2009 paper Sec. 5): random points
// (g -> 1 with the walls' edge correction), a perfect FCC lattice (peaks at
// the lattice distances and angles), hand-built overlaps (exact badness).
#include "support.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "granflow/granflow.h"
#include "granflow/analysis.h"

#define PI 3.14159265358979323846

// xorshift-style uniform deviates in [0, 1), fixed seed: the test is repeatable.
static double uniform(uint64_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    return (double)(*s >> 11) * (1.0 / 9007199254740992.0);
}

static void gr_random_points_tend_to_one(void **state)
{
    (void)state;
    // Uniform points in a 12 x 4 x 12 box: the y walls (4 d apart) cut most
    // shells of radius up to 3, and the region reaches the x walls and the
    // base, so both the exact slab correction and the numerical one are used.
    const double W = 12, D = 4, H = 12, rmax = 3, dr = 0.05;
    const size_t N = 2500, F = 3;
    gf_series s = gf_test_series(F, W, D);
    uint64_t seed = 0x9e3779b97f4a7c15ULL;
    for (size_t k = 0; k < F; k++)
        for (size_t i = 0; i < N; i++)
            assert_int_equal(gf_packing_push(&s.frames[k].pk, (int64_t)i + 1, 1, W * (uniform(&seed) - 0.5),
                                             D * (uniform(&seed) - 0.5), H * uniform(&seed), 0.5),
                             GF_OK);
    gf_analysis_opts o = gf_analysis_opts_default();
    o.t0 = 0;
    o.t1 = (double)F;
    o.gr_x0 = -7; // the whole width
    o.gr_x1 = 7;
    o.gr_z0 = -1;       // from the base ...
    o.gr_z1 = H - rmax; // ... to where shells still stay below the points' top
    o.gr_rmax = rmax;
    o.gr_dr = dr;
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_gr(&s, &o, &out), GF_OK);
    const gf_table *g = gf_test_table(&out, "gr");
    size_t nbin = (size_t)(rmax / dr + 0.5);
    assert_int_equal(g->nrow, nbin);
    // Pair counts per bin, brute force, for the size of the errors.
    double *count = calloc(nbin, sizeof *count);
    assert_non_null(count);
    for (size_t k = 0; k < F; k++) {
        const gf_packing *p = &s.frames[k].pk;
        for (size_t i = 0; i < p->n; i++) {
            if (!(p->z[i] < o.gr_z1)) continue;
            for (size_t j = 0; j < p->n; j++) {
                double dx = p->x[j] - p->x[i], dy = p->y[j] - p->y[i], dz = p->z[j] - p->z[i];
                double d = sqrt(dx * dx + dy * dy + dz * dz);
                if (j != i && d < rmax) count[(size_t)(d / dr)] += 1.0;
            }
        }
    }
    // Errors: a bin's count C is Poisson-like, but a pair with both centres
    // in the region is counted from both ends, so Var(C) <= 2 C and the
    // relative error of g is sqrt(2 / C). The density is estimated per frame
    // from the region's count, Binomial(N, q) with q = 9/12 of the box, which
    // shifts every bin together by a relative sd sqrt((1 - q) / (q N F)).
    // Each bin with C >= 100 (Gaussian regime) must lie within 5 sd of 1.
    double q = o.gr_z1 / H, var_rho = (1 - q) / (q * (double)N * (double)F);
    size_t tested = 0;
    for (size_t k = 0; k < nbin; k++) {
        gf_assert_near(g->v[k * 2], (k + 0.5) * dr, 1e-12);
        if (count[k] < 100) continue;
        double sd = sqrt(2.0 / count[k] + var_rho);
        gf_assert_near(g->v[k * 2 + 1], 1.0, 5.0 * sd);
        tested++;
    }
    assert_true(tested > nbin * 3 / 4);
    // Without the correction g would fall to ~0.6 at r = 3 here (y walls 4 d
    // apart): the test above detects the missing or a wrong correction.
    free(count);
    gf_measure_free(&out);
    gf_series_free(&s);
}

// FCC lattice with nearest-neighbour distance 1 (cubic cell a = sqrt 2) filling
// a W x D container from z = 0.25 to z < H.
static void fcc_fill(gf_packing *p, double W, double D, double H)
{
    const double a = sqrt(2.0);
    const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
    int64_t id = 1;
    for (int i = -10; i <= 10; i++)
        for (int j = -10; j <= 10; j++)
            for (int k = 0; k <= 12; k++)
                for (int b = 0; b < 4; b++) {
                    double x = a * (i + basis[b][0]) + 0.1, y = a * (j + basis[b][1]) + 0.1;
                    double z = a * (k + basis[b][2]) + 0.25;
                    if (fabs(x) < 0.5 * W - 0.2 && fabs(y) < 0.5 * D - 0.2 && z < H)
                        assert_int_equal(gf_packing_push(p, id++, 1, x, y, z, 0.5), GF_OK);
                }
}

static void gr_and_g3_of_fcc_lattice(void **state)
{
    (void)state;
    const double W = 10, D = 7, H = 12, dr = 0.03, rcut = 1.2;
    gf_series s = gf_test_series(1, W, D);
    fcc_fill(&s.frames[0].pk, W, D, H);
    gf_analysis_opts o = gf_analysis_opts_default();
    o.gr_x0 = -2;
    o.gr_x1 = 2;
    o.gr_z0 = 3;
    o.gr_z1 = 7;
    o.gr_rmax = 2.5;
    o.gr_dr = dr;
    o.g3_rcut = rcut; // between the first (1) and second (sqrt 2) shells
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_gr(&s, &o, &out), GF_OK);

    // g(r): non-zero exactly in the bins holding the FCC distances sqrt(n),
    // n = 1..6 (none lies within 0.005 of a bin edge with dr = 0.03).
    const gf_table *g = gf_test_table(&out, "gr");
    bool lattice_bin[84] = {false};
    assert_int_equal(g->nrow, 84);
    for (int n = 1; n <= 6; n++) lattice_bin[(int)(sqrt((double)n) / dr)] = true;
    for (size_t k = 0; k < g->nrow; k++) {
        double v = g->v[k * 2 + 1];
        if (lattice_bin[k]) assert_true(v > 0.0);
        else assert_true(v == 0.0);
    }
    // The peaks at 1, sqrt 2, sqrt 3 and 2 are local maxima; the first is the highest.
    const double peaks[4] = {1.0, sqrt(2.0), sqrt(3.0), 2.0};
    for (int m = 0; m < 4; m++) {
        size_t k = (size_t)(peaks[m] / dr);
        assert_true(g->v[k * 2 + 1] > g->v[(k - 1) * 2 + 1] && g->v[k * 2 + 1] > g->v[(k + 1) * 2 + 1]);
    }
    gf_assert_near(gf_test_value(&out, "gr_first_peak_r"), 1.0, dr);

    // Reference by brute force: neighbours within rcut of each region centre
    // and the angles between them, sorted into 60, 90, 120 and 180 degrees.
    const gf_packing *p = &s.frames[0].pk;
    double centres = 0, bonds = 0, cls[4] = {0};
    for (size_t i = 0; i < p->n; i++) {
        if (!(p->x[i] > o.gr_x0 && p->x[i] < o.gr_x1 && p->z[i] > o.gr_z0 && p->z[i] < o.gr_z1)) continue;
        centres++;
        double v[12][3];
        int nv = 0;
        for (size_t j = 0; j < p->n; j++) {
            double d[3] = {p->x[j] - p->x[i], p->y[j] - p->y[i], p->z[j] - p->z[i]};
            if (j != i && d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < rcut * rcut) {
                assert_true(nv < 12);
                memcpy(v[nv++], d, sizeof d);
            }
        }
        bonds += nv;
        for (int a = 0; a < nv; a++)
            for (int b = a + 1; b < nv; b++) {
                double c = v[a][0] * v[b][0] + v[a][1] * v[b][1] + v[a][2] * v[b][2]; // |v| = 1
                int cl = c > 0.25 ? 0 : c > -0.25 ? 1 : c > -0.75 ? 2 : 3;
                gf_assert_near(c, cl == 0 ? 0.5 : cl == 1 ? 0.0 : cl == 2 ? -0.5 : -1.0, 1e-12);
                cls[cl]++;
            }
    }
    assert_true(centres > 50);
    gf_assert_near(gf_test_value(&out, "coordination"), bonds / centres, 1e-12);
    assert_true(bonds / centres > 10.0 && bonds / centres <= 12.0);

    // g3: a density per degree on 1-degree bins; exact angles 60, 90, 120 and
    // 180 land in the bin on either side of the edge (rounding), 180 in the last.
    const gf_table *g3 = gf_test_table(&out, "g3");
    assert_int_equal(g3->nrow, 180);
    double total = 0, at[4] = {0};
    for (size_t k = 0; k < 180; k++) {
        double v = g3->v[k * 2 + 1];
        gf_assert_near(g3->v[k * 2], k + 0.5, 1e-12);
        total += v;
        int cl = (k == 59 || k == 60) ? 0 : (k == 89 || k == 90) ? 1 : (k == 119 || k == 120) ? 2 : k == 179 ? 3 : -1;
        if (cl < 0) assert_true(v == 0.0);
        else at[cl] += v;
    }
    gf_assert_near(total, 1.0, 1e-12);
    double npairs = cls[0] + cls[1] + cls[2] + cls[3];
    for (int m = 0; m < 4; m++) gf_assert_near(at[m], cls[m] / npairs, 1e-12);
    // An interior FCC site has 24 : 12 : 24 : 6 of its 66 pairs at these
    // angles; wall sites only remove some, so 60 and 120 still dominate.
    assert_true(at[0] > at[1] && at[2] > at[1] && at[1] > at[3] && at[3] > 0.0);
    gf_measure_free(&out);
    gf_series_free(&s);
}

static void gr_rejects_bad_options(void **state)
{
    (void)state;
    gf_series s = gf_test_series(1, 10, 8);
    gf_analysis_opts o = gf_analysis_opts_default();
    o.gr_x0 = 20; // entirely outside the 10 d wide container
    o.gr_x1 = 30;
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_gr(&s, &o, &out), GF_ERR_PARAM);
    gf_measure_free(&out);
    o = gf_analysis_opts_default();
    o.gr_dr = 0;
    assert_int_equal(gf_measure_gr(&s, &o, &out), GF_ERR_PARAM);
    gf_measure_free(&out);
    gf_series_free(&s);
}

// Five spheres around (0, 0, 30): A-B overlap 0.1, A-C 0.05, A-E 0.05 (E has
// r = 0.6), A-D just touch (no overlap), B-C apart.
static void overlaps(gf_packing *p, double shift)
{
    assert_int_equal(gf_packing_push(p, 1, 1, 0, 0, 30, 0.5), GF_OK);            // A
    assert_int_equal(gf_packing_push(p, 2, 1, 0.9 - shift, 0, 30, 0.5), GF_OK);  // B
    assert_int_equal(gf_packing_push(p, 3, 1, 0, 0.95, 30, 0.5), GF_OK);         // C
    assert_int_equal(gf_packing_push(p, 4, 1, 0, 0, 31.25, 0.75), GF_OK);        // D
    assert_int_equal(gf_packing_push(p, 5, 1, 0, 0, 28.95, 0.6), GF_OK);         // E
}

static void badness_of_hand_built_overlaps(void **state)
{
    (void)state;
    gf_packing p = {0};
    overlaps(&p, 0.0);
    // Sum over i in the box of its overlaps squared, over p: a pair inside
    // the box counts from both sides (2009 paper Sec. 5: sum over i and its n_i).
    const double all_lo[3] = {-5, -5, 25}, all_hi[3] = {5, 5, 35};
    gf_assert_near(gf_badness(&p, all_lo, all_hi), (2 * 0.01 + 2 * 0.0025 + 2 * 0.0025) / 5, 1e-14);
    const double a_lo[3] = {-0.1, -0.1, 29.9}, a_hi[3] = {0.1, 0.1, 30.1};
    gf_assert_near(gf_badness(&p, a_lo, a_hi), 0.01 + 0.0025 + 0.0025, 1e-14); // A's partners lie outside
    const double b_lo[3] = {0.8, -0.1, 29.9}, b_hi[3] = {1.0, 0.1, 30.1};
    gf_assert_near(gf_badness(&p, b_lo, b_hi), 0.01, 1e-14);
    const double d_lo[3] = {-0.1, -0.1, 31}, d_hi[3] = {0.1, 0.1, 32};
    gf_assert_near(gf_badness(&p, d_lo, d_hi), 0.0, 1e-28); // touching is no overlap
    const double none_lo[3] = {3, 3, 3}, none_hi[3] = {4, 4, 4};
    assert_true(isnan(gf_badness(&p, none_lo, none_hi)));
    gf_packing_free(&p);
}

static void badness_measure_averages_the_window(void **state)
{
    (void)state;
    gf_series s = gf_test_series(3, 50, 8);
    const double shift[3] = {0.3, 0.0, 0.1}; // B's overlap with A: 0.4, 0.1, 0.2
    for (size_t k = 0; k < 3; k++) overlaps(&s.frames[k].pk, shift[k]);
    gf_analysis_opts o = gf_analysis_opts_default(); // region -15 < x < 15, 15 < z < 45: all five
    o.t0 = 0.5;                   // frames at t = 1 and 2
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_badness(&s, &o, &out), GF_OK);
    const gf_table *t = gf_test_table(&out, "badness");
    assert_int_equal(t->nrow, 2);
    assert_int_equal(t->ncol, 3);
    double b1 = (2 * 0.01 + 4 * 0.0025) / 5, b2 = (2 * 0.04 + 4 * 0.0025) / 5;
    gf_assert_near(t->v[0], 1.0, 0);
    gf_assert_near(t->v[1], b1, 1e-14);
    gf_assert_near(t->v[2], 5.0, 0);
    gf_assert_near(t->v[3], 2.0, 0);
    gf_assert_near(t->v[4], b2, 1e-14);
    gf_assert_near(gf_test_value(&out, "badness"), 0.5 * (b1 + b2), 1e-14);
    assert_non_null(out.gnuplot);
    assert_non_null(strstr(out.gnuplot, "badness.csv"));
    gf_measure_free(&out);
    gf_series_free(&s);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(gr_random_points_tend_to_one),
    cmocka_unit_test(gr_and_g3_of_fcc_lattice),
    cmocka_unit_test(gr_rejects_bad_options),
    cmocka_unit_test(badness_of_hand_built_overlaps),
    cmocka_unit_test(badness_measure_averages_the_window),
};

GF_TEST_MAIN("structure", tests)
