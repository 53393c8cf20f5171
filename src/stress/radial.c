// SPDX-License-Identifier: MIT
// The radial stress field of a converging hopper (Jenike 1961; Sokolovskii;
// Nedderman, Statics and Kinematics of Granular Materials, ch. 8): in polar
// (wedge) or spherical (cone) coordinates about the apex, r the distance
// from it and theta the angle from the vertical, the passive limit state
//   sigma_ij = rho g r S_ij(theta),  S_rr, S_tt = s (1 +- sin(phi) cos 2w),
//   S_rt = s sin(phi) sin 2w,  hoop S_pp = s (1 + sin(phi))  (Haar-von Karman),
// w the angle of the major principal direction from e_r towards e_theta.
// Equilibrium, div sigma = rho g (-cos theta, sin theta) in (e_r, e_theta),
// becomes two ODEs for s(theta) and w(theta), integrated from the axis
// (w = pi/2: major principal stress horizontal) to the wall, where the wall
// friction is fully mobilised (S_rt = -tan(phi_w) S_tt): the axis value
// s(0) is found by shooting.
#include <math.h>
#include <string.h>

#include "core/error.h"
#include "stress/radial.h"

#define GF_PI 3.14159265358979323846

typedef struct gf_radial_ode {
    double a;   // sin(phi)
    int k;      // 0: plane (wedge), 1: axisymmetric (cone)
} gf_radial_ode;

// d(s, w)/dtheta (docs/stress.md, "The radial field").
static void gf_radial_rhs(const gf_radial_ode *o, double th, const double y[2], double dy[2])
{
    double s = y[0], w = y[1], a = o->a, c = cos(2.0 * w), n = sin(2.0 * w);
    double cot = o->k ? cos(th) / sin(th) : 0.0;
    double R1 = -cos(th) - s * (1.0 + 3.0 * a * c) - o->k * s * (a * c - a + a * n * cot);
    double R2 = sin(th) - 3.0 * s * a * n - o->k * s * (-a * (c + 1.0) * cot + a * n);
    double det = a - c;
    dy[0] = (R1 * n - c * R2) / det;
    dy[1] = (a * n * R2 - (1.0 - a * c) * R1) / (2.0 * s * a * det);
}

// Integrates from the axis to theta_w with s(0) = s0 (RK4, `steps` steps);
// fills the table when `tab` is given. False when the solution breaks down.
static bool gf_radial_shoot(const gf_radial_ode *o, double s0, double thw, int steps, double *tab_s, double *tab_w,
                            double *sw, double *ww)
{
    // Regular at the axis: w = pi/2 + w1 theta, w1 from the first equation's
    // limit (n cot(theta) -> -2 w1 on a cone's axis).
    double a = o->a, w1 = (1.0 + s0 * (1.0 - 3.0 * a - 2.0 * a * o->k)) / (2.0 * s0 * a * (1.0 + o->k));
    double th0 = 1e-6 * thw, h = (thw - th0) / steps;
    double y[2] = {s0, 0.5 * GF_PI + w1 * th0};
    if (tab_s) {
        tab_s[0] = y[0];
        tab_w[0] = y[1];
    }
    for (int i = 0; i < steps; i++) {
        double th = th0 + i * h, k1[2], k2[2], k3[2], k4[2], t[2];
        gf_radial_rhs(o, th, y, k1);
        for (int q = 0; q < 2; q++) t[q] = y[q] + 0.5 * h * k1[q];
        gf_radial_rhs(o, th + 0.5 * h, t, k2);
        for (int q = 0; q < 2; q++) t[q] = y[q] + 0.5 * h * k2[q];
        gf_radial_rhs(o, th + 0.5 * h, t, k3);
        for (int q = 0; q < 2; q++) t[q] = y[q] + h * k3[q];
        gf_radial_rhs(o, th + h, t, k4);
        for (int q = 0; q < 2; q++) y[q] += h / 6.0 * (k1[q] + 2.0 * k2[q] + 2.0 * k3[q] + k4[q]);
        // The passive branch keeps the major direction between horizontal and
        // the radial direction's normal; leaving it (or meeting a < cos 2w,
        // where the system is singular) is no solution.
        if (!(y[0] > 0.0) || !(y[1] > 0.5 * GF_PI - 1e-9 && y[1] < GF_PI) || !(cos(2.0 * y[1]) < a - 1e-9))
            return false;
        if (tab_s) {
            tab_s[i + 1] = y[0];
            tab_w[i + 1] = y[1];
        }
    }
    *sw = y[0];
    *ww = y[1];
    return true;
}

// The wall condition's residual at w: S_rt + tan(phi_w) S_tt per unit s.
static double gf_radial_wall(double a, double mu_w, double w)
{
    return a * sin(2.0 * w) + mu_w * (1.0 - a * cos(2.0 * w));
}

