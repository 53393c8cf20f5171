// SPDX-License-Identifier: MIT
// Internal: files written whole or not at all: write PATH.tmp, then rename it
// over PATH. Every writer of results, configs and checkpoints goes through here.
#ifndef GF_CORE_ATOMIC_FILE_H
#define GF_CORE_ATOMIC_FILE_H

#include <stdio.h>

#include "granflow/core.h"

/// Opens PATH.tmp for writing into *out (its name goes to tmp, of size n).
/// GF_ERR_PARAM when the name does not fit, GF_ERR_IO when it cannot be created.
gf_status gf_atomic_open(const char *path, char *tmp, size_t n, FILE **out);

/// Flushes and closes f, then renames tmp over path. On any failure tmp is
/// removed and GF_ERR_IO returned with a message naming the file.
gf_status gf_atomic_commit(FILE *f, const char *tmp, const char *path);

/// Closes f and removes tmp after the caller's own failure (its error stays).
void gf_atomic_abort(FILE *f, const char *tmp);

#endif
