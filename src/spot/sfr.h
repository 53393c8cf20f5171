// SPDX-License-Identifier: MIT
// Internal: the stochastic flow rule's step (sfr.c; Kamrin and Bazant, PRE 75,
// 041301, 2007; docs/stress.md "The sfr walk"): a spot steps along one of
// the two slip lines of the local stress, forwards or backwards, with
// probabilities biased towards the drift direction, minus the out-of-balance
// force on the grains when the friction drops; plus an out-of-plane step.
#ifndef GF_SPOT_SFR_H
#define GF_SPOT_SFR_H

#include "core/rng.h"
#include "stress/stress.h"

/// The walk's constants, from spot.step_xy = h and spot.step_z = dz and the
/// slip-line half-angle eps: L = h / (sqrt 2 sin eps), delta = 2 dz / L, so
/// that with a vertical major stress and an upward drift its moments are the
/// diffusive walk's: E[dx^2] = E[dy^2] = h^2 / 2, E[dz] = dz.
typedef struct gf_sfr_walk {
    double L;      ///< length of an in-plane step, d
    double delta;  ///< bias strength (at most 1 / max(|a|, |b|), see gf_sfr_probs)
    double hperp;  ///< out-of-plane step +-h / sqrt 2, d
    double eps;    ///< slip-line angle from the major principal direction, radians
    double rise;   ///< spot.sfr_rise = steady: every step's dz (step_z); 0: the slip line's own
} gf_sfr_walk;

gf_sfr_walk gf_sfr_walk_make(double step_xy, double step_z, double eps, gf_sfr_rise rise);

/// The four in-plane steps (unit vectors in (u, z): +alpha, -alpha, +beta,
/// -beta) and their probabilities at a point whose major principal
/// direction is psi and out-of-balance force f (docs/stress.md):
/// g = -f / |f| = a alpha + b beta, P(+-alpha) = (1 +- delta a) / 4,
/// P(+-beta) = (1 +- delta b) / 4.
void gf_sfr_probs(const gf_sfr_walk *wk, double psi, const double f[2], double e[4][2], double prob[4]);

/// One step: in-plane (du, dz) and out-of-plane dv, from two random draws;
/// with a steady rise dz is step_z and du the slip-line step's own.
void gf_sfr_draw(const gf_sfr_walk *wk, double psi, const double f[2], gf_rng *rng, double *du, double *dz,
                 double *dv);

#endif
