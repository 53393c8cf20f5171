// SPDX-License-Identifier: MIT
// The one implementation of key tables (config/keys.h): finding, listing,
// parsing, checking, printing, getting and setting values by name, for
// gf_config's keys and the analysis options alike.
#include <ctype.h>
#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "config/keys.h"
#include "core/alloc.h"
#include "core/error.h"

const gf_key *gf_keys_find(const gf_key_table *t, const char *section, const char *name)
{
    for (size_t i = 0; i < t->count; i++)
        if (strcmp(t->keys[i].section, section) == 0 && strcmp(t->keys[i].name, name) == 0) return &t->keys[i];
    return NULL;
}

bool gf_keys_section_known(const gf_key_table *t, const char *section)
{
    for (size_t i = 0; i < t->count; i++)
        if (strcmp(t->keys[i].section, section) == 0) return true;
    return false;
}

// Appends `s` to the NUL-terminated text in buf[0..n), truncating.
static void gf_keys_append(char *buf, size_t n, const char *s)
{
    size_t len = strlen(buf);
    if (len + 1 < n) snprintf(buf + len, n - len, "%s", s);
}

void gf_keys_list(const gf_key_table *t, const char *section, char *buf, size_t n)
{
    if (n == 0) return;
    buf[0] = '\0';
    for (size_t i = 0; i < t->count; i++) {
        const gf_key *k = &t->keys[i];
        const char *item;
        if (section) {
            if (strcmp(k->section, section) != 0) continue;
            item = k->name;
        } else {
            if (i > 0 && strcmp(t->keys[i - 1].section, k->section) == 0) continue;
            item = k->section;
        }
        if (buf[0]) gf_keys_append(buf, n, ", ");
        gf_keys_append(buf, n, item);
    }
}

static double *gf_keys_dfield(void *base, const gf_key *k) { return (double *)(void *)((char *)base + k->offset); }

static const double *gf_keys_cdfield(const void *base, const gf_key *k)
{
    return (const double *)(const void *)((const char *)base + k->offset);
}

static size_t *gf_keys_count_field(void *base, const gf_key *k)
{
    return (size_t *)(void *)((char *)base + k->count_offset);
}

static size_t gf_keys_list_count(const void *base, const gf_key *k)
{
    size_t v;
    memcpy(&v, (const char *)base + k->count_offset, sizeof v);
    return v;
}

static bool gf_keys_in_range(const gf_key *k, double v)
{
    bool lo = k->min_open ? v > k->min : v >= k->min;
    bool hi = k->max_open ? v < k->max : v <= k->max;
    return lo && hi;
}

void gf_keys_format_double(double v, char *buf, size_t n)
{
    uint64_t want, got;
    memcpy(&want, &v, sizeof want);
    for (int prec = 15; prec <= 17; prec++) {
        snprintf(buf, n, "%.*g", prec, v);
        double back = strtod(buf, NULL);
        memcpy(&got, &back, sizeof got);
        if (got == want) return;
    }
}

// A set key's names and aliases, appended to buf: "dump, vtk; both = dump,vtk".
static void gf_keys_set_names(const gf_key *k, char *buf, size_t n)
{
    for (size_t i = 0; k->names[i]; i++) {
        if (i > 0) gf_keys_append(buf, n, ", ");
        gf_keys_append(buf, n, k->names[i]);
    }
    for (size_t i = 0; k->aliases && k->aliases[i]; i += 2) {
        gf_keys_append(buf, n, i ? ", " : "; ");
        gf_keys_append(buf, n, k->aliases[i]);
        gf_keys_append(buf, n, " = ");
        gf_keys_append(buf, n, k->aliases[i + 1]);
    }
}

