// SPDX-License-Identifier: MIT
// analysis/summary.json: the headline numbers of gf_analyze, written and read back.
#include "analysis/summary.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/atomic_file.h"
#include "core/textscan.h"
#include "core/json.h"

gf_summary_item *gf_summary_slot(gf_summary *s, const char *key)
{
    for (size_t k = 0; k < s->n; k++)
        if (!strcmp(s->item[k].key, key)) return &s->item[k];
    if (s->n == sizeof s->item / sizeof s->item[0] || strlen(key) >= GF_TABLE_NAME) return NULL;
    gf_summary_item *it = &s->item[s->n++];
    memset(it, 0, sizeof *it);
    strcpy(it->key, key);
    return it;
}

void gf_summary_num(gf_summary *s, const char *key, double v)
{
    gf_summary_item *it = gf_summary_slot(s, key);
    if (it) {
        it->value = v;
        it->is_text = 0;
    }
}

void gf_summary_text(gf_summary *s, const char *key, const char *text)
{
    gf_summary_item *it = gf_summary_slot(s, key);
    if (!it) return;
    it->is_text = 1;
    snprintf(it->text, sizeof it->text, "%.*s", (int)sizeof it->text - 1, text);
    for (char *c = it->text; *c; c++) // keep the JSON valid whatever the message says
        if (*c == '"' || *c == '\\' || (unsigned char)*c < 0x20) *c = '\'';
}

gf_status gf_summary_read(gf_summary *s, const char *path)
{
    struct stat sb;
    if (stat(path, &sb) != 0 && errno == ENOENT) return GF_OK;
    gf_textscan ts;
    gf_status st = gf_textscan_open_regular(&ts, path, (long long)16 * 1024 * 1024);
    if (st != GF_OK) return st;
    ts.max_line = GF_TEXTSCAN_MAX_SHORT_LINE;
    char *line;
    size_t n;
    while (gf_textscan_next(&ts, &line, &n, &st) > 0) {
        char key[GF_TABLE_NAME], rest[320];
        if (sscanf(line, " \"%47[^\"]\" : %319[^\n]", key, rest) != 2) continue;
        size_t len = strlen(rest);
        while (len && (rest[len - 1] == ',' || rest[len - 1] == ' ')) rest[--len] = '\0';
        if (rest[0] == '"') {
            if (len >= 2) rest[len - 1] = '\0';
            gf_summary_text(s, key, rest + 1);
        } else if (!strcmp(rest, "null")) {
            gf_summary_num(s, key, NAN);
        } else {
            char *end;
            double v = strtod(rest, &end);
            if (end != rest) gf_summary_num(s, key, v);
        }
    }
    gf_textscan_close(&ts);
    return st;
}

gf_status gf_summary_write(const gf_summary *s, const char *path)
{
    char tmp[4096];
    FILE *f;
    gf_status st = gf_atomic_open(path, tmp, sizeof tmp, &f);
    if (st != GF_OK) return st;
    gf_json j = gf_json_start(f, true);
    gf_json_object_begin(&j, NULL);
    for (size_t k = 0; k < s->n; k++) {
        const gf_summary_item *it = &s->item[k];
        if (it->is_text) gf_json_string(&j, it->key, it->text);
        else gf_json_general(&j, it->key, it->value, 10); // null when not finite
    }
    gf_json_end(&j);
    return gf_atomic_commit(f, tmp, path);
}
