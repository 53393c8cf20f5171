// SPDX-License-Identifier: MIT
// Internal: polling the stop flag (set by a signal handler, e.g. the CLI's
// gf_cli_catch_stop) in the loops that can run long.
#ifndef GF_CORE_STOP_H
#define GF_CORE_STOP_H

#include <signal.h>

#include "granflow/core.h"

/// GF_OK while `stop` is NULL or zero; once it is non-zero, GF_ERR_INTERRUPTED
/// with the message "WHAT: interrupted".
gf_status gf_stop_check(volatile sig_atomic_t *stop, const char *what);

#endif
