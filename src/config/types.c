// SPDX-License-Identifier: MIT
// The value syntax of packing.types: a list of LAMMPS atom types.
#include "granflow/config.h"

#include <ctype.h>
#include <errno.h>
#include <stdlib.h>

#include "core/error.h"

gf_status gf_packing_types_parse(const char *text, int32_t *types, size_t max, size_t *n)
{
    *n = 0;
    if (!text) return GF_OK;
    const char *p = text;
    for (;;) {
        while (*p == ' ' || *p == '\t' || *p == ',') p++;
        if (!*p) return GF_OK;
        const char *start = p;
        while (*p && *p != ' ' && *p != '\t' && *p != ',') p++;
        int len = (int)(p - start);
        char *end;
        errno = 0;
        long v = strtol(start, &end, 10);
        if (end != p || !isdigit((unsigned char)*start) || errno == ERANGE || v < 1 || v > INT32_MAX)
            return gf_error_set(GF_ERR_PARAM, "'%.*s' is not an atom type (an integer >= 1)", len, start);
        if (*n == max)
            return gf_error_set(GF_ERR_PARAM, "more than %zu atom types", max);
        types[(*n)++] = (int32_t)v;
    }
}
