// SPDX-License-Identifier: MIT
// The table of container shapes (docs/geometry.md, "Adding a shape"): one row
// per value of container.shape. A shape is one file (box.c, cylinder.c,
// wedge.c, meshshape.c) defining its gf_shape_ops and its row's gf_shape; this table is
// the only place that lists them.
#include "geom/container.h"

#include <string.h>

static const gf_shape *const gf_shapes_builtin[] = {
    &gf_box_shape,
    &gf_cylinder_shape,
    &gf_wedge_shape,
    &gf_mesh_shape,
};

// Shapes added at run time (tests plant one here). Not thread-safe: register
// before any container is made.
#define GF_SHAPES_EXTRA 4
static const gf_shape *gf_shapes_extra[GF_SHAPES_EXTRA];
static int gf_shapes_nextra;

const gf_shape *gf_shape_find(gf_container_shape id)
{
    for (size_t k = 0; k < sizeof gf_shapes_builtin / sizeof *gf_shapes_builtin; k++)
        if (gf_shapes_builtin[k]->id == id) return gf_shapes_builtin[k];
    for (int k = 0; k < gf_shapes_nextra; k++)
        if (gf_shapes_extra[k]->id == id) return gf_shapes_extra[k];
    return NULL;
}

bool gf_shape_register(const gf_shape *s)
{
    if (!s || gf_shapes_nextra >= GF_SHAPES_EXTRA) return false;
    gf_shapes_extra[gf_shapes_nextra++] = s;
    return true;
}

bool gf_container_reads_key(const gf_container *c, const char *key)
{
    if (!c->type || !c->type->keys) return false;
    for (const char *const *k = c->type->keys; *k; k++)
        if (strcmp(*k, key) == 0) return true;
    return false;
}
