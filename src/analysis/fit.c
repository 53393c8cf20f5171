// SPDX-License-Identifier: MIT
// Non-linear least squares for the calibration fits (thesis Sec. 3.3): the
// Gaussian velocity profile and the exponential decay of velocity correlations,
// by a small Levenberg-Marquardt solver.
#include <math.h>
#include <string.h>

#include "core/error.h"
#include "granflow/analysis.h"

#define GF_LM_MAXP 3
#define GF_LM_MAXIT 500
#define GF_LM_XTOL 1e-11 // converged when every step is below this, relative to the parameter's scale

/// A model y = f(x; p) with its gradient df/dp; returns false when p is out of its domain.
typedef bool (*gf_lm_model)(double x, const double *p, double *f, double *grad);

/// Sum of squared residuals at p, or +inf when p is outside the model's domain.
static double gf_lm_chi2(gf_lm_model model, const double *x, const double *y, size_t n, const double *p)
{
    double chi2 = 0.0, f, g[GF_LM_MAXP];
    for (size_t i = 0; i < n; i++) {
        if (!model(x[i], p, &f, g)) return INFINITY;
        chi2 += (y[i] - f) * (y[i] - f);
    }
    return isfinite(chi2) ? chi2 : INFINITY;
}

/// Solves the m x m system a d = b (m <= 3) by Gaussian elimination with partial
/// pivoting; false when singular.
static bool gf_lm_solve(size_t m, double a[GF_LM_MAXP][GF_LM_MAXP], double *b, double *d)
{
    for (size_t c = 0; c < m; c++) {
        size_t piv = c;
        for (size_t r = c + 1; r < m; r++)
            if (fabs(a[r][c]) > fabs(a[piv][c])) piv = r;
        if (!(fabs(a[piv][c]) > 0.0)) return false;
        if (piv != c) {
            for (size_t k = 0; k < m; k++) {
                double t = a[c][k];
                a[c][k] = a[piv][k];
                a[piv][k] = t;
            }
            double t = b[c];
            b[c] = b[piv];
            b[piv] = t;
        }
        for (size_t r = c + 1; r < m; r++) {
            double f = a[r][c] / a[c][c];
            for (size_t k = c; k < m; k++) a[r][k] -= f * a[c][k];
            b[r] -= f * b[c];
        }
    }
    for (size_t c = m; c-- > 0;) {
        double s = b[c];
        for (size_t k = c + 1; k < m; k++) s -= a[c][k] * d[k];
        d[c] = s / a[c][c];
    }
    for (size_t c = 0; c < m; c++)
        if (!isfinite(d[c])) return false;
    return true;
}

/// Levenberg-Marquardt (Marquardt's diagonal scaling) from p; `scale` gives the
/// size against which each parameter's step is judged converged. Returns false
/// when it does not converge in GF_LM_MAXIT iterations.
static bool gf_lm_fit(gf_lm_model model, const double *x, const double *y, size_t n, double *p, size_t m,
                      void (*scale)(const double *p, double *s))
{
    double chi2 = gf_lm_chi2(model, x, y, n, p);
    if (!isfinite(chi2)) return false;
    double lambda = 1e-3;
    for (int it = 0; it < GF_LM_MAXIT; it++) {
        if (chi2 == 0.0) return true; // exact fit
        double jtj[GF_LM_MAXP][GF_LM_MAXP] = {{0}}, jtr[GF_LM_MAXP] = {0};
        for (size_t i = 0; i < n; i++) {
            double f = 0.0, g[GF_LM_MAXP] = {0};
            model(x[i], p, &f, g);
            double r = y[i] - f;
            for (size_t a = 0; a < m; a++) {
                jtr[a] += g[a] * r;
                for (size_t b = 0; b < m; b++) jtj[a][b] += g[a] * g[b];
            }
        }
        // Raise lambda until a step lowers chi^2. When even a tiny gradient step
        // cannot (lambda huge), p is the minimum to machine precision.
        for (;;) {
            double a[GF_LM_MAXP][GF_LM_MAXP], b[GF_LM_MAXP], d[GF_LM_MAXP] = {0}, q[GF_LM_MAXP];
            for (size_t r = 0; r < m; r++) {
                for (size_t c = 0; c < m; c++) a[r][c] = jtj[r][c];
                a[r][r] += lambda * (jtj[r][r] > 0.0 ? jtj[r][r] : 1.0);
                b[r] = jtr[r];
            }
            bool ok = gf_lm_solve(m, a, b, d);
            double c2 = INFINITY;
            if (ok) {
                for (size_t r = 0; r < m; r++) q[r] = p[r] + d[r];
                c2 = gf_lm_chi2(model, x, y, n, q);
            }
            if (c2 <= chi2) {
                double s[GF_LM_MAXP];
                scale(p, s);
                bool small = true;
                for (size_t r = 0; r < m; r++) small = small && fabs(d[r]) <= GF_LM_XTOL * s[r];
                memcpy(p, q, sizeof(double) * m);
                chi2 = c2;
                lambda = fmax(lambda * 0.1, 1e-12);
                if (small) return true;
                break;
            }
            lambda *= 10.0;
            if (lambda > 1e16) return true;
        }
    }
    return false;
}

// ---------------------------------------------------------------------------
// Gaussian: p = (A, mu, var).

