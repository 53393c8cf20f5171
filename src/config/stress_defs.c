// SPDX-License-Identifier: MIT
// The stress solver's parameters from the [stress] keys: the one place
// outside the key table that reads them (src/stress/ takes the plain struct).
#include "granflow/config.h"

gf_stress_def gf_config_stress_def(const gf_config *cfg)
{
    return (gf_stress_def){
        .friction_angle = cfg->stress_friction_angle,
        .wall_friction_angle = cfg->stress_wall_friction_angle,
        .spacing = cfg->stress_spacing,
    };
}
