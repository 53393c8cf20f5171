// SPDX-License-Identifier: MIT
// The one JSON writer: nesting, keys, escaped strings, numbers in a fixed format.
#include "core/json.h"

#include <inttypes.h>
#include <math.h>

#include "core/error.h"

gf_json gf_json_start(FILE *f, bool pretty) { return (gf_json){.f = f, .pretty = pretty}; }

static void gf_json_string_body(FILE *f, const char *s)
{
    fputc('"', f);
    for (const unsigned char *c = (const unsigned char *)s; *c; c++) {
        if (*c == '"' || *c == '\\') fprintf(f, "\\%c", *c);
        else if (*c < 0x20) fprintf(f, "\\u%04x", (unsigned)*c);
        else fputc(*c, f);
    }
    fputc('"', f);
}

static bool gf_json_inline(const gf_json *j)
{
    if (!j->pretty) return true;
    for (int k = 0; k < j->depth; k++)
        if (j->array[k]) return true; // inside an array: one line
    return false;
}

// The separator, indentation and key before a value.
static void gf_json_lead(gf_json *j, const char *key)
{
    if (j->depth > 0) {
        int k = j->depth - 1;
        if (gf_json_inline(j)) {
            if (j->nonempty[k]) fputs(", ", j->f);
        } else {
            fputs(j->nonempty[k] ? ",\n" : "\n", j->f);
            for (int i = 0; i < j->depth; i++) fputs("  ", j->f);
        }
        j->nonempty[k] = true;
    }
    if (key && j->depth > 0 && !j->array[j->depth - 1]) {
        gf_json_string_body(j->f, key);
        fputs(": ", j->f);
    }
}

static void gf_json_open(gf_json *j, const char *key, bool array)
{
    gf_json_lead(j, key);
    fputc(array ? '[' : '{', j->f);
    GF_ASSERT(j->depth < GF_JSON_DEPTH);
    if (j->depth >= GF_JSON_DEPTH) return; // the caller's bug: written flat from here on
    j->array[j->depth] = array;
    j->nonempty[j->depth] = false;
    j->depth++;
}

void gf_json_object_begin(gf_json *j, const char *key) { gf_json_open(j, key, false); }

void gf_json_array_begin(gf_json *j, const char *key) { gf_json_open(j, key, true); }

void gf_json_end(gf_json *j)
{
    if (j->depth <= 0) return;
    int k = --j->depth;
    bool array = j->array[k];
    if (!array && j->nonempty[k] && !gf_json_inline(j)) {
        fputc('\n', j->f);
        for (int i = 0; i < k; i++) fputs("  ", j->f);
    }
    fputc(array ? ']' : '}', j->f);
    if (j->depth == 0) fputc('\n', j->f);
}

void gf_json_string(gf_json *j, const char *key, const char *s)
{
    gf_json_lead(j, key);
    gf_json_string_body(j->f, s ? s : "");
}

void gf_json_int(gf_json *j, const char *key, int64_t v)
{
    gf_json_lead(j, key);
    fprintf(j->f, "%" PRId64, v);
}

void gf_json_uint(gf_json *j, const char *key, uint64_t v)
{
    gf_json_lead(j, key);
    fprintf(j->f, "%" PRIu64, v);
}

void gf_json_bool(gf_json *j, const char *key, bool v)
{
    gf_json_lead(j, key);
    fputs(v ? "true" : "false", j->f);
}

void gf_json_null(gf_json *j, const char *key)
{
    gf_json_lead(j, key);
    fputs("null", j->f);
}

void gf_json_fixed(gf_json *j, const char *key, double v, int decimals)
{
    gf_json_lead(j, key);
    if (isfinite(v)) fprintf(j->f, "%.*f", decimals, v);
    else fputs("null", j->f);
}

void gf_json_general(gf_json *j, const char *key, double v, int digits)
{
    gf_json_lead(j, key);
    if (isfinite(v)) fprintf(j->f, "%.*g", digits, v);
    else fputs("null", j->f);
}