void gf_keys_range(const gf_key *k, char *buf, size_t n)
{
    if (n == 0) return;
    buf[0] = '\0';
    switch (k->type) {
    case GF_KEY_ENUM:
        for (size_t i = 0; k->names[i]; i++) {
            if (i > 0) gf_keys_append(buf, n, ", ");
            gf_keys_append(buf, n, k->names[i]);
        }
        return;
    case GF_KEY_SET:
        gf_keys_append(buf, n, "list of ");
        gf_keys_set_names(k, buf, n);
        return;
    case GF_KEY_PATH: snprintf(buf, n, "path"); return;
    case GF_KEY_UINT64: snprintf(buf, n, "[0, %" PRIu64 "]", UINT64_MAX); return;
    case GF_KEY_DOUBLE:
    case GF_KEY_AUTO:
    case GF_KEY_INT64:
    case GF_KEY_SIZE:
    case GF_KEY_LIST: break;
    }
    char lo[32] = "-inf", hi[32] = "inf";
    if (isfinite(k->min)) gf_keys_format_double(k->min, lo, sizeof lo);
    if (isfinite(k->max)) gf_keys_format_double(k->max, hi, sizeof hi);
    snprintf(buf, n, "%c%s, %s%c%s", k->min_open || !isfinite(k->min) ? '(' : '[', lo, hi,
             k->max_open || !isfinite(k->max) ? ')' : ']',
             k->type == GF_KEY_AUTO || (k->type == GF_KEY_LIST && k->auto_empty) ? " or auto" : "");
}

static gf_key_result gf_keys_out_of_range(const gf_key *k, char *why, size_t n)
{
    char range[64];
    gf_keys_range(k, range, sizeof range);
    snprintf(why, n, "out of range %s", range);
    return GF_KEY_OUT_OF_RANGE;
}

// strtod/strtoll over the whole string; NULL or "" never parse.
static bool gf_keys_parse_double(const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end != '\0') return false;
    *out = v;
    return true;
}

static gf_key_result gf_keys_assign_double(const gf_key *k, void *cfg, const char *value,
                                           char *why, size_t n)
{
    double v;
    if (!gf_keys_parse_double(value, &v)) {
        snprintf(why, n, k->type == GF_KEY_AUTO ? "not a number or 'auto'" : "not a number");
        return GF_KEY_BAD_VALUE;
    }
    if (!isfinite(v)) {
        snprintf(why, n, "not a finite number");
        return GF_KEY_BAD_VALUE;
    }
    if (!gf_keys_in_range(k, v)) return gf_keys_out_of_range(k, why, n);
    *gf_keys_dfield(cfg, k) = v;
    return GF_KEY_OK;
}

static gf_key_result gf_keys_bad_integer(const char *value, char *why, size_t n)
{
    double v;
    snprintf(why, n, gf_keys_parse_double(value, &v) ? "not an integer" : "not a number");
    return GF_KEY_BAD_VALUE;
}

static gf_key_result gf_keys_assign_int64(const gf_key *k, void *cfg, const char *value,
                                          char *why, size_t n)
{
    char *end;
    errno = 0;
    long long v = strtoll(value, &end, 10);
    if (end == value || *end != '\0') return gf_keys_bad_integer(value, why, n);
    if (errno == ERANGE || !gf_keys_in_range(k, (double)v)) return gf_keys_out_of_range(k, why, n);
    int64_t x = (int64_t)v;
    memcpy((char *)cfg + k->offset, &x, sizeof x);
    return GF_KEY_OK;
}

static gf_key_result gf_keys_assign_uint64(const gf_key *k, void *cfg, const char *value,
                                           char *why, size_t n)
{
    char *end;
    errno = 0;
    unsigned long long v = strtoull(value, &end, 10);
    if (end == value || *end != '\0') return gf_keys_bad_integer(value, why, n);
    // strtoull accepts "-1" and wraps it around; a minus sign is out of range here.
    if (errno == ERANGE || value[0] == '-') return gf_keys_out_of_range(k, why, n);
    uint64_t x = (uint64_t)v;
    memcpy((char *)cfg + k->offset, &x, sizeof x);
    return GF_KEY_OK;
}

static gf_key_result gf_keys_assign_enum(const gf_key *k, void *cfg, const char *value,
                                         char *why, size_t n)
{
    for (int i = 0; k->names[i]; i++) {
        if (strcmp(k->names[i], value) == 0) {
            memcpy((char *)cfg + k->offset, &i, sizeof i);
            return GF_KEY_OK;
        }
    }
    char names[128];
    gf_keys_range(k, names, sizeof names);
    snprintf(why, n, "not one of: %s", names);
    return GF_KEY_BAD_VALUE;
}

