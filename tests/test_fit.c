// SPDX-License-Identifier: MIT
// The calibration fits (thesis Sec. 3.3): Gaussian velocity profiles and the
// exponential decay of velocity correlations, on exact and noisy synthetic data.
#include "support.h"

#include <math.h>
#include <string.h>

#include "core/rng.h"
#include "granflow/analysis.h"

static double normal(gf_rng *r)
{
    // Box-Muller: one standard normal deviate.
    return sqrt(-2.0 * log(gf_rng_uniform_pos(r))) * cos(6.283185307179586 * gf_rng_uniform(r));
}

/// Standard deviations of least-squares parameters for noise sd `sigma`:
/// sqrt(diag(sigma^2 (J^T J)^-1)), J the model's Jacobian at the true
/// parameters (m = 2 or 3). This is the Cramer-Rao / linearised error of the fit.
static void fisher_sd(const double (*jac)[3], size_t n, size_t m, double sigma, double *sd)
{
    double a[3][3] = {{0}};
    for (size_t i = 0; i < n; i++)
        for (size_t r = 0; r < m; r++)
            for (size_t c = 0; c < m; c++) a[r][c] += jac[i][r] * jac[i][c];
    // Inverse by cofactors (m = 3) or directly (m = 2).
    double inv_diag[3];
    if (m == 2) {
        double det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
        inv_diag[0] = a[1][1] / det;
        inv_diag[1] = a[0][0] / det;
    } else {
        double c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
        double c11 = a[0][0] * a[2][2] - a[0][2] * a[2][0];
        double c22 = a[0][0] * a[1][1] - a[0][1] * a[1][0];
        double det = a[0][0] * c00 - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                     a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
        inv_diag[0] = c00 / det;
        inv_diag[1] = c11 / det;
        inv_diag[2] = c22 / det;
    }
    for (size_t r = 0; r < m; r++) sd[r] = sigma * sqrt(inv_diag[r]);
}

#define NPT 51

// x = -25 .. 25 step 1 (the 50 d silo in 1 d bins), y = A exp(-(x-mu)^2/(2 var)).
static void gauss_data(double amp, double mu, double var, double *x, double *y, double (*jac)[3])
{
    for (size_t i = 0; i < NPT; i++) {
        x[i] = -25.0 + (double)i;
        double u = x[i] - mu, e = exp(-u * u / (2.0 * var));
        y[i] = amp * e;
        if (jac) {
            jac[i][0] = e;
            jac[i][1] = amp * e * u / var;
            jac[i][2] = amp * e * u * u / (2.0 * var * var);
        }
    }
}

static void gaussian_exact(void **state)
{
    (void)state;
    // Narrow, wide (truncated by the range: moments start far off) and off-centre.
    const double cases[][3] = {{2.5, 0.7, 30.0}, {0.3, -1.2, 400.0}, {1.0, 9.0, 4.0}, {5.0, 0.0, 1.6}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        double x[NPT], y[NPT], amp, mu, var;
        gauss_data(cases[k][0], cases[k][1], cases[k][2], x, y, NULL);
        assert_int_equal(gf_fit_gaussian(x, y, NPT, &amp, &mu, &var), GF_OK);
        gf_assert_near(amp, cases[k][0], 1e-8 * cases[k][0]);
        gf_assert_near(mu, cases[k][1], 1e-8 * sqrt(cases[k][2]));
        gf_assert_near(var, cases[k][2], 1e-8 * cases[k][2]);
    }
}

static void gaussian_noisy(void **state)
{
    (void)state;
    // Noise of 2% of the amplitude on 51 points. The least-squares estimates are
    // unbiased to first order with sd from the Fisher matrix; each of 20 seeded
    // profiles must land within 5 sd (a 5-sd miss has probability 6e-7).
    const double amp0 = 1.0, mu0 = 0.5, var0 = 60.0, sigma = 0.02;
    double x[NPT], y[NPT], jac[NPT][3], sd[3];
    gauss_data(amp0, mu0, var0, x, y, jac);
    fisher_sd((const double(*)[3])jac, NPT, 3, sigma, sd);
    gf_rng rng;
    gf_rng_seed(&rng, 12345, 1);
    double mean_var = 0.0;
    for (int rep = 0; rep < 20; rep++) {
        double yn[NPT], amp, mu, var;
        for (size_t i = 0; i < NPT; i++) yn[i] = y[i] + sigma * normal(&rng);
        assert_int_equal(gf_fit_gaussian(x, yn, NPT, &amp, &mu, &var), GF_OK);
        gf_assert_near(amp, amp0, 5.0 * sd[0]);
        gf_assert_near(mu, mu0, 5.0 * sd[1]);
        gf_assert_near(var, var0, 5.0 * sd[2]);
        mean_var += var / 20.0;
    }
    // The mean of 20 has sd sd/sqrt(20): a biased fit would show here.
    gf_assert_near(mean_var, var0, 5.0 * sd[2] / sqrt(20.0));
}

