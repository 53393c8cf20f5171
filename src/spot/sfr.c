// SPDX-License-Identifier: MIT
// The stochastic flow rule's step (sfr.h; docs/stress.md "The sfr walk").
#include "spot/sfr.h"

#include <math.h>

gf_sfr_walk gf_sfr_walk_make(double step_xy, double step_z, double eps, gf_sfr_rise rise)
{
    gf_sfr_walk wk = {.eps = eps, .hperp = step_xy / sqrt(2.0), .rise = rise == GF_RISE_STEADY ? step_z : 0.0};
    wk.L = step_xy / (sqrt(2.0) * sin(eps));
    wk.delta = wk.L > 0.0 ? 2.0 * step_z / wk.L : 0.0;
    return wk;
}

void gf_sfr_probs(const gf_sfr_walk *wk, double psi, const double f[2], double e[4][2], double prob[4])
{
    // Slip lines at psi -+ eps from the major principal direction (PRE 75, 041301; docs/stress.md).
    double al[2] = {cos(psi - wk->eps), sin(psi - wk->eps)}, be[2] = {cos(psi + wk->eps), sin(psi + wk->eps)};
    e[0][0] = al[0], e[0][1] = al[1];
    e[1][0] = -al[0], e[1][1] = -al[1];
    e[2][0] = be[0], e[2][1] = be[1];
    e[3][0] = -be[0], e[3][1] = -be[1];
    // Spots drift against the force on the grains (PRE 75, 041301, abstract; 2009 paper, Sec. 1): g = -f / |f|.
    double nf = hypot(f[0], f[1]), a = 0.0, b = 0.0;
    if (nf > 0.0) {
        double g[2] = {-f[0] / nf, -f[1] / nf};
        double det = al[0] * be[1] - al[1] * be[0]; // sin(2 eps) > 0
        a = (g[0] * be[1] - g[1] * be[0]) / det;
        b = (al[0] * g[1] - al[1] * g[0]) / det;
    }
    double d = wk->delta, m = fmax(fabs(a), fabs(b));
    if (d * m > 1.0) d = 1.0 / m; // no negative probability: the drift saturates
    prob[0] = 0.25 * (1.0 + d * a);
    prob[1] = 0.25 * (1.0 - d * a);
    prob[2] = 0.25 * (1.0 + d * b);
    prob[3] = 0.25 * (1.0 - d * b);
}

void gf_sfr_draw(const gf_sfr_walk *wk, double psi, const double f[2], gf_rng *rng, double *du, double *dz,
                 double *dv)
{
    double e[4][2], prob[4];
    gf_sfr_probs(wk, psi, f, e, prob);
    double u = gf_rng_uniform(rng), acc = 0.0;
    int pick = 3;
    for (int k = 0; k < 4; k++) {
        acc += prob[k];
        if (u < acc) {
            pick = k;
            break;
        }
    }
    *du = wk->L * e[pick][0];
    *dz = wk->rise > 0.0 ? wk->rise : wk->L * e[pick][1];
    *dv = gf_rng_below(rng, 2) ? wk->hperp : -wk->hperp;
}
