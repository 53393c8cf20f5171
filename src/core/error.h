// SPDX-License-Identifier: MIT
// Internal: setting the thread's last-error message together with a status.
#ifndef GF_CORE_ERROR_H
#define GF_CORE_ERROR_H

#include <stddef.h>

#include "granflow/core.h"

/// Records a printf-style message as the thread's last error and returns status.
gf_status gf_error_set(gf_status status, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/// Copies `in` to out[0..n) with every byte that is not printable ASCII or
/// part of valid UTF-8 written as \xNN (binary input never reaches a
/// terminal raw). Returns the full escaped length (as snprintf); out may be
/// NULL when n is 0. gf_error_set applies it to every message.
size_t gf_escape(const char *in, char *out, size_t n);

/// Clears the thread's last-error message.
void gf_error_clear(void);

/// Records a warning for gf_warning() and passes it to the gf_set_warning_fn
/// callback; never prints. No trailing newline, no program name.
void gf_warn(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/// Calls the gf_set_assert_fn hook (default: print, abort).
void gf_assert_fail(const char *condition, const char *file, int line);

/// Misuse of an internal API (a bug), never bad user input. Compiled into
/// every build (Release defines NDEBUG, which would leave the hook unused),
/// so keep it out of hot loops.
#define GF_ASSERT(c) ((c) ? (void)0 : gf_assert_fail(#c, __FILE__, __LINE__))

#endif
