// SPDX-License-Identifier: MIT
// Internal: the one allocator. 64-byte aligned blocks with a byte counter, so
// every test can end by checking gf_bytes_allocated() == 0 (STYLE item 5).
#ifndef GF_CORE_ALLOC_H
#define GF_CORE_ALLOC_H

#include <stddef.h>
#include <stdio.h>
#include <sys/types.h>

/// Zeroed, 64-byte aligned block of `size` bytes, or NULL (size 0 gives NULL).
void *gf_alloc(size_t size);
/// Zeroed block of n elements of `size` bytes, or NULL (also when n * size
/// does not fit a size_t: a size derived from input can never wrap around).
void *gf_alloc_array(size_t n, size_t size);
/// Frees a block from gf_alloc; `size` must be the size it was allocated with.
void gf_free(void *p, size_t size);
/// Grows or shrinks a block, keeping min(old, new) bytes and zeroing the rest.
void *gf_realloc(void *p, size_t old_size, size_t new_size);

/// A zeroed block of n elements of `size` bytes whose pages are not touched
/// here: a page becomes resident only when written (fresh anonymous pages
/// read as zero), so an MPI rank that writes only its region of the
/// particles' arrays holds only that region (issue 23). Small blocks, and
/// every block under an allocator set by gf_set_allocator, come from
/// gf_alloc_array. Free with gf_free_pages and the same n and size.
void *gf_alloc_pages(size_t n, size_t size);
void gf_free_pages(void *p, size_t n, size_t size);
#define GF_NEW_PAGES(T, n) ((T *)gf_alloc_pages((size_t)(n), sizeof(T)))
#define GF_DELETE_PAGES(p, n) gf_free_pages((p), (size_t)(n), sizeof(*(p)))

/// The allocator set by gf_set_allocator (default aligned_alloc/free), unzeroed, uncounted.
void *gf_hook_alloc(size_t size, size_t alignment);
void gf_hook_free(void *block, size_t size);

/// Typed helpers: n elements of type T.
#define GF_NEW(T, n) ((T *)gf_alloc_array((size_t)(n), sizeof(T)))
#define GF_DELETE(p, n) gf_free((p), sizeof(*(p)) * (size_t)(n))

#endif
