// SPDX-License-Identifier: MIT
#include "report/html.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/alloc.h"
#include "core/error.h"
#include "core/fs.h"
#include "core/json_read.h"
#include "core/textscan.h"
#include "report/fields.h"

#define GF_HTML_ENTRIES 256 // keys of one summary.json (the analysis writes up to 256)
#define GF_HTML_COLUMNS 64  // fields of one CSV line

void gf_html_text(FILE *out, const char *s)
{
    for (; *s; s++) {
        switch (*s) {
        case '&': fputs("&amp;", out); break;
        case '<': fputs("&lt;", out); break;
        case '>': fputs("&gt;", out); break;
        case '"': fputs("&quot;", out); break;
        default: fputc(*s, out);
        }
    }
}

gf_status gf_html_base64_file(FILE *out, const char *path)
{
    static const char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    int fd;
    gf_status st = gf_fs_open_regular(path, GF_HTML_PICTURE_MAX, &fd);
    if (st != GF_OK) return st;
    unsigned char in[3 * 4096];
    char enc[4 * 4096];
    long long total = 0;
    for (;;) {
        // Whole groups of 3 bytes per chunk, so only the file's end needs padding.
        size_t n = 0;
        while (n < sizeof in) {
            ssize_t got = read(fd, in + n, sizeof in - n);
            if (got < 0 && errno == EINTR) continue;
            if (got < 0) {
                int e = errno;
                close(fd);
                return gf_error_set(GF_ERR_IO, "%s: read error: %s", path, strerror(e));
            }
            if (got == 0) break;
            n += (size_t)got;
        }
        total += (long long)n;
        if (total > GF_HTML_PICTURE_MAX) { // grown since it was opened
            close(fd);
            return gf_error_set(GF_ERR_FORMAT, "%s: more than the %lld bytes expected of a picture", path,
                                (long long)GF_HTML_PICTURE_MAX);
        }
        size_t w = 0;
        for (size_t i = 0; i < n; i += 3) {
            unsigned v = (unsigned)in[i] << 16 | (i + 1 < n ? (unsigned)in[i + 1] << 8 : 0) |
                         (i + 2 < n ? in[i + 2] : 0);
            enc[w++] = digits[v >> 18 & 63];
            enc[w++] = digits[v >> 12 & 63];
            enc[w++] = i + 1 < n ? digits[v >> 6 & 63] : '=';
            enc[w++] = i + 2 < n ? digits[v & 63] : '=';
        }
        fwrite(enc, 1, w, out);
        if (n < sizeof in) break;
    }
    close(fd);
    return GF_OK;
}

gf_status gf_html_image(FILE *out, const char *path, const char *alt)
{
    size_t n = strlen(path);
    const char *mime = n > 4 && !strcmp(path + n - 4, ".svg") ? "image/svg+xml" : "image/png";
    fprintf(out, "<img src=\"data:%s;base64,", mime);
    gf_status st = gf_html_base64_file(out, path);
    fputs("\" alt=\"", out);
    gf_html_text(out, alt);
    fputs("\">", out);
    return st;
}

// Strips white space; for a JSON key or value (json) also the commas after
// it and its surrounding quotes (a CSV line keeps its trailing empty fields).
static char *gf_html_trim(char *s, bool json)
{
    while (*s == ' ' || *s == '\t') s++;
    size_t n = strlen(s);
    while (n && (s[n - 1] == '\n' || s[n - 1] == '\r' || s[n - 1] == ' ' || (json && s[n - 1] == ','))) s[--n] = '\0';
    if (json && n >= 2 && s[0] == '"' && s[n - 1] == '"') {
        s[n - 1] = '\0';
        s++;
    }
    return s;
}

typedef struct gf_html_reading {
    gf_html_entry *e;
    size_t max, n;
} gf_html_reading;

// One member as text: a number as %lld or %.17g (the same double back; the
// table rounds it), null as `null`, a string as it is, an array or object as
// compact JSON.
static gf_status gf_html_json_entry(void *ctx, const gf_json_member *m)
{
    gf_html_reading *r = ctx;
    if (r->n == r->max) return GF_OK; // more are dropped
    gf_html_entry *e = &r->e[r->n++];
    snprintf(e->key, sizeof e->key, "%s", m->key);
    e->text = m->kind == GF_JSON_STRING || m->kind == GF_JSON_ARRAY || m->kind == GF_JSON_OBJECT;
    switch (m->kind) {
    case GF_JSON_NULL: snprintf(e->value, sizeof e->value, "null"); break;
    case GF_JSON_BOOL: snprintf(e->value, sizeof e->value, "%s", m->number != 0 ? "true" : "false"); break;
    case GF_JSON_INT: snprintf(e->value, sizeof e->value, "%lld", m->integer); break;
    case GF_JSON_REAL: snprintf(e->value, sizeof e->value, "%.17g", m->number); break;
    default: snprintf(e->value, sizeof e->value, "%s", m->text); break;
    }
    return GF_OK;
}

