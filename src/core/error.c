// SPDX-License-Identifier: MIT
#include "core/error.h"

#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"

// Longest message kept. Longer ones lose their middle, never their end: the
// reason comes last ("PATH: cannot write: No space left on device").
#define GF_ERR_CAP 4096

static _Thread_local char gf_errbuf[GF_ERR_CAP];

// Length of the valid UTF-8 sequence at s (1-4), or 0 if the bytes there
// are not one.
static size_t gf_utf8_len(const unsigned char *s)
{
    size_t n = s[0] >= 0xF0 && s[0] <= 0xF4 ? 4 : s[0] >= 0xE0 ? 3 : s[0] >= 0xC2 && s[0] < 0xE0 ? 2 : 0;
    if (s[0] >= 0xF8) n = 0;
    for (size_t k = 1; k < n; k++)
        if ((s[k] & 0xC0) != 0x80) return 0;
    return n;
}

size_t gf_escape(const char *in, char *out, size_t n)
{
    size_t w = 0;
#define GF_PUT_CH(c)                \
    do {                            \
        if (w + 1 < n) out[w] = (c); \
        w++;                        \
    } while (0)
    for (const unsigned char *s = (const unsigned char *)in; *s;) {
        size_t u = *s >= 0x80 ? gf_utf8_len(s) : 0;
        if (u > 0) { // valid UTF-8 (a path in Greek is not binary)
            for (size_t k = 0; k < u; k++) GF_PUT_CH((char)s[k]);
            s += u;
            continue;
        }
        if (*s >= 0x20 && *s < 0x7F) {
            GF_PUT_CH((char)*s);
        } else {
            char hex[5];
            snprintf(hex, sizeof hex, "\\x%02X", *s);
            for (int k = 0; k < 4; k++) GF_PUT_CH(hex[k]);
        }
        s++;
    }
#undef GF_PUT_CH
    if (n) out[w < n ? w : n - 1] = '\0';
    return w;
}

gf_status gf_error_set(gf_status status, const char *fmt, ...)
{
    va_list ap, ap2;
    va_start(ap, fmt);
    va_copy(ap2, ap);
    char small[GF_ERR_CAP];
    int len = vsnprintf(small, sizeof small, fmt, ap);
    va_end(ap);
    char *raw = small;
    if (len >= (int)sizeof small && (raw = gf_alloc((size_t)len + 1)) != NULL)
        vsnprintf(raw, (size_t)len + 1, fmt, ap2);
    else if (!raw)
        raw = small; // out of memory: the head of the message, cut short
    va_end(ap2);
    if (len < 0) raw[0] = '\0';
    size_t need = gf_escape(raw, NULL, 0);
    char *esc = need < GF_ERR_CAP ? NULL : gf_alloc(need + 1);
    if (!esc) {
        gf_escape(raw, gf_errbuf, sizeof gf_errbuf);
    } else {
        gf_escape(raw, esc, need + 1);
        // Head and tail, cut at character boundaries.
        size_t keep = (GF_ERR_CAP - 8) / 2, head = keep, tail = need - keep;
        while (head > 0 && ((unsigned char)esc[head] & 0xC0) == 0x80) head--;
        while (tail < need && ((unsigned char)esc[tail] & 0xC0) == 0x80) tail++;
        snprintf(gf_errbuf, sizeof gf_errbuf, "%.*s ... %s", (int)head, esc, esc + tail);
        gf_free(esc, need + 1);
    }
    if (raw != small) gf_free(raw, (size_t)len + 1);
    return status;
}

void gf_error_clear(void) { gf_errbuf[0] = '\0'; }

const char *gf_last_error(void) { return gf_errbuf; }

const char *gf_status_str(gf_status status)
{
    switch (status) {
    case GF_OK: return "ok";
    case GF_ERR_PARAM: return "invalid parameter";
    case GF_ERR_IO: return "i/o error";
    case GF_ERR_FORMAT: return "malformed data";
    case GF_ERR_NOMEM: return "out of memory";
    case GF_ERR_STATE: return "invalid state";
    case GF_ERR_INTERRUPTED: return "interrupted";
    case GF_ERR_EXISTS: return "output exists";
    }
    return "unknown status";
}

const char *gf_version(void) { return GF_VERSION_STRING; }
