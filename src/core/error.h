// SPDX-License-Identifier: MIT
// Internal: setting the thread's last-error message together with a status.
#ifndef GF_CORE_ERROR_H
#define GF_CORE_ERROR_H

#include "granflow/core.h"

/// Records a printf-style message as the thread's last error and returns status.
gf_status gf_error_set(gf_status status, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/// Clears the thread's last-error message.
void gf_error_clear(void);

#ifndef NDEBUG
#include <assert.h>
/// Misuse of an internal API (a bug), never bad user input.
#define GF_ASSERT(c) assert(c)
#else
#define GF_ASSERT(c) ((void)0)
#endif

#endif