gf_status gf_html_json_load(const char *path, gf_html_entry *e, size_t max, int *n)
{
    *n = -1;
    if (access(path, F_OK) != 0 && errno == ENOENT) return GF_OK;
    gf_html_reading r = {e, max, 0};
    // jansson reads the whole file first: on an error no entry was made.
    gf_status st = gf_json_read_members(path, gf_html_json_entry, &r);
    *n = st == GF_OK ? (int)r.n : -2;
    return st;
}

int gf_html_json_read(const char *path, gf_html_entry *e, size_t max)
{
    int n;
    gf_html_json_load(path, e, max, &n);
    return n;
}

// Whether `s` is a whole number as a summary writes a count: digits, maybe a sign.
static bool gf_html_is_count(const char *s)
{
    if (*s == '-') s++;
    if (!*s) return false;
    for (; *s; s++)
        if (*s < '0' || *s > '9') return false;
    return true;
}

// 0.9900 -> 0.99, 4.000 -> 4: the zeros a rounding to 4 digits leaves claim a
// precision the number may not have (a bin centre, a whole time).
static char *gf_html_strip_zeros(char *s)
{
    if (!strchr(s, '.')) return s;
    size_t n = strlen(s);
    while (n && s[n - 1] == '0') s[--n] = '\0';
    if (n && s[n - 1] == '.') s[--n] = '\0';
    return s;
}

void gf_html_number(FILE *out, const char *text)
{
    char *end;
    double v = strtod(text, &end);
    if (!strcmp(text, "null") || !strcmp(text, "nan")) {
        fputs("—", out);
        return;
    }
    if (end == text || *end || !isfinite(v) || (gf_html_is_count(text) && strlen(text) < 16)) {
        gf_html_text(out, text); // a text, or a count: as it is
        return;
    }
    if (v == 0) {
        fputs("0", out);
        return;
    }
    char m[32];
    snprintf(m, sizeof m, "%.3e", v); // rounded to 4 digits: d.ddde+XX
    char *e = strchr(m, 'e');
    int exp10 = e ? atoi(e + 1) : 0;
    if (exp10 >= -3 && exp10 <= 5) {
        // plain decimals, as many as 4 significant digits need (none from 1000 up: 68970)
        char fixed[48];
        snprintf(fixed, sizeof fixed, "%.*f", exp10 >= 3 ? 0 : 3 - exp10, strtod(m, NULL));
        fputs(gf_html_strip_zeros(fixed), out);
    } else if (e) {
        *e = '\0';
        fprintf(out, "%s × 10<sup>%d</sup>", gf_html_strip_zeros(m), exp10);
    }
}

void gf_html_unit(FILE *out, const char *unit)
{
    for (const char *p = unit; *p; p++) {
        if (p[0] == '^' && p[1] >= '0' && p[1] <= '9') {
            fprintf(out, "<sup>%c</sup>", p[1]);
            p++;
        } else {
            char c[2] = {*p, '\0'};
            gf_html_text(out, c);
        }
    }
}

// The key in words (the key itself when the report does not know it).
static void gf_html_words(FILE *out, const char *key)
{
    const gf_report_field *f = gf_report_field_find(key);
    if (f) gf_html_text(out, f->words);
    else if (!strncmp(key, "skipped_", 8) && key[8]) { // the analysis' note on a measurement it could not make
        fputs("the measurement ", out);
        gf_html_text(out, key + 8);
    } else gf_html_text(out, key);
}

static const char *gf_html_unit_of(const char *key)
{
    const gf_report_field *f = gf_report_field_find(key);
    return f ? f->unit : "";
}

void gf_html_kv_table(FILE *out, const gf_html_entry *e, size_t n, const char *const *why)
{
    fputs("<table class=\"kv\">\n<tr><th>Quantity</th><th>Value</th><th>Unit</th><th>Key</th></tr>\n", out);
    size_t omitted = 0;
    for (size_t k = 0; k < n; k++) {
        if (why && why[k]) {
            omitted++;
            continue;
        }
        fputs("<tr><th>", out);
        gf_html_words(out, e[k].key);
        fputs(e[k].text ? "</th><td>" : "</th><td class=\"num\">", out);
        if (e[k].text) gf_html_text(out, e[k].value);
        else gf_html_number(out, e[k].value);
        fputs("</td><td>", out);
        gf_html_unit(out, gf_html_unit_of(e[k].key));
        fputs("</td><td><code>", out);
        gf_html_text(out, e[k].key);
        fputs("</code></td></tr>\n", out);
    }
    fputs("</table>\n", out);
    if (!omitted) return;
    // One line per reason, naming every entry it covers (in the table's order).
    fputs("<p class=\"omit\">Left out as not meaningful for this run:</p>\n<ul class=\"omit\">\n", out);
    for (size_t k = 0; k < n; k++) {
        bool said = false;
        for (size_t i = 0; i < k && !said; i++) said = why[i] && why[k] && !strcmp(why[i], why[k]);
        if (!why[k] || said) continue;
        fputs("<li>", out);
        for (size_t i = k, first = 1; i < n; i++) {
            if (!why[i] || strcmp(why[i], why[k])) continue;
            if (!first) fputs(", ", out);
            first = 0;
            gf_html_words(out, e[i].key);
            fputs(" (<code>", out);
            gf_html_text(out, e[i].key);
            fputs("</code>)", out);
        }
        fputs(": ", out);
        gf_html_text(out, why[k]);
        fputs("</li>\n", out);
    }
    fputs("</ul>\n", out);
}

