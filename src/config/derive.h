// SPDX-License-Identifier: MIT
// Internal: the derived values of a config, worked out in one place (issue
// 24): gf_config_validate resolves the `auto` keys with these, and the defs
// builders (defs.c) read them.
#ifndef GF_CONFIG_DERIVE_H
#define GF_CONFIG_DERIVE_H

#include "granflow/config.h"

/// relax.radius r_e: auto (NaN) = spot.radius + 1.
double gf_config_r_e(const gf_config *cfg);
/// spot.insertion_margin: auto (NaN) = spot.radius.
double gf_config_insertion_margin(const gf_config *cfg);
/// dem.kt: auto (NaN) = 2/7 dem.kn.
double gf_config_dem_kt(const gf_config *cfg);
/// dem.gammat: auto (NaN) = dem.gamman / 2.
double gf_config_dem_gammat(const gf_config *cfg);
/// Threads of a parallel fixed step: run.threads, or every core for 0.
int gf_config_threads(const gf_config *cfg);

#endif
