// SPDX-License-Identifier: MIT
// On resume, the configuration text a checkpoint stores is compared with the
// one this run would store, setting by setting (checkpoint.c calls it).
//
// The comparison is by (section, key), not by position: comments and blank
// lines are skipped (a key's documentation may change between versions
// without stranding checkpoints), and a key this version has that the stored
// text does not list, wherever it is missing (start, middle, end, a whole
// section), is accepted when its value here is its default (an older version
// without the key behaved as the default does), else refused by name. A key
// the stored text lists twice, or that this version does not know (a newer
// version's checkpoint), is refused by name too. The stored text comes from
// the file: it is walked as bytes, with no assumption about its lines.
#include <stdbool.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "spot/sim_internal.h"

/// One setting line of a configuration text, with the section it is in.
typedef struct gf_ckpt_line {
    const char *sec, *line;
    size_t seclen, len, keylen;
    bool seen; ///< listed by the stored text
} gf_ckpt_line;

typedef struct gf_ckpt_lines {
    gf_ckpt_line *v;
    size_t n, cap;
} gf_ckpt_lines;

/// A text being walked: the next setting line and the section it is in.
typedef struct gf_ckpt_walk {
    const char *p, *end;
    const char *sec;
    size_t seclen;
} gf_ckpt_walk;

// The next setting line (a key = value; [section] lines only change w->sec)
// past comments and blank lines, in *out; false at the end of the text.
static bool gf_ckpt_next(gf_ckpt_walk *w, gf_ckpt_line *out)
{
    while (w->p < w->end) {
        const char *p = w->p;
        const char *nl = memchr(p, '\n', (size_t)(w->end - p));
        size_t n = nl ? (size_t)(nl - p) : (size_t)(w->end - p);
        w->p = p + n + (nl ? 1 : 0);
        if (n == 0 || p[0] == '#' || p[0] == ';') continue;
        if (p[0] == '[') {
            w->sec = p + 1;
            w->seclen = n >= 2 && p[n - 1] == ']' ? n - 2 : n - 1;
            continue;
        }
        const char *eq = memchr(p, '=', n);
        size_t kl = eq ? (size_t)(eq - p) : n;
        while (kl > 0 && p[kl - 1] == ' ') kl--;
        *out = (gf_ckpt_line){.sec = w->sec, .seclen = w->seclen, .line = p, .len = n, .keylen = kl};
        return true;
    }
    return false;
}

// Every setting line of a text this version wrote (a few hundred at most).
static gf_status gf_ckpt_lines_of(const char *text, size_t len, gf_ckpt_lines *out)
{
    gf_ckpt_walk w = {text, text + len, "", 0};
    gf_ckpt_line l;
    while (gf_ckpt_next(&w, &l)) {
        if (out->n == out->cap) {
            size_t cap = out->cap ? 2 * out->cap : 256;
            gf_ckpt_line *v = gf_realloc(out->v, out->cap * sizeof *v, cap * sizeof *v);
            if (!v) return gf_error_set(GF_ERR_NOMEM, "out of memory");
            out->v = v;
            out->cap = cap;
        }
        out->v[out->n++] = l;
    }
    return GF_OK;
}

static void gf_ckpt_lines_free(gf_ckpt_lines *l) { gf_free(l->v, l->cap * sizeof *l->v); }

// The line of `set` with the section and key of `l`, or NULL.
static gf_ckpt_line *gf_ckpt_find(const gf_ckpt_lines *set, const gf_ckpt_line *l)
{
    for (size_t i = 0; i < set->n; i++) {
        gf_ckpt_line *s = &set->v[i];
        if (s->seclen == l->seclen && s->keylen == l->keylen && !memcmp(s->sec, l->sec, l->seclen) &&
            !memcmp(s->line, l->line, l->keylen))
            return s;
    }
    return NULL;
}

// The value of a setting line: what follows its '=' and the spaces after it.
static const char *gf_ckpt_value(const gf_ckpt_line *l, size_t *len)
{
    const char *eq = memchr(l->line, '=', l->len);
    size_t at = eq ? (size_t)(eq - l->line) + 1 : l->len;
    while (at < l->len && l->line[at] == ' ') at++;
    *len = l->len - at;
    return l->line + at;
}

#define GF_CKPT_RESUMABLE \
    "(on resume only run.duration, run.checkpoint_interval, run.stall_time and run.threads may change)"

gf_status gf_ckpt_compare_settings(const char *path, const char *stored, size_t slen, const char *mine, size_t mlen,
                                   const char *def, size_t dlen)
{
    gf_ckpt_lines m = {0}, d = {0};
    gf_status st = gf_ckpt_lines_of(mine, mlen, &m);
    if (st == GF_OK) st = gf_ckpt_lines_of(def, dlen, &d);
    gf_ckpt_walk w = {stored, stored + slen, "", 0};
    gf_ckpt_line s;
    // Names from the file are cut to 64 bytes; gf_error_set escapes their bytes.
    while (st == GF_OK && gf_ckpt_next(&w, &s)) {
        const int sl = (int)(s.seclen < 64 ? s.seclen : 64), kl = (int)(s.keylen < 64 ? s.keylen : 64);
        gf_ckpt_line *a = gf_ckpt_find(&m, &s);
        if (!a)
            st = gf_error_set(GF_ERR_PARAM,
                              "%s: the checkpoint's configuration has the key %.*s.%.*s, which this granflow does not "
                              "know (a checkpoint of a newer version?)",
                              path, sl, s.sec, kl, s.line);
        else if (a->seen)
            st = gf_error_set(GF_ERR_FORMAT, "%s: the checkpoint's configuration lists %.*s.%.*s twice", path, sl,
                              s.sec, kl, s.line);
        if (st != GF_OK) break;
        a->seen = true;
        if (a->len != s.len || memcmp(a->line, s.line, s.len) != 0)
            st = gf_error_set(GF_ERR_PARAM,
                              "%s: %.*s.%.*s differs from the configuration the checkpoint was made with "
                              GF_CKPT_RESUMABLE,
                              path, sl, s.sec, kl, s.line);
    }
    // This version's keys the checkpoint does not list: the older version that
    // wrote it ran them at their defaults.
    for (size_t i = 0; st == GF_OK && i < m.n; i++) {
        const gf_ckpt_line *a = &m.v[i];
        if (a->seen) continue;
        const gf_ckpt_line *b = gf_ckpt_find(&d, a);
        if (b && b->len == a->len && !memcmp(b->line, a->line, a->len)) continue;
        size_t al, bl;
        const char *av = gf_ckpt_value(a, &al), *bv = b ? gf_ckpt_value(b, &bl) : (bl = 0, "");
        st = gf_error_set(GF_ERR_PARAM,
                          "%s: %.*s.%.*s differs from the configuration the checkpoint was made with: the checkpoint "
                          "does not list it (a version without the key made it, and ran at the default, %.*s), and "
                          "here it is %.*s " GF_CKPT_RESUMABLE,
                          path, (int)a->seclen, a->sec, (int)a->keylen, a->line, (int)bl, bv, (int)al, av);
    }
    gf_ckpt_lines_free(&m);
    gf_ckpt_lines_free(&d);
    return st;
}