// Opens a text file of the run for a table: absent is not an error (*found
// false); anything but a regular file of at most GF_HTML_TEXT_MAX bytes is.
static gf_status gf_html_open_text(gf_textscan *ts, const char *path, bool *found)
{
    *found = false;
    struct stat sb;
    if (stat(path, &sb) != 0 && errno == ENOENT) return GF_OK;
    gf_status st = gf_textscan_open_regular(ts, path, GF_HTML_TEXT_MAX);
    if (st != GF_OK) return st;
    ts->max_line = GF_TEXTSCAN_MAX_SHORT_LINE;
    *found = true;
    return GF_OK;
}

gf_status gf_html_json_table(FILE *out, const char *path, bool *found)
{
    *found = false;
    gf_html_entry *e = GF_NEW(gf_html_entry, GF_HTML_ENTRIES);
    if (!e) return gf_error_set(GF_ERR_NOMEM, "out of memory");
    int n;
    gf_status st = gf_html_json_load(path, e, GF_HTML_ENTRIES, &n); // the error names the file (line, column)
    if (n >= 0) gf_html_kv_table(out, e, (size_t)n, NULL);
    GF_DELETE(e, GF_HTML_ENTRIES);
    *found = n != -1;
    return st;
}

// One CSV line's fields, in place: every field, empty ones too (strtok would
// drop them and shift the columns). Returns how many (at most max).
static size_t gf_html_fields(char *text, char **field, size_t max)
{
    size_t n = 0;
    for (char *tok = text, *comma; tok && n < max; tok = comma ? comma + 1 : NULL) {
        comma = strchr(tok, ',');
        if (comma) *comma = '\0';
        field[n++] = tok;
    }
    return n;
}

gf_status gf_html_csv_table(FILE *out, const char *path, size_t max_rows, bool *found)
{
    gf_textscan ts;
    gf_status st = gf_html_open_text(&ts, path, found);
    if (st != GF_OK || !*found) return st;
    fputs("<table class=\"csv\">\n", out);
    char *line;
    size_t len, row = 0;
    bool keyed = false; // a first column of keys: in words, with the unit at the end
    while (row <= max_rows && gf_textscan_next(&ts, &line, &len, &st) > 0) {
        char *text = gf_html_trim(line, false);
        if (!*text) continue; // a blank line
        char *field[GF_HTML_COLUMNS];
        size_t n = gf_html_fields(text, field, GF_HTML_COLUMNS);
        if (row == 0) keyed = !strcmp(field[0], "key");
        fputs("<tr>", out);
        for (size_t c = 0; c < n; c++) {
            if (row == 0) {
                fputs("<th>", out);
                if (keyed && c == 0) fputs("Quantity", out);
                else
                    for (const char *p = field[c]; *p; p++) { // the column's name, _ as spaces
                        char ch[2] = {*p == '_' ? ' ' : *p, '\0'};
                        gf_html_text(out, ch);
                    }
                fputs("</th>", out);
            } else if (keyed && c == 0) {
                fputs("<th>", out);
                gf_html_words(out, field[0]);
                fputs("</th>", out);
            } else {
                fputs("<td class=\"num\">", out);
                gf_html_number(out, field[c]);
                fputs("</td>", out);
            }
        }
        if (keyed) {
            if (row == 0) fputs("<th>Unit</th><th>Key</th>", out);
            else {
                fputs("<td>", out);
                gf_html_unit(out, gf_html_unit_of(field[0]));
                fputs("</td><td><code>", out);
                gf_html_text(out, field[0]);
                fputs("</code></td>", out);
            }
        }
        fputs("</tr>\n", out);
        row++;
    }
    gf_textscan_close(&ts);
    fputs("</table>\n", out);
    return st;
}

gf_status gf_html_pre_file(FILE *out, const char *path, bool *found)
{
    gf_textscan ts;
    gf_status st = gf_html_open_text(&ts, path, found);
    if (st != GF_OK || !*found) return st;
    fputs("<pre>", out);
    char *line;
    size_t len;
    while (gf_textscan_next(&ts, &line, &len, &st) > 0) {
        gf_html_text(out, line);
        fputc('\n', out);
    }
    gf_textscan_close(&ts);
    fputs("</pre>\n", out);
    return st;
}
