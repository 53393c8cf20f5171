// SPDX-License-Identifier: MIT
// Internal: the radial stress field of a converging hopper (radial.c), the
// field of the converging section of a stress field (stress.c).
#ifndef GF_STRESS_RADIAL_H
#define GF_STRESS_RADIAL_H

#include <stdbool.h>

#include "core/error.h"

/// Points of the tabulated solution from the axis to the wall.
#define GF_RADIAL_N 401

/// sigma_ij = rho g r S_ij(theta), tabulated: s and w at theta_i = i theta_w / (N - 1).
typedef struct gf_radial {
    double theta_w;  ///< wall angle from the vertical, radians
    double sin_phi;
    int axisym;      ///< 1: cone; 0: wedge
    double s0;       ///< s on the axis: the mean stress there is rho g r s0
    double s[GF_RADIAL_N], w[GF_RADIAL_N];
} gf_radial;

/// Solves the radial field for internal and wall friction angles phi,
/// phi_w and the wall's half-angle from the vertical theta_w (degrees).
/// GF_ERR_STATE when none exists (a hopper too shallow for mass flow).
gf_status gf_radial_solve(double phi_deg, double phi_w_deg, double theta_w_deg, int axisym, gf_radial *out);

/// Which argument of gf_radial_solve gf_radial_edge varies.
typedef enum gf_radial_arg { GF_RADIAL_WALL_FRICTION, GF_RADIAL_HALF_ANGLE } gf_radial_arg;

/// Bisects, `iters` times, between `ok` (a radial field exists with argument
/// `arg` there, the others as given) and `bad` (none does); returns the last
/// value with one. Existence is monotone in either argument.
double gf_radial_edge(double phi_deg, double phi_w_deg, double theta_w_deg, int axisym, gf_radial_arg arg,
                      double ok, double bad, int iters);

/// Jenike's mass-flow limit: the largest wall half-angle from the vertical
/// (degrees) at which a radial field holds with the wall friction phi_w
/// fully mobilised (a steeper hopper has one, a shallower one none: funnel
/// flow). GF_ERR_STATE when there is none even for a nearly vertical wall.
gf_status gf_radial_mass_flow_angle(double phi_deg, double phi_w_deg, int axisym, double *theta_c_deg);

/// The stresses (sigma_uu, sigma_zz, sigma_uz, hoop) in rho_b g d at
/// distance r from the apex and angle theta from the vertical (negative:
/// the left side), and the major principal direction psi from the u axis.
void gf_radial_at(const gf_radial *rf, double r, double theta, double out[4], double *psi);

#endif