// Comma-separated names, each trimmed and each at most once, as bits; or an
// alias standing for such a list as the whole value. An unknown element is
// named with its place in the list.
static gf_key_result gf_keys_assign_set(const gf_key *k, void *cfg, const char *value, char *why, size_t n)
{
    for (size_t i = 0; k->aliases && k->aliases[i]; i += 2)
        if (strcmp(value, k->aliases[i]) == 0) return gf_keys_assign_set(k, cfg, k->aliases[i + 1], why, n);
    int bits = 0;
    size_t count = 0;
    for (const char *p = value;; count++) {
        const char *e = strchr(p, ',');
        size_t len = e ? (size_t)(e - p) : strlen(p);
        while (len > 0 && isspace((unsigned char)*p)) p++, len--;
        while (len > 0 && isspace((unsigned char)p[len - 1])) len--;
        int bit = -1;
        for (int i = 0; k->names[i]; i++)
            if (strlen(k->names[i]) == len && strncmp(k->names[i], p, len) == 0) bit = i;
        if (bit < 0) {
            char names[128] = "";
            gf_keys_set_names(k, names, sizeof names);
            snprintf(why, n, "element %zu '%.*s' is not one of: %s", count + 1, (int)(len < 64 ? len : 64), p, names);
            return GF_KEY_BAD_VALUE;
        }
        if (bits & (1 << bit)) {
            snprintf(why, n, "element %zu '%s' is listed twice", count + 1, k->names[bit]);
            return GF_KEY_BAD_VALUE;
        }
        bits |= 1 << bit;
        if (!e) break;
        p = e + 1;
    }
    memcpy((char *)cfg + k->offset, &bits, sizeof bits);
    return GF_KEY_OK;
}

static gf_key_result gf_keys_assign_size(const gf_key *k, void *base, const char *value, char *why, size_t n)
{
    char *end;
    errno = 0;
    long long v = strtoll(value, &end, 10);
    if (end == value || *end != '\0') return gf_keys_bad_integer(value, why, n);
    if (errno == ERANGE || v < 0 || !gf_keys_in_range(k, (double)v)) return gf_keys_out_of_range(k, why, n);
    size_t x = (size_t)v;
    memcpy((char *)base + k->offset, &x, sizeof x);
    return GF_KEY_OK;
}

// Comma-separated numbers, each trimmed; stored with their count only when all are good.
static gf_key_result gf_keys_assign_list(const gf_key *k, void *base, const char *value, char *why, size_t n)
{
    double *dst = gf_keys_dfield(base, k);
    if (k->auto_empty && strcmp(value, "auto") == 0) {
        memset(dst, 0, sizeof *dst * k->list_max);
        *gf_keys_count_field(base, k) = 0;
        return GF_KEY_OK;
    }
    double v[64];
    size_t count = 0;
    const char *p = value;
    for (;;) {
        const char *e = strchr(p, ',');
        size_t len = e ? (size_t)(e - p) : strlen(p);
        char tok[64];
        while (len > 0 && isspace((unsigned char)*p)) p++, len--;
        while (len > 0 && isspace((unsigned char)p[len - 1])) len--;
        if (count == k->list_max || count == sizeof v / sizeof v[0]) {
            snprintf(why, n, "more than %zu values", k->list_max);
            return GF_KEY_BAD_VALUE;
        }
        snprintf(tok, sizeof tok, "%.*s", (int)(len < sizeof tok ? len : sizeof tok - 1), p);
        if (len == 0 || len >= sizeof tok || !gf_keys_parse_double(tok, &v[count]) || !isfinite(v[count])) {
            snprintf(why, n, "value %zu '%s' is not a number", count + 1, tok);
            return GF_KEY_BAD_VALUE;
        }
        if (!gf_keys_in_range(k, v[count])) {
            char range[64];
            gf_keys_range(k, range, sizeof range);
            snprintf(why, n, "value %zu = %s out of range %s", count + 1, tok, range);
            return GF_KEY_OUT_OF_RANGE;
        }
        if (k->increasing && count > 0 && !(v[count] > v[count - 1])) {
            snprintf(why, n, "the values must increase");
            return GF_KEY_BAD_VALUE;
        }
        count++;
        if (!e) break;
        p = e + 1;
    }
    memset(dst, 0, sizeof *dst * k->list_max);
    memcpy(dst, v, sizeof *v * count);
    *gf_keys_count_field(base, k) = count;
    return GF_KEY_OK;
}