static bool gf_gauss_model(double x, const double *p, double *f, double *g)
{
    if (!(p[2] > 0.0)) return false;
    double u = x - p[1];
    double e = exp(-u * u / (2.0 * p[2]));
    *f = p[0] * e;
    g[0] = e;
    g[1] = p[0] * e * u / p[2];
    g[2] = p[0] * e * u * u / (2.0 * p[2] * p[2]);
    return true;
}

static void gf_gauss_scale(const double *p, double *s)
{
    s[0] = fabs(p[0]);
    s[1] = sqrt(p[2]);
    s[2] = p[2];
}

gf_status gf_fit_gaussian(const double *x, const double *y, size_t n, double *amp, double *mu, double *var)
{
    if (n < 3) return gf_error_set(GF_ERR_PARAM, "Gaussian fit needs 3 points, got %zu", n);
    double xmin = INFINITY, xmax = -INFINITY, ymax = -INFINITY, w = 0.0, wx = 0.0;
    size_t npos = 0;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(x[i]) || !isfinite(y[i]))
            return gf_error_set(GF_ERR_PARAM, "Gaussian fit: point %zu is not finite", i);
        xmin = fmin(xmin, x[i]);
        xmax = fmax(xmax, x[i]);
        ymax = fmax(ymax, y[i]);
        if (y[i] > 0.0) {
            npos++;
            w += y[i];
            wx += y[i] * x[i];
        }
    }
    if (npos < 3 || !(ymax > 0.0))
        return gf_error_set(GF_ERR_PARAM, "Gaussian fit needs 3 positive values, got %zu", npos);
    // Start from the moments of the positive part of the profile.
    double p[3];
    p[0] = ymax;
    p[1] = wx / w;
    double wxx = 0.0;
    for (size_t i = 0; i < n; i++)
        if (y[i] > 0.0) wxx += y[i] * (x[i] - p[1]) * (x[i] - p[1]);
    p[2] = wxx / w;
    double range = xmax - xmin;
    if (!(range > 0.0)) return gf_error_set(GF_ERR_PARAM, "Gaussian fit needs distinct x values");
    if (!(p[2] > 0.0)) p[2] = 0.01 * range * range;
    if (!gf_lm_fit(gf_gauss_model, x, y, n, p, 3, gf_gauss_scale))
        return gf_error_set(GF_ERR_PARAM, "Gaussian fit did not converge (%zu points)", n);
    // A flat profile drives the width to infinity: no Gaussian to speak of.
    if (!(p[2] > 0.0) || !(p[2] < 1e4 * range * range) || !(p[0] > 0.0) || !isfinite(p[1]))
        return gf_error_set(GF_ERR_PARAM, "Gaussian fit: no peak in the data (A = %g, var = %g over a range of %g)",
                            p[0], p[2], range);
    *amp = p[0];
    *mu = p[1];
    *var = p[2];
    return GF_OK;
}

// ---------------------------------------------------------------------------
// Exponential: p = (a, k) with k = 1/beta, so the fit may pass through k = 0.

static bool gf_exp_model(double x, const double *p, double *f, double *g)
{
    double e = exp(-p[1] * x);
    *f = p[0] * e;
    g[0] = e;
    g[1] = -p[0] * x * e;
    return isfinite(e);
}

static void gf_exp_scale(const double *p, double *s)
{
    s[0] = fabs(p[0]);
    s[1] = fabs(p[1]);
}

gf_status gf_fit_exponential(const double *x, const double *y, size_t n, double *a, double *beta)
{
    if (n < 2) return gf_error_set(GF_ERR_PARAM, "exponential fit needs 2 points, got %zu", n);
    for (size_t i = 0; i < n; i++)
        if (!isfinite(x[i]) || !isfinite(y[i]))
            return gf_error_set(GF_ERR_PARAM, "exponential fit: point %zu is not finite", i);
    // Start from the straight line through (x, ln y) of the positive points
    // (centred sums, as in gf_fit_linear).
    size_t m = 0;
    double mx = 0.0, my = 0.0;
    for (size_t i = 0; i < n; i++)
        if (y[i] > 0.0) {
            mx += x[i];
            my += log(y[i]);
            m++;
        }
    if (m < 2) return gf_error_set(GF_ERR_PARAM, "exponential fit needs 2 positive values, got %zu", m);
    mx /= (double)m;
    my /= (double)m;
    double sxx = 0.0, sxy = 0.0;
    for (size_t i = 0; i < n; i++)
        if (y[i] > 0.0) {
            sxx += (x[i] - mx) * (x[i] - mx);
            sxy += (x[i] - mx) * (log(y[i]) - my);
        }
    if (!(sxx > 0.0)) return gf_error_set(GF_ERR_PARAM, "exponential fit needs positive values at 2 distinct x");
    double slope = sxy / sxx, icpt = my - slope * mx;
    if (!(slope < 0.0))
        return gf_error_set(GF_ERR_PARAM, "exponential fit: the data do not decay (log slope %g)", slope);
    double p[2] = {exp(icpt), -slope};
    if (!gf_lm_fit(gf_exp_model, x, y, n, p, 2, gf_exp_scale))
        return gf_error_set(GF_ERR_PARAM, "exponential fit did not converge (%zu points)", n);
    if (!(p[1] > 0.0) || !isfinite(p[0]))
        return gf_error_set(GF_ERR_PARAM, "exponential fit: no decay (a = %g, 1/beta = %g)", p[0], p[1]);
    *a = p[0];
    *beta = 1.0 / p[1];
    return GF_OK;
}
