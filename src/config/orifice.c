// SPDX-License-Identifier: MIT
// The orifice position: where on the base it may be (docs/config.md, "Checks
// across keys"). A shape whose outlet has a fixed place (a cylinder's axis)
// checks that in its own validate op (src/geom/).
#include "config/orifice.h"

#include <math.h>

#include "config/where.h"
#include "core/error.h"

gf_status gf_config_check_orifice(const gf_config *cfg)
{
    gf_config_msg m;
    const double xy[2] = {cfg->orifice_x, cfg->orifice_y};
    const char *key[2] = {"container.orifice_x", "container.orifice_y"};
    for (int k = 0; k < 2; k++) {
        if (xy[k] == 0.0) continue;
        if (k == 1 && cfg->orifice_shape == GF_ORIFICE_SLIT) {
            gf_config_msg_make(&m, cfg, key[k], "container.orifice_shape");
            return gf_error_set(GF_ERR_PARAM, "%s%s: a slit spans the whole depth (%s has no y position; "
                                              "container.orifice_x moves it)", m.lead, m.key[0], m.key[1]);
        }
    }
    const double half = 0.5 * cfg->orifice_diameter;
    if (!(fabs(cfg->orifice_x) + half < 0.5 * cfg->container_width)) {
        gf_config_msg_make(&m, cfg, "container.orifice_x", "container.width");
        return gf_error_set(GF_ERR_PARAM, "%s%s puts the orifice (container.orifice_diameter = %g) partly outside "
                                          "the base: |orifice_x| + orifice_diameter/2 must be less than half of %s",
                            m.lead, m.key[0], cfg->orifice_diameter, m.key[1]);
    }
    if (cfg->orifice_y != 0.0 && !(fabs(cfg->orifice_y) + half <= 0.5 * cfg->container_depth)) {
        gf_config_msg_make(&m, cfg, "container.orifice_y", "container.depth");
        return gf_error_set(GF_ERR_PARAM, "%s%s puts the orifice (container.orifice_diameter = %g) partly outside "
                                          "the base: |orifice_y| + orifice_diameter/2 must be at most half of %s",
                            m.lead, m.key[0], cfg->orifice_diameter, m.key[1]);
    }
    return GF_OK;
}
