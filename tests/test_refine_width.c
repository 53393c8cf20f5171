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

// Same lines, r_s free, factors up to 2: dx x sqrt(2 / 1.3); the spot's Var
// at z = 8 with that slope is predicted as 10.7 + (2 - 1.3)(8 + 2.6) =
// 18.12, 3.12 above the DEM's 15 (beyond twice the combined 0.31), so r_s
// moves by
// -3.12 / (2 + 0.4 x 2.6) = -1.026 to 1.574. With factors up to 1.5 r_s stops
// at 2.6 / 1.5; with r_s fixed by the correlation it does not move.
static void slope_sets_step_level_sets_radius(void **state)
{
    (void)state;
    gf_dem_flowstats d, s;
    line(&d, 2.0, -1.0, 0.5);
    line(&s, 1.3, 0.3, 0.2);
    double dx = 0.5, rs = 2.6;
    gf_dem_refine_width(&d, &s, 0.10, true, 2.0, &dx, &rs);
    gf_assert_near(dx, 0.5 * sqrt(2.0 / 1.3), 1e-12);
    gf_assert_near(rs, 2.6 - 3.12 / 3.04, 1e-12);
    dx = 0.5, rs = 2.6;
    gf_dem_refine_width(&d, &s, 0.10, true, 1.5, &dx, &rs);
    gf_assert_near(rs, 2.6 / 1.5, 1e-12);
    dx = 0.5, rs = 2.6;
    gf_dem_refine_width(&d, &s, 0.10, false, 2.0, &dx, &rs);
    gf_assert_near(dx, 0.5 * sqrt(2.0 / 1.3), 1e-12);
    assert_true(rs == 2.6);
}

// Equal slopes and levels 0.5 apart with errors of 0.29 and 0.12 (0.31
// combined): not two standard errors, so r_s stays; dx too (the slopes agree).
static void noise_does_not_move_radius(void **state)
{
    (void)state;
    gf_dem_flowstats d, s;
    line(&d, 2.0, -1.0, 0.5);
    line(&s, 2.0, -0.5, 0.2);
    double dx = 0.5, rs = 2.6;
    gf_dem_refine_width(&d, &s, 0.10, true, 2.0, &dx, &rs);
    gf_assert_near(dx, 0.5, 1e-12);
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
    cmocka_unit_test(slope_sets_step_level_sets_radius),
    cmocka_unit_test(noise_does_not_move_radius),
    cmocka_unit_test(one_height_scales_step),
};

GF_TEST_MAIN("refine_width", tests)
