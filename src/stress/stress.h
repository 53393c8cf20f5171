// SPDX-License-Identifier: MIT
// Internal: the limit-state Mohr-Coulomb stress field of a container
// (docs/stress.md; issue 28). Plane strain in (x, z) for a container whose
// profiles are across x (box, wedge), axisymmetric in (r, z) with the
// Haar-von Karman hypothesis for one whose profiles are radial (cylinder,
// cone). Solved once, by marching the equilibrium equations down from the
// free surface (stress.c), stored on a regular grid (field.c) that the
// spot engine's stochastic flow rule reads (spot/walk.c) and that is
// written to the run directory and drawn (render/stress.c).
// Stresses are compressive positive, in units of rho_b g d (rho_b the bulk
// density, g gravity, d the particle diameter); angles are radians.
#ifndef GF_STRESS_STRESS_H
#define GF_STRESS_STRESS_H

#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "geom/container.h"
#include "granflow/config.h"

/// The stress at one point of the field, in the plane of the solution:
/// u is x (plane strain) or r (axisymmetric).
typedef struct gf_stress_point {
    double suu, szz, suz; ///< in-plane stresses
    double stt;           ///< out-of-plane stress: sigma_yy (plane strain) or the hoop stress
    double p;             ///< mean in-plane stress P = (suu + szz) / 2
    double psi;           ///< angle of the major principal direction from the u axis, in [0, pi)
    double f[2];          ///< out-of-balance force per unit drop of sin(phi), (u, z): div(P R(psi)) (docs/stress.md)
} gf_stress_point;

/// The field on a regular grid of nodes u_i = u0 + i du, z_j = z0 + j dz.
typedef struct gf_stress_field {
    gf_stress_def def;
    bool axisym;          ///< (r, z) with hoop stress; else (x, z)
    int nu, nz;
    double u0, du, z0, dz;
    double ztop, zstop;   ///< the free surface and the lowest level solved
    double sin_phi, eps;  ///< sin(phi) and the slip-line half angle pi/4 - phi/2
    gf_stress_point *pt;  ///< nu * nz, index j * nu + i
    unsigned char *in;    ///< 1 where the node is inside the material
    long clamped;         ///< states pulled back onto the yield surface while marching (should be 0)
    bool radial;          ///< below the top of the funnel (z < zcol) the field is the radial one
    double apex_u, apex_z, theta_w; ///< its apex and wall half-angle from the vertical (radians)
    double wall_mobilised; ///< the wall friction angle of the radial field, degrees: phi_w, or less when
                           ///< the hopper is too shallow for a field at phi_w (funnel flow by Jenike's criterion)
    double mass_flow_angle; ///< a cone's: Jenike's mass-flow limit, the largest wall half-angle from the vertical
                            ///< (degrees) with a radial field at phi, phi_w; NAN for other containers
} gf_stress_field;

/// Solves the field of container c filled up to `ztop` (the free surface,
/// no surcharge) down to z = 0 (the base or the outlet plane). GF_ERR_PARAM
/// with a message naming the key when def is out of range; GF_ERR_STATE
/// when the container has a column or no cross-section at some height.
gf_status gf_stress_solve(const gf_stress_def *def, const gf_container *c, double ztop, gf_stress_field *out);

/// Frees the field's arrays (leaves it zeroed).
void gf_stress_free(gf_stress_field *f);

/// The stress at (u, z), bilinear over the inside nodes around it; false
/// when no inside node is within one cell (outside the material).
bool gf_stress_at(const gf_stress_field *f, double u, double z, gf_stress_point *out);

/// The field's coordinate u of a 3D point: x, or r = hypot(x, y).
static inline double gf_stress_u(const gf_stress_field *f, double x, double y)
{
    return f->axisym ? sqrt(x * x + y * y) : x;
}

/// The two slip-line (characteristic) directions at psi: alpha at psi - eps
/// and beta at psi + eps from the u axis, unit vectors in (u, z).
void gf_stress_slip_dirs(const gf_stress_field *f, double psi, double alpha[2], double beta[2]);

/// Writes the field as CSV: one line per inside node (docs/stress.md).
gf_status gf_stress_write_csv(const gf_stress_field *f, const char *path);

#endif