gf_key_result gf_keys_assign(const gf_key *k, void *cfg, const char *value, char *why, size_t n)
{
    if (value[0] == '\0' && k->type != GF_KEY_PATH) {
        snprintf(why, n, "empty value");
        return GF_KEY_BAD_VALUE;
    }
    switch (k->type) {
    case GF_KEY_AUTO:
        if (strcmp(value, "auto") == 0) {
            *gf_keys_dfield(cfg, k) = NAN;
            return GF_KEY_OK;
        }
        return gf_keys_assign_double(k, cfg, value, why, n);
    case GF_KEY_DOUBLE: return gf_keys_assign_double(k, cfg, value, why, n);
    case GF_KEY_INT64: return gf_keys_assign_int64(k, cfg, value, why, n);
    case GF_KEY_UINT64: return gf_keys_assign_uint64(k, cfg, value, why, n);
    case GF_KEY_ENUM: return gf_keys_assign_enum(k, cfg, value, why, n);
    case GF_KEY_SET: return gf_keys_assign_set(k, cfg, value, why, n);
    case GF_KEY_SIZE: return gf_keys_assign_size(k, cfg, value, why, n);
    case GF_KEY_LIST: return gf_keys_assign_list(k, cfg, value, why, n);
    case GF_KEY_PATH: {
        size_t len = strlen(value);
        if (len >= GF_PATH_MAX) {
            snprintf(why, n, "path too long (%zu bytes, at most %d)", len, GF_PATH_MAX - 1);
            return GF_KEY_BAD_VALUE;
        }
        char *dst = (char *)cfg + k->offset;
        memset(dst, 0, GF_PATH_MAX);
        memcpy(dst, value, len);
        return GF_KEY_OK;
    }
    }
    snprintf(why, n, "unknown key type");
    return GF_KEY_BAD_VALUE;
}

bool gf_keys_check(const gf_key *k, const void *cfg, char *why, size_t n)
{
    const char *field = (const char *)cfg + k->offset;
    switch (k->type) {
    case GF_KEY_AUTO:
    case GF_KEY_DOUBLE: {
        double v = *gf_keys_cdfield(cfg, k);
        if (k->type == GF_KEY_AUTO && isnan(v)) return true;
        if (!isfinite(v)) {
            snprintf(why, n, "not a finite number");
            return false;
        }
        if (gf_keys_in_range(k, v)) return true;
        gf_keys_out_of_range(k, why, n);
        return false;
    }
    case GF_KEY_INT64: {
        int64_t v;
        memcpy(&v, field, sizeof v);
        if (gf_keys_in_range(k, (double)v)) return true;
        gf_keys_out_of_range(k, why, n);
        return false;
    }
    case GF_KEY_UINT64: return true;
    case GF_KEY_SIZE: {
        size_t v;
        memcpy(&v, field, sizeof v);
        if (gf_keys_in_range(k, (double)v)) return true;
        gf_keys_out_of_range(k, why, n);
        return false;
    }
    case GF_KEY_LIST: {
        size_t count = gf_keys_list_count(cfg, k);
        const double *v = gf_keys_cdfield(cfg, k);
        if (count > k->list_max || (count == 0 && !k->auto_empty)) {
            snprintf(why, n, "%zu values (1 to %zu)", count, k->list_max);
            return false;
        }
        for (size_t i = 0; i < count; i++) {
            if (!isfinite(v[i]) || !gf_keys_in_range(k, v[i])) {
                gf_keys_out_of_range(k, why, n);
                return false;
            }
            if (k->increasing && i > 0 && !(v[i] > v[i - 1])) {
                snprintf(why, n, "the values must increase");
                return false;
            }
        }
        return true;
    }
    case GF_KEY_ENUM: {
        int v, count = 0;
        memcpy(&v, field, sizeof v);
        while (k->names[count]) count++;
        if (v < 0 || v >= count) {
            char names[128];
            gf_keys_range(k, names, sizeof names);
            snprintf(why, n, "enum value %d is not one of: %s", v, names);
            return false;
        }
        return true;
    }
    case GF_KEY_SET: {
        int v, count = 0;
        memcpy(&v, field, sizeof v);
        while (k->names[count]) count++;
        if (v <= 0 || v >= 1 << count) {
            char names[128] = "";
            gf_keys_set_names(k, names, sizeof names);
            snprintf(why, n, "set value %d is not a non-empty list of: %s", v, names);
            return false;
        }
        return true;
    }
    case GF_KEY_PATH: {
        // A loop, not memchr: with LTO gcc sees the 480-byte analysis options
        // reach this function and warns, though no analysis key is a path.
        const char *c = field;
        for (size_t i = 0; i < GF_PATH_MAX; i++)
            if (c[i] == '\0') return true;
        snprintf(why, n, "path is not NUL-terminated within %d bytes", GF_PATH_MAX);
        return false;
    }
    }
    return false;
}

