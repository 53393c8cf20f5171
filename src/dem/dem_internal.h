// SPDX-License-Identifier: MIT
// Internal helpers shared by the DEM files (src/dem/).
#ifndef GF_DEM_INTERNAL_H
#define GF_DEM_INTERNAL_H

#include "granflow/core.h"
#include "granflow/dem.h"

/// Weighted least-squares line Var(z) = level + slope (z - zm) through the
/// heights the DEM measured precisely enough (gf_dem_flowstats_measured with
/// vtol), weighted by the DEM's 1 / err^2, zm their weighted mean height (so
/// level and slope are uncorrelated), fitted to the DEM's and to the spot's
/// Var at those heights with the same weights (so the two lines compare);
/// each coefficient with its standard error from the run's own errors.
typedef struct gf_dem_var_lines {
    int n;                           ///< heights used (below 2, or all at one height: no line)
    double zm;                       ///< the weighted mean height, d
    gf_dem_value level[2], slope[2]; ///< [0] the DEM's, [1] the spot's: Var at zm, d Var / dz
} gf_dem_var_lines;
void gf_dem_var_lines_fit(const gf_dem_flowstats *dem, const gf_dem_flowstats *spot, double vtol,
                          gf_dem_var_lines *l);

/// The refinement's update of the two parameters that set the widths of the
/// v_z(x) profiles, Var(z) ~ 2 b_s (z + r_s) + r_s^2 / 5 + birth spread:
/// step_xy sets the growth rate (b_s ~ dx^2: dx x sqrt(slope_DEM / slope_spot)),
/// r_s the level (taken as d Var / d r_s = 2 b_s + 2 r_s / 5). When a single
/// factor on every Var (the step alone: the weighted geometric mean of
/// Var_DEM / Var_spot) would bring every measured height within vtol, only
/// dx moves, by that factor; so it does when r_s is not `rs_free` (the DEM's
/// correlation length fixed it). Else, with at least two measured heights,
/// both are fitted (r_s only for a level difference beyond twice its
/// uncertainty). The level is compared at zm, where the spot's
/// Var after the step change is predicted as ka Var (ka = the change of
/// b_s). Each factor is limited to [1 / maxf, maxf].
void gf_dem_refine_width(const gf_dem_flowstats *dem, const gf_dem_flowstats *spot, double vtol, bool rs_free,
                         double maxf, double *step_xy, double *r_s);

#endif
