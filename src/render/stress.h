// SPDX-License-Identifier: MIT
// Internal: the picture of a stress field (stress.c; docs/stress.md).
#ifndef GF_RENDER_STRESS_H
#define GF_RENDER_STRESS_H

#include "geom/container.h"
#include "stress/stress.h"

/// Draws the field of container c to `path` (PNG, SVG or PDF by its
/// extension): P shaded, the major principal direction as bars, the alpha
/// (red) and beta (blue) slip lines traced from the surface and the walls.
gf_status gf_render_stress(const gf_stress_field *f, const gf_container *c, const char *title, const char *path);

/// When DIR/stress.csv exists (a run with spot.flow_rule = sfr): the field
/// solved again from cfg and the surface height in the file's header, drawn
/// to outdir/stress.EXT. GF_OK and nothing written without the file.
gf_status gf_render_stress_of_run(const char *dir, const gf_config *cfg, const char *outdir, const char *ext,
                                  const char *title, const char **written);

#endif
