// SPDX-License-Identifier: MIT
// The table of container shapes (docs/geometry.md, "Adding a shape"): one row
// per value of container.shape. A shape is one file (box.c, cylinder.c,
// wedge.c, meshshape.c) defining its gf_shape_ops and its row's gf_shape
// (with the check of its keys); this table is the only place that lists them.
#include "geom/container.h"

#include <string.h>

#include "core/error.h"
#include "core/shape_check.h"

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
    // The planted first: a row for a built-in's value stands in for it.
    for (int k = gf_shapes_nextra - 1; k >= 0; k--)
        if (gf_shapes_extra[k]->id == id) return gf_shapes_extra[k];
    for (size_t k = 0; k < sizeof gf_shapes_builtin / sizeof *gf_shapes_builtin; k++)
        if (gf_shapes_builtin[k]->id == id) return gf_shapes_builtin[k];
    return NULL;
}

bool gf_shape_register(const gf_shape *s)
{
    if (!s || gf_shapes_nextra >= GF_SHAPES_EXTRA) return false;
    gf_shapes_extra[gf_shapes_nextra++] = s;
    return true;
}

bool gf_shape_unregister(const gf_shape *s)
{
    for (int k = 0; k < gf_shapes_nextra; k++)
        if (gf_shapes_extra[k] == s) {
            for (int j = k + 1; j < gf_shapes_nextra; j++) gf_shapes_extra[j - 1] = gf_shapes_extra[j];
            gf_shapes_nextra--;
            return true;
        }
    return false;
}

bool gf_container_reads_key(const gf_container *c, const char *key)
{
    if (!c->type || !c->type->keys) return false;
    for (const char *const *k = c->type->keys; *k; k++)
        if (strcmp(*k, key) == 0) return true;
    return false;
}

// What gf_config_validate asks of the shapes (core/shape_check.h): the
// container defs of the config so far, handed to its shape's validate op.
static gf_status gf_shapes_validate(void *arg, const char **wall_key)
{
    gf_config *cfg = arg;
    gf_container_defs d;
    gf_config_container_defs(cfg, &d);
    *wall_key = NULL;
    const gf_shape *s = gf_shape_find(d.shape);
    if (!s) return gf_error_set(GF_ERR_PARAM, "container.shape: no shape has the value %d", (int)d.shape);
    *wall_key = s->wall_key;
    return s->validate ? s->validate(&d, cfg) : GF_OK;
}

__attribute__((constructor)) static void gf_shapes_register(void) { gf_shape_validate_set(gf_shapes_validate); }