void gf_keys_format(const gf_key *k, const void *cfg, char *buf, size_t n)
{
    const char *field = (const char *)cfg + k->offset;
    switch (k->type) {
    case GF_KEY_AUTO:
        if (isnan(*gf_keys_cdfield(cfg, k))) {
            snprintf(buf, n, "auto");
            return;
        }
        gf_keys_format_double(*gf_keys_cdfield(cfg, k), buf, n);
        return;
    case GF_KEY_DOUBLE: gf_keys_format_double(*gf_keys_cdfield(cfg, k), buf, n); return;
    case GF_KEY_INT64: {
        int64_t v;
        memcpy(&v, field, sizeof v);
        snprintf(buf, n, "%" PRId64, v);
        return;
    }
    case GF_KEY_UINT64: {
        uint64_t v;
        memcpy(&v, field, sizeof v);
        snprintf(buf, n, "%" PRIu64, v);
        return;
    }
    case GF_KEY_ENUM: {
        int v, count = 0;
        memcpy(&v, field, sizeof v);
        while (k->names[count]) count++;
        if (v >= 0 && v < count)
            snprintf(buf, n, "%s", k->names[v]);
        else
            snprintf(buf, n, "%d", v);
        return;
    }
    case GF_KEY_SET: { // the names of the bits set, in table order: "dump,vtk"
        int v;
        memcpy(&v, field, sizeof v);
        if (n) buf[0] = '\0';
        for (int i = 0; k->names[i]; i++) {
            if (!(v & (1 << i))) continue;
            if (buf[0]) gf_keys_append(buf, n, ",");
            gf_keys_append(buf, n, k->names[i]);
        }
        return;
    }
    case GF_KEY_PATH: snprintf(buf, n, "%.*s", GF_PATH_MAX - 1, field); return;
    case GF_KEY_SIZE: {
        size_t v;
        memcpy(&v, field, sizeof v);
        snprintf(buf, n, "%zu", v);
        return;
    }
    case GF_KEY_LIST: {
        size_t count = gf_keys_list_count(cfg, k);
        const double *v = gf_keys_cdfield(cfg, k);
        if (n) buf[0] = '\0';
        if (count == 0 && k->auto_empty) snprintf(buf, n, "auto");
        for (size_t i = 0; i < count && i < k->list_max; i++) {
            char num[32];
            gf_keys_format_double(v[i], num, sizeof num);
            if (i > 0) gf_keys_append(buf, n, ",");
            gf_keys_append(buf, n, num);
        }
        return;
    }
    }
    if (n) buf[0] = '\0';
}

void gf_keys_defaults(const gf_key_table *t, void *base)
{
    for (size_t i = 0; i < t->count; i++) {
        char why[160];
        gf_key_result r = gf_keys_assign(&t->keys[i], base, t->keys[i].def, why, sizeof why);
        GF_ASSERT(r == GF_KEY_OK); // the table's own defaults always parse
        (void)r;
    }
}

const gf_key *gf_keys_lookup(const gf_key_table *t, const char *key, const char *fn)
{
    if (!key) {
        gf_error_set(GF_ERR_PARAM, "%s: key is NULL", fn);
        return NULL;
    }
    const char *dot = strchr(key, '.');
    char section[64];
    size_t len = dot ? (size_t)(dot - key) : 0;
    const gf_key *k = NULL;
    if (dot && len < sizeof section) {
        memcpy(section, key, len);
        section[len] = '\0';
        k = gf_keys_find(t, section, dot + 1);
    }
    if (!k) {
        char list[2048];
        if (dot && len < sizeof section && gf_keys_section_known(t, section)) {
            gf_keys_list(t, section, list, sizeof list);
            gf_error_set(GF_ERR_PARAM, "%s: unknown key '%s' (keys of [%s]: %s)", fn, key, section, list);
        } else {
            gf_keys_list(t, NULL, list, sizeof list);
            gf_error_set(GF_ERR_PARAM, "%s: unknown key '%s' (expected section.key; sections: %s)", fn, key, list);
        }
    }
    return k;
}

