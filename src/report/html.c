// SPDX-License-Identifier: MIT
#include "report/html.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "core/json_read.h"

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
    FILE *f = fopen(path, "rb");
    if (!f) return gf_error_set(GF_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    unsigned char in[3 * 4096];
    char enc[4 * 4096];
    size_t n;
    // Whole groups of 3 bytes per chunk, so only the file's end needs padding.
    while ((n = fread(in, 1, sizeof in, f)) > 0) {
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
    int err = ferror(f);
    fclose(f);
    return err ? gf_error_set(GF_ERR_IO, "%s: read error", path) : GF_OK;
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

typedef struct gf_html_kv {
    FILE *out;
    bool open; // <table> written
} gf_html_kv;

static gf_status gf_html_json_row(void *ctx, const gf_json_member *m)
{
    gf_html_kv *t = ctx;
    if (!t->open) fputs("<table class=\"kv\">\n", t->out);
    t->open = true;
    fputs("<tr><th>", t->out);
    gf_html_text(t->out, m->key);
    fputs("</th><td>", t->out);
    char num[64];
    switch (m->kind) {
    case GF_JSON_NULL: fputs("—", t->out); break; // a number that was not finite
    case GF_JSON_BOOL: fputs(m->number != 0 ? "true" : "false", t->out); break;
    case GF_JSON_INT:
        snprintf(num, sizeof num, "%lld", m->integer);
        fputs(num, t->out);
        break;
    case GF_JSON_REAL: // summary.json's numbers have at most 10 significant digits
        snprintf(num, sizeof num, "%.10g", m->number);
        fputs(num, t->out);
        break;
    default: gf_html_text(t->out, m->text); break; // a string; an array or object as compact JSON
    }
    fputs("</td></tr>\n", t->out);
    return GF_OK;
}

gf_status gf_html_json_table(FILE *out, const char *path)
{
    gf_html_kv t = {out, false};
    gf_status st = gf_json_read_members(path, gf_html_json_row, &t);
    if (st != GF_OK) return st; // jansson reads the whole file first: nothing written
    fputs(t.open ? "</table>\n" : "<table class=\"kv\">\n</table>\n", out);
    return GF_OK;
}

bool gf_html_csv_table(FILE *out, const char *path, size_t max_rows)
{
    FILE *f = fopen(path, "r");
    if (!f) return false;
    fputs("<table class=\"csv\">\n", out);
    char *line = NULL;
    size_t cap = 0, row = 0;
    while (gf_getline(&line, &cap, f) > 0 && row <= max_rows) {
        const char *cell = row == 0 ? "th" : "td";
        char *text = gf_html_trim(line, false);
        if (!*text) continue; // a blank line
        fputs("<tr>", out);
        // Every field, empty ones too (strtok would drop them and shift the columns).
        for (char *tok = text, *comma; tok; tok = comma ? comma + 1 : NULL) {
            comma = strchr(tok, ',');
            if (comma) *comma = '\0';
            fprintf(out, "<%s>", cell);
            gf_html_text(out, tok);
            fprintf(out, "</%s>", cell);
        }
        fputs("</tr>\n", out);
        row++;
    }
    gf_free(line, cap);
    fclose(f);
    fputs("</table>\n", out);
    return true;
}

bool gf_html_pre_file(FILE *out, const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) return false;
    fputs("<pre>", out);
    char *line = NULL;
    size_t cap = 0;
    while (gf_getline(&line, &cap, f) > 0) gf_html_text(out, line);
    gf_free(line, cap);
    fclose(f);
    fputs("</pre>\n", out);
    return true;
}
