// SPDX-License-Identifier: MIT
// Fuzz target: an STL file (geom/stl.c), parsed from memory, and when it
// parses, made into a mesh container's field and checked (geom/meshshape.c).
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "fuzz.h"
#include "geom/container.h"
#include "geom/meshshape.h"
#include "geom/stl.h"
#include "granflow/granflow.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    gf_stl m;
    if (gf_stl_parse("fuzz.stl", data, size, 1.0, &m) != GF_OK) return 0;
    // Small meshes only through the field and the checks (a huge bounding box is refused there).
    bool small = m.nt <= 2000;
    for (size_t v = 0; v < m.nv && small; v++)
        for (int a = 0; a < 3; a++) small = small && m.v[v][a] > -50.0 && m.v[v][a] < 50.0;
    gf_stl_free(&m);
    if (!small) return 0;
    const char *path = gf_fuzz_file(".stl", data, size);
    if (!path) return 0;
    gf_config cfg = gf_config_default();
    cfg.container_shape = GF_SHAPE_MESH;
    snprintf(cfg.container_mesh, sizeof cfg.container_mesh, "%s", path);
    cfg.orifice_diameter = 1.0;
    cfg.container_mesh_resolution = 2.0;
    if (gf_config_validate(&cfg) == GF_OK) {
        gf_container c = gf_container_make(&cfg);
        const double p[3] = {0.1, 0.2, 0.3};
        gf_wall_hit hit[GF_WALL_HITS];
        c.ops->walls(&c, p, 0.5, hit);
        c.ops->contains(&c, p[0], p[1], p[2], 0.5, 0.0);
        c.ops->section_area(&c, 0.5);
    }
    gf_meshshape_cache_clear();
    return 0;
}
