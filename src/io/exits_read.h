// SPDX-License-Identifier: MIT
// Internal: reading a run's exits.csv (`id,time,x,y[,pass,entry_time,entry_r]`, one line per exit).
#ifndef GF_IO_EXITS_READ_H
#define GF_IO_EXITS_READ_H

#include <stddef.h>

#include "granflow/core.h"
#include "granflow/exit.h"

/// Reads `path` into a gf_alloc'ed array of exactly *n exits (NULL when there
/// are none), sorted by time (then id). Malformed lines give GF_ERR_FORMAT
/// naming "path:line"; an unreadable file GF_ERR_IO.
gf_status gf_exits_read(const char *path, gf_exit **out, size_t *n);

#endif
