// SPDX-License-Identifier: MIT
// Tables of doubles with named columns, written as CSV; the output of a
// measurement (tables, headline numbers, gnuplot script).
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "granflow/analysis.h"

gf_status gf_table_init(gf_table *t, const char *name, const char *cols)
{
    memset(t, 0, sizeof *t);
    if (strlen(name) >= GF_TABLE_NAME) return gf_error_set(GF_ERR_PARAM, "table name '%s' too long", name);
    strcpy(t->name, name);
    const char *s = cols;
    while (*s) {
        const char *e = strchr(s, ',');
        size_t len = e ? (size_t)(e - s) : strlen(s);
        if (t->ncol == GF_TABLE_MAXCOL || len == 0 || len >= GF_TABLE_NAME)
            return gf_error_set(GF_ERR_PARAM, "table %s: bad column list '%s'", name, cols);
        memcpy(t->cols[t->ncol], s, len);
        t->cols[t->ncol][len] = '\0';
        t->ncol++;
        s += len + (e != NULL);
    }
    if (t->ncol == 0) return gf_error_set(GF_ERR_PARAM, "table %s: no columns", name);
    return GF_OK;
}

gf_status gf_table_add(gf_table *t, const double *row)
{
    if (t->nrow == t->cap) {
        size_t cap = t->cap ? 2 * t->cap : 64;
        double *v = gf_realloc(t->v, sizeof(double) * t->cap * t->ncol, sizeof(double) * cap * t->ncol);
        if (!v) return gf_error_set(GF_ERR_NOMEM, "table %s: out of memory at %zu rows", t->name, t->nrow);
        t->v = v;
        t->cap = cap;
    }
    memcpy(t->v + t->nrow * t->ncol, row, sizeof(double) * t->ncol);
    t->nrow++;
    return GF_OK;
}

void gf_table_free(gf_table *t)
{
    if (t->v) gf_free(t->v, sizeof(double) * t->cap * t->ncol);
    memset(t, 0, sizeof *t);
}

gf_status gf_table_write_csv(const gf_table *t, const char *path)
{
    char tmp[4096];
    FILE *f;
    gf_status st = gf_atomic_open(path, tmp, sizeof tmp, &f);
    if (st != GF_OK) return st;
    for (size_t c = 0; c < t->ncol; c++) fprintf(f, "%s%s", c ? "," : "", t->cols[c]);
    fputc('\n', f);
    for (size_t r = 0; r < t->nrow; r++) {
        for (size_t c = 0; c < t->ncol; c++) {
            double v = t->v[r * t->ncol + c];
            // gnuplot and spreadsheets read "nan" as missing.
            if (isnan(v)) fprintf(f, "%snan", c ? "," : "");
            else fprintf(f, "%s%.10g", c ? "," : "", v);
        }
        fputc('\n', f);
    }
    return gf_atomic_commit(f, tmp, path);
}

gf_status gf_measure_value(gf_measure_out *o, const char *key, double value)
{
    if (o->nvalues == GF_MEASURE_MAXVALUE || strlen(key) >= GF_TABLE_NAME)
        return gf_error_set(GF_ERR_PARAM, "too many headline values (at '%s')", key);
    strcpy(o->values[o->nvalues].key, key);
    o->values[o->nvalues].value = value;
    o->nvalues++;
    return GF_OK;
}

gf_status gf_measure_gnuplot(gf_measure_out *o, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int add = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (add < 0) return gf_error_set(GF_ERR_PARAM, "bad gnuplot format '%s'", fmt);
    size_t old = o->gnuplot ? strlen(o->gnuplot) : 0;
    char *s = gf_realloc(o->gnuplot, o->gnuplot ? old + 1 : 0, old + (size_t)add + 1);
    if (!s) return gf_error_set(GF_ERR_NOMEM, "out of memory for a gnuplot script");
    va_start(ap, fmt);
    vsnprintf(s + old, (size_t)add + 1, fmt, ap);
    va_end(ap);
    o->gnuplot = s;
    return GF_OK;
}

void gf_measure_free(gf_measure_out *o)
{
    for (size_t k = 0; k < o->ntables; k++) gf_table_free(&o->tables[k]);
    if (o->gnuplot) gf_free(o->gnuplot, strlen(o->gnuplot) + 1);
    memset(o, 0, sizeof *o);
}
