// SPDX-License-Identifier: MIT
// gf_packing storage: grow, append, free (formats layer; granflow/particles.h).
#include "granflow/particles.h"

#include <string.h>

#include "core/alloc.h"
#include "core/error.h"

gf_status gf_packing_reserve(gf_packing *p, size_t cap)
{
    if (cap <= p->cap) return GF_OK;
    size_t old = p->cap;
#define GF_GROW(field)                                                                       \
    do {                                                                                     \
        void *q = gf_realloc(p->field, sizeof(*p->field) * old, sizeof(*p->field) * cap);    \
        if (!q) return gf_error_set(GF_ERR_NOMEM, "out of memory for %zu particles", cap);   \
        p->field = q;                                                                        \
    } while (0)
    GF_GROW(id);
    GF_GROW(layer);
    GF_GROW(x);
    GF_GROW(y);
    GF_GROW(z);
    GF_GROW(r);
#undef GF_GROW
    p->cap = cap;
    return GF_OK;
}

gf_status gf_packing_push(gf_packing *p, int64_t id, int32_t layer, double x, double y, double z,
                          double r)
{
    if (p->n == p->cap) {
        gf_status st = gf_packing_reserve(p, p->cap < 64 ? 64 : 2 * p->cap);
        if (st != GF_OK) return st;
    }
    size_t i = p->n++;
    p->id[i] = id;
    p->layer[i] = layer;
    p->x[i] = x;
    p->y[i] = y;
    p->z[i] = z;
    p->r[i] = r;
    return GF_OK;
}

void gf_packing_free(gf_packing *p)
{
    GF_DELETE(p->id, p->cap);
    GF_DELETE(p->layer, p->cap);
    GF_DELETE(p->x, p->cap);
    GF_DELETE(p->y, p->cap);
    GF_DELETE(p->z, p->cap);
    GF_DELETE(p->r, p->cap);
    memset(p, 0, sizeof *p);
}