gf_status gf_radial_solve(double phi_deg, double phi_w_deg, double theta_w_deg, int axisym, gf_radial *out)
{
    memset(out, 0, sizeof *out);
    if (!(theta_w_deg > 0.0 && theta_w_deg < 89.0))
        return gf_error_set(GF_ERR_PARAM, "hopper half-angle %g degrees: the radial field needs (0, 89)", theta_w_deg);
    gf_radial_ode o = {.a = sin(phi_deg * GF_PI / 180.0), .k = axisym ? 1 : 0};
    double mu_w = tan(phi_w_deg * GF_PI / 180.0), thw = theta_w_deg * GF_PI / 180.0;
    out->theta_w = thw;
    out->sin_phi = o.a;
    out->axisym = o.k;
    // Scan s0 for a sign change of the wall residual, then bisect.
    double prev_s0 = 0.0, prev_g = NAN;
    bool found = false;
    double lo = 0.0, hi = 0.0;
    for (int i = 1; i <= 400 && !found; i++) {
        double s0 = 0.02 * i * i / 40.0; // 0.0005 .. 80, denser near 0
        double sw, ww;
        if (!gf_radial_shoot(&o, s0, thw, 400, NULL, NULL, &sw, &ww)) {
            prev_g = NAN;
            continue;
        }
        double g = gf_radial_wall(o.a, mu_w, ww);
        if (isfinite(prev_g) && (g < 0.0) != (prev_g < 0.0)) {
            lo = prev_s0;
            hi = s0;
            found = true;
        }
        prev_s0 = s0;
        prev_g = g;
    }
    if (!found)
        return gf_error_set(GF_ERR_STATE,
                            "no radial stress field for a hopper half-angle of %g degrees with phi = %g and phi_w = %g "
                            "degrees (too shallow for mass flow)",
                            theta_w_deg, phi_deg, phi_w_deg);
    double sw, ww;
    (void)gf_radial_shoot(&o, lo, thw, 400, NULL, NULL, &sw, &ww);
    double glo = gf_radial_wall(o.a, mu_w, ww);
    for (int it = 0; it < 80; it++) {
        double mid = 0.5 * (lo + hi);
        if (!gf_radial_shoot(&o, mid, thw, 400, NULL, NULL, &sw, &ww)) {
            hi = mid;
            continue;
        }
        double g = gf_radial_wall(o.a, mu_w, ww);
        if ((g < 0.0) == (glo < 0.0)) {
            lo = mid;
            glo = g;
        } else {
            hi = mid;
        }
    }
    out->s0 = 0.5 * (lo + hi);
    if (!gf_radial_shoot(&o, out->s0, thw, GF_RADIAL_N - 1, out->s, out->w, &sw, &ww))
        return gf_error_set(GF_ERR_STATE, "the radial stress field broke down");
    return GF_OK;
}

double gf_radial_edge(double phi_deg, double phi_w_deg, double theta_w_deg, int axisym, gf_radial_arg arg,
                      double ok, double bad, int iters)
{
    gf_radial rf;
    for (int it = 0; it < iters; it++) {
        double mid = 0.5 * (ok + bad);
        bool has = arg == GF_RADIAL_WALL_FRICTION ? gf_radial_solve(phi_deg, mid, theta_w_deg, axisym, &rf) == GF_OK
                                                  : gf_radial_solve(phi_deg, phi_w_deg, mid, axisym, &rf) == GF_OK;
        if (has)
            ok = mid;
        else
            bad = mid;
    }
    gf_error_clear();
    return ok;
}

// Jenike (1961), Nedderman ch. 8: the mass-flow limit is where the radial
// field ceases to exist.
gf_status gf_radial_mass_flow_angle(double phi_deg, double phi_w_deg, int axisym, double *theta_c_deg)
{
    gf_radial rf;
    const double lo = 0.5, hi = 88.5;
    if (gf_radial_solve(phi_deg, phi_w_deg, lo, axisym, &rf) != GF_OK)
        return gf_error_set(GF_ERR_STATE, "no radial stress field even at a half-angle of %g degrees (phi = %g, phi_w = %g)",
                            lo, phi_deg, phi_w_deg);
    *theta_c_deg = gf_radial_solve(phi_deg, phi_w_deg, hi, axisym, &rf) == GF_OK
                       ? hi
                       : gf_radial_edge(phi_deg, phi_w_deg, 0.0, axisym, GF_RADIAL_HALF_ANGLE, lo, hi, 30);
    return GF_OK;
}

void gf_radial_at(const gf_radial *rf, double r, double theta, double out[4], double *psi)
{
    double th = fabs(theta), t = th / rf->theta_w * (GF_RADIAL_N - 1);
    if (t > GF_RADIAL_N - 1) t = GF_RADIAL_N - 1;
    int i = (int)t;
    if (i > GF_RADIAL_N - 2) i = GF_RADIAL_N - 2;
    double f = t - i, s = rf->s[i] + f * (rf->s[i + 1] - rf->s[i]), w = rf->w[i] + f * (rf->w[i + 1] - rf->w[i]);
    // e_r at (pi/2 - theta) from the u axis; e_theta is e_r turned clockwise,
    // so the major direction is at psi = pi/2 - theta - w. Mirrored for theta < 0.
    double ps = 0.5 * GF_PI - th - w;
    if (theta < 0.0) ps = GF_PI - ps;
    double P = r * s, a = rf->sin_phi;
    out[0] = P * (1.0 + a * cos(2.0 * ps)); // sigma_uu
    out[1] = P * (1.0 - a * cos(2.0 * ps)); // sigma_zz
    out[2] = P * a * sin(2.0 * ps);         // sigma_uz
    out[3] = P * (1.0 + a);                 // hoop: the major principal stress (passive)
    ps = fmod(ps, GF_PI);
    if (ps < 0.0) ps += GF_PI;
    *psi = ps;
}
