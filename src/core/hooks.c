// SPDX-License-Identifier: MIT
// The embedding hooks: assertion handler, warning sink (the allocator hook
// is in alloc.c, the one file that calls the C library's allocator).
#include "core/error.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

// ---- assertions ---------------------------------------------------------------

static int gf_default_assert(const char *condition, const char *file, int line)
{
    fprintf(stderr, "granflow: internal check failed: %s (%s:%d)\n", condition, file, line);
    return 1;
}

static gf_assert_fn *gf_assert_hook = gf_default_assert;

void gf_set_assert_fn(gf_assert_fn *fn) { gf_assert_hook = fn ? fn : gf_default_assert; }

void gf_assert_fail(const char *condition, const char *file, int line)
{
    if (gf_assert_hook(condition, file, line)) abort();
}

// ---- warnings -----------------------------------------------------------------

static gf_warning_fn *gf_warning_hook;
static void *gf_warning_ctx;

// The newest GF_WARNINGS_KEPT messages of this thread, oldest first from `first`.
static _Thread_local char gf_warn_text[GF_WARNINGS_KEPT][512];
static _Thread_local size_t gf_warn_first, gf_warn_n;

void gf_set_warning_fn(gf_warning_fn *fn, void *ctx)
{
    gf_warning_hook = fn;
    gf_warning_ctx = ctx;
}

void gf_warn(const char *fmt, ...)
{
    size_t slot = (gf_warn_first + gf_warn_n) % GF_WARNINGS_KEPT;
    if (gf_warn_n == GF_WARNINGS_KEPT)
        gf_warn_first = (gf_warn_first + 1) % GF_WARNINGS_KEPT; // drop the oldest
    else
        gf_warn_n++;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(gf_warn_text[slot], sizeof gf_warn_text[slot], fmt, ap);
    va_end(ap);
    if (gf_warning_hook) gf_warning_hook(gf_warning_ctx, gf_warn_text[slot]);
}

size_t gf_warning_count(void) { return gf_warn_n; }

const char *gf_warning(size_t i)
{
    if (i >= gf_warn_n) return NULL;
    return gf_warn_text[(gf_warn_first + i) % GF_WARNINGS_KEPT];
}

void gf_warnings_clear(void) { gf_warn_first = gf_warn_n = 0; }
