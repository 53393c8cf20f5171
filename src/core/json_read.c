// SPDX-License-Identifier: MIT
// The one JSON reader: jansson parses, this walks the top-level object.
// jansson allocates with the C library's allocator, not gf_alloc: its
// allocator hook (json_set_alloc_funcs) is process-wide and would take over
// the host program's own use of jansson; every block is freed before return.
#include "core/json_read.h"

#include <errno.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "core/error.h"
#include "core/fs.h"

/// The largest JSON file read: summaries and reports are kilobytes.
#define GF_JSON_READ_MAX ((long long)16 * 1024 * 1024)

static gf_status gf_json_read_value(const char *key, json_t *v, gf_json_member_fn fn, void *ctx)
{
    gf_json_member m = {.key = key, .number = NAN};
    char *dump = NULL;
    switch (json_typeof(v)) {
    case JSON_NULL: m.kind = GF_JSON_NULL; break;
    case JSON_TRUE:
    case JSON_FALSE:
        m.kind = GF_JSON_BOOL;
        m.number = json_is_true(v) ? 1.0 : 0.0;
        break;
    case JSON_INTEGER:
        m.kind = GF_JSON_INT;
        m.integer = (long long)json_integer_value(v);
        m.number = (double)m.integer;
        break;
    case JSON_REAL:
        m.kind = GF_JSON_REAL;
        m.number = json_real_value(v);
        break;
    case JSON_STRING:
        m.kind = GF_JSON_STRING;
        m.text = json_string_value(v);
        break;
    case JSON_ARRAY:
    case JSON_OBJECT:
        m.kind = json_is_array(v) ? GF_JSON_ARRAY : GF_JSON_OBJECT;
        dump = json_dumps(v, JSON_COMPACT | JSON_ENCODE_ANY);
        if (!dump) return gf_error_set(GF_ERR_NOMEM, "out of memory reading JSON key '%s'", key);
        m.text = dump;
        break;
    }
    gf_status st = fn(ctx, &m);
    // jansson's own free (json_dumps allocates with it), not gf_free.
    json_free_t jfree;
    json_get_alloc_funcs(NULL, &jfree);
    if (dump) jfree(dump);
    return st;
}

gf_status gf_json_read_members(const char *path, gf_json_member_fn fn, void *ctx)
{
    // Only a regular file of bounded size (a FIFO or a link to /dev/zero in
    // its place would never end: issue 26).
    int fd = -1;
    gf_status so = gf_fs_open_regular(path, GF_JSON_READ_MAX, &fd);
    if (so != GF_OK) return so;
    FILE *f = fdopen(fd, "r");
    if (!f) {
        int e = errno;
        close(fd);
        gf_status st = gf_error_set(GF_ERR_IO, "%s: cannot open: %s", path, strerror(e));
        errno = e;
        return st;
    }
    json_error_t err;
    json_t *root = json_loadf(f, JSON_REJECT_DUPLICATES, &err);
    // An integer beyond long long (a 64-bit seed above 2^63): read every
    // number as a double instead of refusing the file.
    if (!root && json_error_code(&err) == json_error_numeric_overflow && fseek(f, 0, SEEK_SET) == 0)
        root = json_loadf(f, JSON_REJECT_DUPLICATES | JSON_DECODE_INT_AS_REAL, &err);
    int read_error = ferror(f);
    fclose(f);
    if (!root && read_error) return gf_error_set(GF_ERR_IO, "%s: read error", path);
    if (!root) return gf_error_set(GF_ERR_FORMAT, "%s:%d:%d: not valid JSON: %s", path, err.line, err.column, err.text);
    gf_status st = GF_OK;
    if (!json_is_object(root)) {
        st = gf_error_set(GF_ERR_FORMAT, "%s: the top value is not an object ({\"key\": value, ...})", path);
    } else {
        const char *key;
        json_t *v;
        json_object_foreach(root, key, v)
        {
            st = gf_json_read_value(key, v, fn, ctx);
            if (st != GF_OK) break;
        }
    }
    json_decref(root);
    return st;
}
