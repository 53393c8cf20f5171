// SPDX-License-Identifier: MIT
// gf_exits_read: the exits.csv a run writes (src/io/rundir.c), back into gf_exit records.
#include "io/exits_read.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/alloc.h"
#include "core/error.h"
#include "core/textscan.h"

/// Trims blanks (and a trailing \r) around a field in place.
static char *gf_exits_trim(char *s)
{
    s = (char *)gf_textscan_skip_blank(s);
    size_t n = strlen(s);
    while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\r')) s[--n] = '\0';
    return s;
}

/// Splits at commas in place; returns the number of fields (only the first max stored).
static size_t gf_exits_split(char *s, char **tok, size_t max)
{
    size_t n = 0;
    for (;;) {
        char *comma = strchr(s, ',');
        if (comma) *comma = '\0';
        if (n < max) tok[n] = gf_exits_trim(s);
        n++;
        if (!comma) return n;
        s = comma + 1;
    }
}

static int gf_exits_cmp(const void *pa, const void *pb)
{
    const gf_exit *a = pa, *b = pb;
    if (a->time != b->time) return a->time < b->time ? -1 : 1;
    return (a->id > b->id) - (a->id < b->id);
}

static gf_status gf_exits_parse(gf_textscan *ts, gf_exit **arr, size_t *n, size_t *cap)
{
    // id,time,x,y (a run without recirculation's columns, or an older run),
    // or id,time,x,y,pass,entry_time,entry_r.
    static const char *const names[7] = {"id", "time", "x", "y", "pass", "entry_time", "entry_r"};
    size_t ncol = 0;
    for (;;) {
        char *line, *tok[7];
        size_t len;
        gf_status st;
        int r = gf_textscan_next(ts, &line, &len, &st);
        if (r < 0) return st;
        if (r == 0) break;
        if (!*gf_textscan_skip_blank(line)) continue;
        size_t nf = gf_exits_split(line, tok, 7);
        if (!ncol) {
            bool ok = nf == 4 || nf == 7;
            for (size_t k = 0; ok && k < nf; k++) ok = strcasecmp(tok[k], names[k]) == 0;
            if (!ok)
                return gf_error_set(GF_ERR_FORMAT, "%s:%ld: expected the header 'id,time,x,y' or "
                                                   "'id,time,x,y,pass,entry_time,entry_r'", ts->path, ts->line);
            ncol = nf;
            continue;
        }
        if (nf != ncol)
            return gf_error_set(GF_ERR_FORMAT, "%s:%ld: %zu fields, expected %zu as the header says%s", ts->path,
                                ts->line, nf, ncol, ts->partial && nf < ncol ? " (truncated file?)" : "");
        gf_exit e = {.pass = 1, .entry_time = 0.0, .entry_r = NAN};
        long long id;
        if (gf_textscan_int(tok[0], &id) != 0 || id <= 0)
            return gf_error_set(GF_ERR_FORMAT, "%s:%ld: column 'id': '%.64s' is not a positive integer", ts->path,
                                ts->line, tok[0]);
        e.id = (int64_t)id;
        double *v[6] = {&e.time, &e.x, &e.y, NULL, &e.entry_time, &e.entry_r};
        for (size_t k = 1; k < ncol; k++) {
            if (k == 4) {
                long long pass;
                if (gf_textscan_int(tok[4], &pass) != 0 || pass <= 0)
                    return gf_error_set(GF_ERR_FORMAT, "%s:%ld: column 'pass': '%.64s' is not a positive integer",
                                        ts->path, ts->line, tok[4]);
                e.pass = pass;
            } else if (gf_textscan_double(tok[k], v[k - 1]) != 0) {
                return gf_error_set(GF_ERR_FORMAT, "%s:%ld: column '%s': '%.64s' is not a finite number", ts->path,
                                    ts->line, names[k], tok[k]);
            }
        }
        if (*n == *cap) {
            size_t nc = *cap ? 2 * *cap : 1024;
            gf_exit *a = gf_realloc(*arr, sizeof(gf_exit) * *cap, sizeof(gf_exit) * nc);
            if (!a) return gf_error_set(GF_ERR_NOMEM, "%s: out of memory at line %ld", ts->path, ts->line);
            *arr = a;
            *cap = nc;
        }
        (*arr)[(*n)++] = e;
    }
    if (!ncol) return gf_error_set(GF_ERR_FORMAT, "%s: empty file, expected the header 'id,time,x,y'", ts->path);
    return GF_OK;
}

gf_status gf_exits_read(const char *path, gf_exit **out, size_t *n)
{
    *out = NULL;
    *n = 0;
    gf_textscan ts;
    gf_exit *arr = NULL;
    size_t cnt = 0, cap = 0;
    // A run wrote it: a regular file (a FIFO or a link to a device in its
    // place would block or never end).
    gf_status st = gf_textscan_open_regular(&ts, path, 0);
    if (st == GF_OK) st = gf_exits_parse(&ts, &arr, &cnt, &cap);
    gf_textscan_close(&ts);
    if (st == GF_OK && cnt > 0 && cnt < cap) { // the caller frees exactly cnt elements
        gf_exit *a = gf_realloc(arr, sizeof(gf_exit) * cap, sizeof(gf_exit) * cnt);
        if (!a) st = gf_error_set(GF_ERR_NOMEM, "%s: out of memory", path);
        else {
            arr = a;
            cap = cnt;
        }
    }
    if (st != GF_OK) {
        if (arr) gf_free(arr, sizeof(gf_exit) * cap);
        return st;
    }
    if (cnt > 1) qsort(arr, cnt, sizeof *arr, gf_exits_cmp);
    *out = arr;
    *n = cnt;
    return GF_OK;
}
