// SPDX-License-Identifier: MIT
// The orifice position: where on the base it may be (docs/config.md, "Checks across keys").
#include "config/orifice.h"

#include <math.h>

#include "config/keys.h"
#include "core/error.h"

gf_status gf_config_check_orifice(const gf_config *cfg)
{
    char v[32], d[32], w[32];
    const double xy[2] = {cfg->orifice_x, cfg->orifice_y};
    const char *key[2] = {"container.orifice_x", "container.orifice_y"};
    for (int k = 0; k < 2; k++) {
        if (xy[k] == 0.0) continue;
        gf_keys_format_double(xy[k], v, sizeof v);
        if (cfg->container_shape == GF_SHAPE_CYLINDER)
            return gf_error_set(GF_ERR_PARAM, "%s = %s: a cylinder's outlet is on its axis (x = y = 0); an "
                                              "off-centre orifice needs container.shape = box", key[k], v);
        if (k == 1 && cfg->orifice_shape == GF_ORIFICE_SLIT)
            return gf_error_set(GF_ERR_PARAM, "%s = %s: a slit spans the whole depth (it has no y position; "
                                              "container.orifice_x moves it)", key[k], v);
    }
    const double half = 0.5 * cfg->orifice_diameter;
    gf_keys_format_double(cfg->orifice_diameter, d, sizeof d);
    if (!(fabs(cfg->orifice_x) + half < 0.5 * cfg->container_width)) {
        gf_keys_format_double(cfg->orifice_x, v, sizeof v);
        gf_keys_format_double(cfg->container_width, w, sizeof w);
        return gf_error_set(GF_ERR_PARAM, "container.orifice_x = %s puts the orifice (container.orifice_diameter = "
                                          "%s) partly outside the base: |orifice_x| + orifice_diameter/2 must be "
                                          "less than container.width/2 (width %s)", v, d, w);
    }
    if (cfg->orifice_y != 0.0 && !(fabs(cfg->orifice_y) + half <= 0.5 * cfg->container_depth)) {
        gf_keys_format_double(cfg->orifice_y, v, sizeof v);
        gf_keys_format_double(cfg->container_depth, w, sizeof w);
        return gf_error_set(GF_ERR_PARAM, "container.orifice_y = %s puts the orifice (container.orifice_diameter = "
                                          "%s) partly outside the base: |orifice_y| + orifice_diameter/2 must be at "
                                          "most container.depth/2 (depth %s)", v, d, w);
    }
    return GF_OK;
}
