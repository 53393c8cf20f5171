// SPDX-License-Identifier: MIT
#include "report/html.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/alloc.h"
#include "core/error.h"
#include "core/fs.h"
#include "core/textscan.h"

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
    gf_textscan ts;
    gf_status st = gf_html_open_text(&ts, path, found);
    if (st != GF_OK || !*found) return st;
    fputs("<table class=\"kv\">\n", out);
    char *line;
    size_t len;
    while (gf_textscan_next(&ts, &line, &len, &st) > 0) {
        char *colon = strstr(line, "\":");
        if (!colon) continue; // the braces
        colon[1] = '\0';
        char *key = gf_html_trim(line, true), *value = gf_html_trim(colon + 2, true);
        fputs("<tr><th>", out);
        gf_html_text(out, key);
        fputs("</th><td>", out);
        gf_html_text(out, strcmp(value, "null") ? value : "—");
        fputs("</td></tr>\n", out);
    }
    gf_textscan_close(&ts);
    fputs("</table>\n", out);
    return st;
}

gf_status gf_html_csv_table(FILE *out, const char *path, size_t max_rows, bool *found)
{
    gf_textscan ts;
    gf_status st = gf_html_open_text(&ts, path, found);
    if (st != GF_OK || !*found) return st;
    fputs("<table class=\"csv\">\n", out);
    char *line;
    size_t len, row = 0;
    while (row <= max_rows && gf_textscan_next(&ts, &line, &len, &st) > 0) {
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
