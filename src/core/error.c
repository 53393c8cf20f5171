// SPDX-License-Identifier: MIT
#include "core/error.h"

#include <stdarg.h>
#include <stdio.h>

static _Thread_local char gf_errbuf[1024];

gf_status gf_error_set(gf_status status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(gf_errbuf, sizeof gf_errbuf, fmt, ap);
    va_end(ap);
    return status;
}

void gf_error_clear(void) { gf_errbuf[0] = '\0'; }

const char *gf_last_error(void) { return gf_errbuf; }

const char *gf_status_str(gf_status status)
{
    switch (status) {
    case GF_OK: return "ok";
    case GF_ERR_PARAM: return "invalid parameter";
    case GF_ERR_IO: return "i/o error";
    case GF_ERR_FORMAT: return "malformed data";
    case GF_ERR_NOMEM: return "out of memory";
    case GF_ERR_STATE: return "invalid state";
    case GF_ERR_INTERRUPTED: return "interrupted";
    }
    return "unknown status";
}

const char *gf_version(void) { return GF_VERSION_STRING; }
