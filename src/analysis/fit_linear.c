// SPDX-License-Identifier: MIT
// Least-squares straight line, the fit behind flow rates, Var(z) and the
// free-surface slope.
#include <math.h>

#include "core/error.h"
#include "granflow/analysis.h"

gf_status gf_fit_linear(const double *x, const double *y, size_t n, double *a, double *b)
{
    // Centred sums: no cancellation when x is far from 0 (times, heights).
    double mx = 0.0, my = 0.0;
    for (size_t i = 0; i < n; i++) {
        mx += x[i];
        my += y[i];
    }
    if (n < 2) return gf_error_set(GF_ERR_PARAM, "linear fit needs 2 points, got %zu", n);
    mx /= (double)n;
    my /= (double)n;
    double sxx = 0.0, sxy = 0.0;
    for (size_t i = 0; i < n; i++) {
        sxx += (x[i] - mx) * (x[i] - mx);
        sxy += (x[i] - mx) * (y[i] - my);
    }
    if (!(sxx > 0.0)) return gf_error_set(GF_ERR_PARAM, "linear fit needs 2 distinct x values");
    *a = sxy / sxx;
    *b = my - *a * mx;
    return GF_OK;
}
