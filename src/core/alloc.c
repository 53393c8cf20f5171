// SPDX-License-Identifier: MIT
#define _DEFAULT_SOURCE // MAP_ANONYMOUS
#include "core/alloc.h"

#include "granflow/core.h"

#include <errno.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

// The only file of src/ that calls the C library's allocator (aligned_alloc
// and free behind the default hook below); tests/check_hooks.sh keeps it so.

// ---- the hook (gf_set_allocator) ----------------------------------------------

static void *gf_default_alloc(size_t size, size_t alignment)
{
    size_t rounded = (size + alignment - 1) & ~(alignment - 1);
    return aligned_alloc(alignment, rounded);
}

static void gf_default_free(void *block, size_t size)
{
    (void)size;
    free(block);
}

static gf_alloc_fn *gf_alloc_hook = gf_default_alloc;
static gf_free_fn *gf_free_hook = gf_default_free;

void gf_set_allocator(gf_alloc_fn *alloc, gf_free_fn *free_fn)
{
    gf_alloc_hook = alloc ? alloc : gf_default_alloc;
    gf_free_hook = alloc && free_fn ? free_fn : gf_default_free;
}

void *gf_hook_alloc(size_t size, size_t alignment) { return gf_alloc_hook(size, alignment); }

void gf_hook_free(void *block, size_t size) { gf_free_hook(block, size); }

// ---- counted, zeroed blocks -----------------------------------------------------

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

// ---- untouched pages (gf_alloc_pages) ---------------------------------------

// Blocks from this size on are mapped whole (fresh zero pages, not touched);
// below it a page or two more or less resident does not matter.
#define GF_PAGES_MIN ((size_t)1 << 20)

// Whether a block of `bytes` is mapped: decided alike at allocation and at
// release (gf_set_allocator is set before anything is allocated).
static bool gf_pages_mapped(size_t bytes) { return bytes >= GF_PAGES_MIN && gf_alloc_hook == gf_default_alloc; }

void *gf_alloc_pages(size_t n, size_t size)
{
    if (size != 0 && n > SIZE_MAX / size) return NULL;
    const size_t bytes = n * size;
    if (!gf_pages_mapped(bytes)) return gf_alloc(bytes);
    void *p = mmap(NULL, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) return NULL;
    atomic_fetch_add(&gf_bytes, bytes);
    return p;
}

void gf_free_pages(void *p, size_t n, size_t size)
{
    if (!p) return;
    const size_t bytes = n * size;
    if (!gf_pages_mapped(bytes)) {
        gf_free(p, bytes);
        return;
    }
    atomic_fetch_sub(&gf_bytes, bytes);
    munmap(p, bytes);
}

size_t gf_bytes_allocated(void) { return atomic_load(&gf_bytes); }