static void gaussian_rejects_bad_data(void **state)
{
    (void)state;
    double x[NPT], y[NPT], amp, mu, var;
    gauss_data(1.0, 0.0, 10.0, x, y, NULL);
    assert_int_equal(gf_fit_gaussian(x, y, 2, &amp, &mu, &var), GF_ERR_PARAM); // < 3 points
    double neg[NPT];
    for (size_t i = 0; i < NPT; i++) neg[i] = -y[i];
    assert_int_equal(gf_fit_gaussian(x, neg, NPT, &amp, &mu, &var), GF_ERR_PARAM); // no positive data
    double flat[NPT];
    for (size_t i = 0; i < NPT; i++) flat[i] = 1.0;
    assert_int_equal(gf_fit_gaussian(x, flat, NPT, &amp, &mu, &var), GF_ERR_PARAM); // no peak
    y[7] = NAN;
    assert_int_equal(gf_fit_gaussian(x, y, NPT, &amp, &mu, &var), GF_ERR_PARAM);
    double same[3] = {1.0, 1.0, 1.0}, ys[3] = {1.0, 2.0, 3.0};
    assert_int_equal(gf_fit_gaussian(same, ys, 3, &amp, &mu, &var), GF_ERR_PARAM); // one x value
}

#define NEXP 71

// r = 1 .. 8 step 0.1, C = a exp(-r / beta) (the correlation fit's range).
static void exp_data(double a, double beta, double *x, double *y, double (*jac)[3])
{
    for (size_t i = 0; i < NEXP; i++) {
        x[i] = 1.0 + 0.1 * (double)i;
        double e = exp(-x[i] / beta);
        y[i] = a * e;
        if (jac) {
            jac[i][0] = e;
            jac[i][1] = a * e * x[i] / (beta * beta);
            jac[i][2] = 0.0;
        }
    }
}

static void exponential_exact(void **state)
{
    (void)state;
    const double cases[][2] = {{0.8, 1.87}, {1.0, 0.3}, {3.0, 20.0}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        double x[NEXP], y[NEXP], a, beta;
        exp_data(cases[k][0], cases[k][1], x, y, NULL);
        assert_int_equal(gf_fit_exponential(x, y, NEXP, &a, &beta), GF_OK);
        gf_assert_near(a, cases[k][0], 1e-8 * cases[k][0]);
        gf_assert_near(beta, cases[k][1], 1e-8 * cases[k][1]);
    }
}

static void exponential_noisy(void **state)
{
    (void)state;
    // Noise sd 0.01 on a decay from 0.8 (the tail reaches 0.01, so some points
    // are negative: the log-linear start skips them, the fit keeps them).
    // Tolerance 5 Fisher sd, as for the Gaussian.
    const double a0 = 0.8, beta0 = 1.87, sigma = 0.01;
    double x[NEXP], y[NEXP], jac[NEXP][3], sd[2];
    exp_data(a0, beta0, x, y, jac);
    fisher_sd((const double(*)[3])jac, NEXP, 2, sigma, sd);
    gf_rng rng;
    gf_rng_seed(&rng, 777, 2);
    size_t negatives = 0;
    for (int rep = 0; rep < 20; rep++) {
        double yn[NEXP], a, beta;
        for (size_t i = 0; i < NEXP; i++) {
            yn[i] = y[i] + sigma * normal(&rng);
            negatives += yn[i] <= 0.0;
        }
        assert_int_equal(gf_fit_exponential(x, yn, NEXP, &a, &beta), GF_OK);
        gf_assert_near(a, a0, 5.0 * sd[0]);
        gf_assert_near(beta, beta0, 5.0 * sd[1]);
    }
    assert_true(negatives > 0); // the case the start must survive did occur
}

static void exponential_rejects_bad_data(void **state)
{
    (void)state;
    double x[NEXP], y[NEXP], a, beta;
    exp_data(1.0, 2.0, x, y, NULL);
    assert_int_equal(gf_fit_exponential(x, y, 1, &a, &beta), GF_ERR_PARAM);
    double grow[NEXP], neg[NEXP];
    for (size_t i = 0; i < NEXP; i++) {
        grow[i] = exp(x[i] / 3.0);
        neg[i] = -y[i];
    }
    assert_int_equal(gf_fit_exponential(x, grow, NEXP, &a, &beta), GF_ERR_PARAM);
    assert_int_equal(gf_fit_exponential(x, neg, NEXP, &a, &beta), GF_ERR_PARAM);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(gaussian_exact),    cmocka_unit_test(gaussian_noisy),    cmocka_unit_test(gaussian_rejects_bad_data),
    cmocka_unit_test(exponential_exact), cmocka_unit_test(exponential_noisy), cmocka_unit_test(exponential_rejects_bad_data),
};

GF_TEST_MAIN("fit", tests)
