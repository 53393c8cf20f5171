// SPDX-License-Identifier: MIT
// Where the flow at one height has become steady: the mean v_z of the band
// in each frame pair against its late value (issue 27, item 2).
#include "analysis/steady_height.h"

#include <math.h>
#include <stdio.h>

enum { GF_SH_MIN_PAIRS = 4 }; // fewer pairs cannot show a start-up
#define GF_SH_TOL 0.005      // a chunk within 0.5% of the late value is steady (noise permitting)
#define GF_SH_SIGMAS 2.5     // ... or within this many standard deviations of the difference
#define GF_SH_FLOW_SE 3.0    // late flow within this many standard errors of 0: no flow
#define GF_SH_RAMP_SE 3.0    // last quarter faster than the third by this many standard errors ...
#define GF_SH_RAMP_TOL 0.05  // ... and by this fraction: still speeding up

/// Mean and sd of the finite values of v[a..b); their number in *k.
static void gf_sh_stats(const double *v, size_t a, size_t b, double *mean, double *sd, size_t *k)
{
    double s = 0.0, s2 = 0.0;
    size_t n = 0;
    for (size_t i = a; i < b; i++)
        if (isfinite(v[i])) {
            s += v[i];
            n++;
        }
    *mean = n ? s / (double)n : NAN;
    for (size_t i = a; i < b; i++)
        if (isfinite(v[i])) s2 += (v[i] - *mean) * (v[i] - *mean);
    *sd = n > 1 ? sqrt(s2 / (double)(n - 1)) : 0.0;
    *k = n;
}

gf_steady_height gf_steady_height_find(const double *m, size_t n)
{
    gf_steady_height r = {.steady = true, .first = 0, .late = NAN};
    if (n < GF_SH_MIN_PAIRS) {
        snprintf(r.why, sizeof r.why, "all %zu frame pairs (too few to see a start-up)", n);
        gf_sh_stats(m, 0, n, &r.late, &(double){0}, &(size_t){0});
        return r;
    }
    size_t h = n / 2, nl;
    double L, sd;
    gf_sh_stats(m, h, n, &L, &sd, &nl);
    r.late = L;
    if (nl < 2 || !(L < 0.0) || fabs(L) <= GF_SH_FLOW_SE * sd / sqrt((double)nl)) {
        r.steady = false;
        r.no_flow = true;
        snprintf(r.why, sizeof r.why, "no steady frames: no downward flow here in the last half of the window");
        return r;
    }
    // Still speeding up: the last quarter against the third.
    size_t q = h + (n - h) / 2, n3, n4;
    double m3, m4, sd3, sd4;
    gf_sh_stats(m, h, q, &m3, &sd3, &n3);
    gf_sh_stats(m, q, n, &m4, &sd4, &n4);
    // Noise within the quarters (a ramp across them is not noise), pooled.
    double sp = n3 + n4 > 2 ? sqrt(((double)(n3 > 0 ? n3 - 1 : 0) * sd3 * sd3 + (double)(n4 > 0 ? n4 - 1 : 0) * sd4 * sd4) /
                                   (double)(n3 + n4 - 2))
                            : 0.0;
    if (n3 >= 2 && n4 >= 2 && fabs(m4) - fabs(m3) > GF_SH_RAMP_TOL * fabs(m4) &&
        fabs(m4) - fabs(m3) > GF_SH_RAMP_SE * sp * sqrt(1.0 / (double)n3 + 1.0 / (double)n4)) {
        r.steady = false;
        snprintf(r.why, sizeof r.why,
                 "no steady frames: the flow here is still speeding up at the end of the window (%.3g -> %.3g d/tau)",
                 -m3, -m4);
        return r;
    }
    size_t J = n / 8 > 2 ? n / 8 : 2;
    r.first = h;
    for (size_t j = 0; j < h && j + J <= n; j++) {
        double c, csd;
        size_t nc;
        gf_sh_stats(m, j, j + J, &c, &csd, &nc);
        if (!nc) continue;
        double tol = fmax(GF_SH_TOL * fabs(L), GF_SH_SIGMAS * sd * sqrt(1.0 / (double)nc + 1.0 / (double)nl));
        if (fabs(c - L) <= tol) {
            r.first = j;
            break;
        }
    }
    // The return value looked at: gcc (without LTO) otherwise warns that the
    // reason may be cut short, which is harmless here.
    if (snprintf(r.why, sizeof r.why, "frame pairs %zu to %zu of %zu: the mean v_z is at its late value %.4g d/tau from pair %zu",
                 r.first + 1, n, n, L, r.first + 1) < 0)
        r.why[0] = 0;
    return r;
}

double gf_steady_height_rise_time(double z, double birth_z, double r_s, double step_z, double mu)
{
    double moves = fmax(0.0, (z - birth_z + r_s) / step_z);
    return (moves + 3.0 * sqrt(moves)) / mu;
}

void gf_steady_height_by_rise(gf_steady_height *v, const double *t_pair, size_t n, double t_ready)
{
    if (v->no_flow || !(t_ready >= 0.0)) return;
    size_t first = 0;
    while (first < n && t_pair[first] < t_ready) first++;
    size_t need = n / 8 > 2 ? n / 8 : 2; // as the noise test's chunks
    if (n - first < need) return; // the spots arrive too late in the window: the noise judges
    v->steady = true;
    v->first = first;
    if (snprintf(v->why, sizeof v->why,
                 "frame pairs %zu to %zu of %zu: from t = %.3g tau, when the first spots have risen here", first + 1,
                 n, n, t_ready) < 0)
        v->why[0] = 0;
}
