// SPDX-License-Identifier: MIT
// The stop flag's one poll (see stop.h).
#include "core/stop.h"

#include "core/error.h"

gf_status gf_stop_check(volatile sig_atomic_t *stop, const char *what)
{
    if (!stop || !*stop) return GF_OK;
    return gf_error_set(GF_ERR_INTERRUPTED, "%s: interrupted", what);
}
