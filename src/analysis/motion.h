// SPDX-License-Identifier: MIT
// Internal: particle motion between snapshots, shared by the velocity,
// diffusion and correlation measurements: particles matched by id, velocities
// between consecutive frames, and the mean velocity field binned in (x, z)
// (in (r, z) in a cylinder).
#ifndef GF_ANALYSIS_MOTION_H
#define GF_ANALYSIS_MOTION_H

#include <signal.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "granflow/analysis.h"

// The id map (gf_idmap) and the frame window (gf_window_frames) are public:
// granflow/analysis.h.

/// A rise between two frames larger than this, d, is a particle put back on
/// the surface (run.recirculate), not motion: granular drainage never lifts a
/// particle by more than a fraction of a diameter.
#define GF_MOTION_JUMP 2.0

/// The particles present in two frames (and not put back on the surface in
/// between: a rise above GF_MOTION_JUMP): midpoint position and velocity
/// (r_b - r_a) / (t_b - t_a), d and d/tau. Arrays hold n entries.
typedef struct gf_steps {
    size_t n, cap;
    double dt; ///< t_b - t_a, tau
    double *x, *y, *z, *vx, *vy, *vz;
} gf_steps;

/// Fills `st` (reusing its arrays) from frames a and b (t_b > t_a, else GF_ERR_PARAM).
gf_status gf_steps_between(const gf_frame *a, const gf_frame *b, gf_steps *st);
void gf_steps_free(gf_steps *st);

/// Mean velocity over y and time in square (x, z) bins of edge `bin`, bins
/// aligned on multiples of it: bin (i, k) covers x in [bin (ix0 + i), bin (ix0 + i + 1)).
/// A radial field (a cylinder's axisymmetric mean flow, thesis Sec. 3.3 fits
/// its statistics about the local mean) bins in (r, z), r = |(x, y)|, and
/// holds the components (v_r, v_theta, v_z): "x" is then r.
typedef struct gf_vfield {
    double bin;
    bool radial;
    long ix0, iz0;
    size_t nx, nz;
    double *sum; ///< per bin: sum vx, sum vy, sum vz, samples (radial: v_r, v_theta, v_z)
} gf_vfield;

/// An empty field covering the particles of frames k0 .. k1-1 (in (r, z) when radial).
gf_status gf_vfield_init(gf_vfield *f, const gf_series *s, size_t k0, size_t k1, double bin, bool radial);
/// Adds every step to its bin.
void gf_vfield_add(gf_vfield *f, const gf_steps *st);
/// Mean velocity of the bin holding (x, z); returns its sample count (0: v
/// untouched). For a radial field x is r and v is (v_r, v_theta, v_z).
double gf_vfield_at(const gf_vfield *f, double x, double z, double v[3]);
/// The mean velocity at (x, y, z) in Cartesian components, either field: a
/// radial field's (v_r, v_theta, v_z) of the annulus of r turned back to
/// (x, y, z) at the point's azimuth. Returns the sample count (0: v untouched).
double gf_vfield_mean(const gf_vfield *f, double x, double y, double z, double v[3]);
void gf_vfield_free(gf_vfield *f);

/// The field over the consecutive frame pairs of [t0, t1]: every frame pair
/// inside the window, as the velocity measurement averages it. `pairs` gets
/// the number of pairs used. Polls *stop (may be NULL) at every pair:
/// GF_ERR_INTERRUPTED once it is non-zero.
gf_status gf_vfield_window(const gf_series *s, double t0, double t1, double bin, bool radial,
                           volatile sig_atomic_t *stop, gf_vfield *f, size_t *pairs);

#endif
