// SPDX-License-Identifier: MIT
// The refinement's width update (src/dem/refine.c, gf_dem_refine_width):
// lines Var(z) = slope z + intercept fitted to the DEM's and the spot's
// profile variances, step_xy from the slopes, r_s from the levels. Numbers
// worked out by hand in the comments; milliseconds.
#include "support.h"

#include <math.h>
#include <string.h>

#include "dem/dem_internal.h"

/// Var = a z + c at z = 6, 8, 10 with standard error e at each height.
static void line(gf_dem_flowstats *f, double a, double c, double e)
{
    memset(f, 0, sizeof *f);
    f->nz = 3;
    for (size_t k = 0; k < 3; k++) {
        f->z[k] = 6.0 + 2.0 * (double)k;
        f->var[k] = (gf_dem_value){a * f->z[k] + c, e};
    }
}

// DEM Var = 2 z - 1 (+- 0.5), spot Var = 1.3 z + 0.3 (+- 0.2): three
// equally weighted heights, mean z 8 (levels 15 and 10.7 there), sum of
// (z - 8)^2 = 8, so the slope's error is e / sqrt(8), the level's e / sqrt(3).
static void fits_both_lines(void **state)
{
    (void)state;
    gf_dem_flowstats d, s;
    line(&d, 2.0, -1.0, 0.5);
    line(&s, 1.3, 0.3, 0.2);
    gf_dem_var_lines l;
    gf_dem_var_lines_fit(&d, &s, 0.10, &l);
    assert_int_equal(l.n, 3);
    gf_assert_near(l.zm, 8.0, 1e-12);
    gf_assert_near(l.slope[0].value, 2.0, 1e-12);
    gf_assert_near(l.level[0].value, 15.0, 1e-12);
    gf_assert_near(l.slope[1].value, 1.3, 1e-12);
    gf_assert_near(l.level[1].value, 10.7, 1e-12);
    gf_assert_near(l.slope[0].err, 0.5 / sqrt(8.0), 1e-12);
    gf_assert_near(l.slope[1].err, 0.2 / sqrt(8.0), 1e-12);
    gf_assert_near(l.level[0].err, 0.5 / sqrt(3.0), 1e-12);
    gf_assert_near(l.level[1].err, 0.2 / sqrt(3.0), 1e-12);
}

/// The step's one factor for DEM Var = 2 z - 1 (+- 0.5) at z = 6, 8, 10 and
/// spot Var = v6 + g (z - 6): the geometric mean of Var_DEM / Var_spot
/// weighted by (Var_DEM / 0.5)^2.
static double one_factor(double v6, double g)
{
    double num = 0.0, den = 0.0;
    for (int k = 0; k < 3; k++) {
        double a = 11.0 + 4.0 * k, b = v6 + 2.0 * g * k, w = (a / 0.5) * (a / 0.5);
        num += w * log(a / b);
        den += w;
    }
    return exp(num / den);
}

// DEM Var = 2 z - 1, spot Var = 1.3 z + 0.3: one factor, the geometric mean
// of 11 / 8.1, 15 / 10.7, 19 / 13.3 weighted by (Var_DEM / 0.5)^2, brings
// all three within 10% (11.3, 15.0, 18.7): only dx moves, by its root.
static void one_factor_moves_step_only(void **state)
{
    (void)state;
    gf_dem_flowstats d, s;
    line(&d, 2.0, -1.0, 0.5);
    line(&s, 1.3, 0.3, 0.2);
    double dx = 0.5, rs = 2.6;
    gf_dem_refine_width(&d, &s, 0.10, true, 2.0, &dx, &rs);
    gf_assert_near(dx, 0.5 * sqrt(one_factor(8.1, 1.3)), 1e-12);
    assert_true(rs == 2.6);
}

// DEM Var = 2 z - 1 (11, 15, 19), spot Var = z + 4 (10, 12, 14): no single
// factor fits (the ratios run 1.10 to 1.36), so the lines: dx x sqrt(2 / 1)
// (factors up to 2: the slope ratio up to 4); the spot's Var at z = 8 is
// then predicted as 2 x 12 = 24, 9 above the DEM's 15 (far beyond twice
// the combined 0.31), so r_s would move by -9 / (2 + 0.4 x 2.6) to -0.36:
// it stops at its limit 2.6 / 2 = 1.3, with factors up to 3 at the smallest
// spot, 1 d. With r_s fixed by the correlation only dx moves, by the one
// factor (the slope alone would leave every Var 24-60% too wide).
static void slope_sets_step_level_sets_radius(void **state)
{
    (void)state;
    gf_dem_flowstats d, s;
    line(&d, 2.0, -1.0, 0.5);
    line(&s, 1.0, 4.0, 0.2);
    double dx = 0.5, rs = 2.6;
    gf_dem_refine_width(&d, &s, 0.10, true, 2.0, &dx, &rs);
    gf_assert_near(dx, 0.5 * sqrt(2.0), 1e-12);
    gf_assert_near(rs, 1.3, 1e-12);
    dx = 0.5, rs = 2.6;
    gf_dem_refine_width(&d, &s, 0.10, true, 3.0, &dx, &rs);
    gf_assert_near(dx, 0.5 * sqrt(2.0), 1e-12);
    gf_assert_near(rs, 1.0, 1e-12);
    dx = 0.5, rs = 2.6;
    gf_dem_refine_width(&d, &s, 0.10, false, 2.0, &dx, &rs);
    gf_assert_near(dx, 0.5 * sqrt(one_factor(10.0, 1.0)), 1e-12);
    assert_true(rs == 2.6);
}

// One height measured to 10% (the others at 50%): no line; dx follows
// Var_DEM / Var_spot there (15 / 10 at z = 8) and r_s stays.
static void one_height_scales_step(void **state)
{
    (void)state;
    gf_dem_flowstats d, s;
    line(&d, 2.0, -1.0, 0.5);
    d.var[0].err = 0.5 * d.var[0].value;
    d.var[2].err = 0.5 * d.var[2].value;
    line(&s, 1.25, 0.0, 0.2);
    gf_dem_var_lines l;
    gf_dem_var_lines_fit(&d, &s, 0.10, &l);
    assert_int_equal(l.n, 1);
    double dx = 0.5, rs = 2.6;
    gf_dem_refine_width(&d, &s, 0.10, true, 2.0, &dx, &rs);
    gf_assert_near(dx, 0.5 * sqrt(15.0 / 10.0), 1e-12);
    assert_true(rs == 2.6);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(fits_both_lines),
    cmocka_unit_test(one_factor_moves_step_only),
    cmocka_unit_test(slope_sets_step_level_sets_radius),
    cmocka_unit_test(one_height_scales_step),
};

GF_TEST_MAIN("refine_width", tests)