gf_status gf_keys_apply(const gf_key_table *t, void *base, const char *lead, bool show_value, const char *section,
                        const char *name, const char *value, const gf_key **found)
{
    char list[256];
    if (found) *found = NULL;
    if (!gf_keys_section_known(t, section)) {
        gf_keys_list(t, NULL, list, sizeof list);
        return gf_error_set(GF_ERR_PARAM, "%s: unknown section [%s] (known: %s)", lead, section, list);
    }
    const gf_key *k = gf_keys_find(t, section, name);
    if (!k) {
        gf_keys_list(t, section, list, sizeof list);
        return gf_error_set(GF_ERR_PARAM, "%s: unknown key '%s' in section [%s] (known: %s)", lead, name, section,
                            list);
    }
    char why[160];
    gf_key_result r = gf_keys_assign(k, base, value, why, sizeof why);
    if (r == GF_KEY_OK) {
        if (found) *found = k;
        return GF_OK;
    }
    if (!show_value) return gf_error_set(GF_ERR_PARAM, "%s: %s", lead, why);
    const char *q = r == GF_KEY_BAD_VALUE ? "'" : "";
    return gf_error_set(GF_ERR_PARAM, "%s: [%s] %s = %s%s%s: %s", lead, section, name, q, value, q, why);
}

// Strips leading and trailing white space in place.
static char *gf_keys_trim(char *s)
{
    while (isspace((unsigned char)*s)) s++;
    size_t n = strlen(s);
    while (n > 0 && isspace((unsigned char)s[n - 1])) s[--n] = '\0';
    return s;
}

gf_status gf_keys_set(const gf_key_table *t, void *base, const char *assignment, const char *origin,
                      const gf_key **found)
{
    if (found) *found = NULL;
    if (!assignment) return gf_error_set(GF_ERR_PARAM, "%s: assignment is NULL", origin);
    size_t size = strlen(assignment) + 1;
    char *buf = gf_alloc(size);
    if (!buf) return gf_error_set(GF_ERR_NOMEM, "%s: out of memory", origin);
    memcpy(buf, assignment, size);
    gf_status st;
    char *eq = strchr(buf, '=');
    char *dot = eq ? memchr(buf, '.', (size_t)(eq - buf)) : NULL;
    if (!eq || !dot) {
        st = gf_error_set(GF_ERR_PARAM, "%s %s: malformed assignment, expected section.key=value", origin, assignment);
    } else {
        *eq = '\0';
        *dot = '\0';
        char *section = gf_keys_trim(buf);
        char *name = gf_keys_trim(dot + 1);
        char *value = gf_keys_trim(eq + 1);
        if (!*section || !*name) {
            st = gf_error_set(GF_ERR_PARAM, "%s %s: malformed assignment, expected section.key=value", origin,
                              assignment);
        } else {
            char lead[GF_PATH_MAX + 160];
            snprintf(lead, sizeof lead, "%s %s.%s=%s", origin, section, name, value);
            st = gf_keys_apply(t, base, lead, false, section, name, value, found);
        }
    }
    gf_free(buf, size);
    return st;
}

gf_status gf_keys_get(const gf_key_table *t, const void *base, const char *key, char *buf, size_t size, const char *fn)
{
    if (!base || !buf || size == 0) return gf_error_set(GF_ERR_PARAM, "%s: NULL struct or empty buffer", fn);
    const gf_key *k = gf_keys_lookup(t, key, fn);
    if (!k) return GF_ERR_PARAM;
    char text[GF_PATH_MAX + 64];
    gf_keys_format(k, base, text, sizeof text);
    if (strlen(text) >= size)
        return gf_error_set(GF_ERR_PARAM, "%s: '%s' needs %zu bytes, buffer has %zu", fn, key, strlen(text) + 1, size);
    memcpy(buf, text, strlen(text) + 1);
    return GF_OK;
}

gf_status gf_keys_name(const gf_key_table *t, size_t i, char *buf, size_t size, const char *fn)
{
    if (i >= t->count) return gf_error_set(GF_ERR_PARAM, "%s: index %zu >= %zu", fn, i, t->count);
    if (!buf || size == 0) return gf_error_set(GF_ERR_PARAM, "%s: empty buffer", fn);
    int w = snprintf(buf, size, "%s.%s", t->keys[i].section, t->keys[i].name);
    if (w < 0 || (size_t)w >= size) return gf_error_set(GF_ERR_PARAM, "%s: buffer too small", fn);
    return GF_OK;
}
