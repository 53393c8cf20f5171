// SPDX-License-Identifier: MIT
// analysis/summary.json: the headline numbers of gf_analyze, written and read back.
#include "analysis/summary.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/json.h"
#include "core/json_read.h"

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
    size_t n = strlen(text);
    if (n >= sizeof it->text) { // cut before a UTF-8 continuation byte, so that the cut text stays UTF-8
        n = sizeof it->text - 1;
        while (n > 0 && ((unsigned char)text[n] & 0xC0) == 0x80) n--;
    }
    memcpy(it->text, text, n);
    it->text[n] = '\0';
    for (char *c = it->text; *c; c++) // keep the JSON valid whatever the message says
        if (*c == '"' || *c == '\\' || (unsigned char)*c < 0x20) *c = '\'';
}

typedef struct gf_summary_reading {
    gf_summary *s;
    const char *path;
} gf_summary_reading;

static gf_status gf_summary_member(void *ctx, const gf_json_member *m)
{
    const gf_summary_reading *r = ctx;
    gf_summary *s = r->s;
    switch (m->kind) {
    case GF_JSON_STRING: gf_summary_text(s, m->key, m->text); return GF_OK;
    case GF_JSON_NULL: gf_summary_num(s, m->key, NAN); return GF_OK; // written for a number not finite
    case GF_JSON_INT:
    case GF_JSON_REAL: gf_summary_num(s, m->key, m->number); return GF_OK;
    default:
        return gf_error_set(GF_ERR_FORMAT, "%s: key '%s': a number, a string or null expected, not %s", r->path, m->key,
                            m->kind == GF_JSON_BOOL ? "true/false" : m->kind == GF_JSON_ARRAY ? "an array" : "an object");
    }
}

gf_status gf_summary_read(gf_summary *s, const char *path)
{
    if (access(path, F_OK) != 0 && errno == ENOENT) return GF_OK; // nothing measured yet
    gf_summary_reading r = {s, path};
    return gf_json_read_members(path, gf_summary_member, &r);
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
