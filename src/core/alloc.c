// SPDX-License-Identifier: MIT
#include "core/alloc.h"

#include "granflow/core.h"

#include <stdatomic.h>
#include <stdint.h>
#include <string.h>

static atomic_size_t gf_bytes;

void *gf_alloc(size_t size)
{
    if (size == 0 || size > SIZE_MAX - 63) return NULL;
    // Whole cache lines, zeroed to the end, whatever allocator is installed.
    size_t rounded = (size + 63) & ~(size_t)63;
    void *p = gf_hook_alloc(rounded, 64);
    if (!p) return NULL;
    memset(p, 0, rounded);
    atomic_fetch_add(&gf_bytes, size);
    return p;
}

void *gf_alloc_array(size_t n, size_t size)
{
    if (size != 0 && n > SIZE_MAX / size) return NULL; // n * size would wrap around
    return gf_alloc(n * size);
}

void gf_free(void *p, size_t size)
{
    if (!p) return;
    atomic_fetch_sub(&gf_bytes, size);
    gf_hook_free(p, (size + 63) & ~(size_t)63);
}

void *gf_realloc(void *p, size_t old_size, size_t new_size)
{
    if (new_size == 0) {
        gf_free(p, old_size);
        return NULL;
    }
    void *q = gf_alloc(new_size);
    if (!q) return NULL;
    if (p) {
        memcpy(q, p, old_size < new_size ? old_size : new_size);
        gf_free(p, old_size);
    }
    return q;
}

size_t gf_bytes_allocated(void) { return atomic_load(&gf_bytes); }
