// SPDX-License-Identifier: MIT
#include "core/textscan.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include "core/alloc.h"
#include "core/error.h"
#include "core/fs.h"

enum {
    GF_TEXTSCAN_CHUNK = 1 << 16, // bytes per gzread
};

// The rest of an open: ts->f and ts->path are set.
static gf_status gf_textscan_start(gf_textscan *ts)
{
    const char *path = ts->path;
    struct stat sb;
    ts->max_line = GF_TEXTSCAN_MAX_LINE;
    ts->cap = 2 * (size_t)GF_TEXTSCAN_CHUNK;
    ts->buf = gf_alloc(ts->cap);
    if (!ts->buf) {
        gzclose(ts->f);
        ts->f = NULL;
        return gf_error_set(GF_ERR_NOMEM, "out of memory reading %s", path);
    }
    gzbuffer(ts->f, GF_TEXTSCAN_CHUNK);
    // gzseek rewinds and decompresses forward in a compressed file: slower
    // than a plain seek, but correct, and readers seek back at most once.
    ts->seekable = stat(path, &sb) == 0 && S_ISREG(sb.st_mode);
    ts->gz = !gzdirect(ts->f);
    return GF_OK;
}

gf_status gf_textscan_open(gf_textscan *ts, const char *path)
{
    memset(ts, 0, sizeof *ts);
    ts->path = path;
    errno = 0;
    ts->f = gzopen(path, "rb");
    if (!ts->f)
        return gf_error_set(errno && errno != ENOMEM ? GF_ERR_IO : GF_ERR_NOMEM, "cannot open %s: %s", path,
                            errno ? strerror(errno) : "out of memory");
    return gf_textscan_start(ts);
}

gf_status gf_textscan_open_regular(gf_textscan *ts, const char *path, long long max_bytes)
{
    memset(ts, 0, sizeof *ts);
    ts->path = path;
    int fd;
    gf_status st = gf_fs_open_regular(path, max_bytes, &fd);
    if (st != GF_OK) return st;
    errno = 0;
    ts->f = gzdopen(fd, "rb");
    if (!ts->f) {
        close(fd);
        return gf_error_set(GF_ERR_NOMEM, "cannot read %s: out of memory", path);
    }
    return gf_textscan_start(ts);
}

void gf_textscan_close(gf_textscan *ts)
{
    if (ts->f) gzclose(ts->f);
    gf_free(ts->buf, ts->cap);
    ts->f = NULL;
    ts->buf = NULL;
    ts->cap = 0;
}

// Whether `path` is gzip members and nothing else: zlib's gzread ignores
// bytes after the last member that do not start another one (issue 26: a .gz
// with trailing garbage was accepted). Decompresses the file once more, into
// nothing, and returns the raw offset of such bytes, or -1 when there are
// none (or the file cannot be read here: gzread reports that itself).
static long long gf_textscan_garbage_at(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return -1;
    z_stream z;
    memset(&z, 0, sizeof z);
    if (inflateInit2(&z, 16 + MAX_WBITS) != Z_OK) {
        fclose(f);
        return -1;
    }
    enum { GF_GZ_IN = 1 << 16 };
    unsigned char *in = gf_alloc(GF_GZ_IN), out[1 << 14];
    if (!in) {
        inflateEnd(&z);
        fclose(f);
        return -1;
    }
    long long consumed = 0, at = -1;
    bool done = false;
    while (!done) {
        if (z.avail_in == 0) {
            size_t got = fread(in, 1, GF_GZ_IN, f);
            if (got == 0) break; // the end of the file at a member's end or inside one
            z.next_in = in;
            z.avail_in = (uInt)got;
        }
        z.next_out = out;
        z.avail_out = sizeof out;
        uInt before = z.avail_in;
        int rc = inflate(&z, Z_NO_FLUSH);
        consumed += before - z.avail_in;
        if (rc == Z_STREAM_END) {
            // Another member must follow, or nothing at all.
            if (z.avail_in == 0) {
                size_t got = fread(in, 1, GF_GZ_IN, f);
                if (got == 0) break;
                z.next_in = in;
                z.avail_in = (uInt)got;
            }
            if (z.avail_in >= 1 && z.next_in[0] != 0x1f) at = consumed;
            else if (z.avail_in >= 2 && z.next_in[1] != 0x8b) at = consumed;
            if (at >= 0) break;
            inflateReset(&z);
        } else if (rc != Z_OK && rc != Z_BUF_ERROR) {
            done = true; // corrupt data: gzread says so
        }
    }
    inflateEnd(&z);
    gf_free(in, GF_GZ_IN);
    fclose(f);
    return at;
}

// At the end of a gzip file's data (`total` bytes): its trailer's ISIZE
// (the last 4 bytes, little-endian) is that size mod 2^32 for a file of one
// member, the common case, checked at the cost of a read; otherwise the file
// is read again for bytes after its members.
static gf_status gf_textscan_check_trailer(const gf_textscan *ts, long long total)
{
    FILE *f = fopen(ts->path, "rb");
    if (!f) return GF_OK; // not a file we can reopen (gzread reads it): nothing to check
    unsigned char t[4];
    bool same = fseek(f, -4, SEEK_END) == 0 && fread(t, 1, 4, f) == 4 &&
                ((uint32_t)t[0] | (uint32_t)t[1] << 8 | (uint32_t)t[2] << 16 | (uint32_t)t[3] << 24) ==
                    (uint32_t)(unsigned long long)total;
    fclose(f);
    if (same) return GF_OK;
    long long at = gf_textscan_garbage_at(ts->path);
    if (at < 0) return GF_OK; // several members, and nothing after them
    return gf_error_set(GF_ERR_FORMAT,
                        "%s: bytes after the end of the gzip data, from byte %lld of the file (appended to it, or "
                        "not one gzip file?)",
                        ts->path, at);
}

// Refills: moves the unread tail to the front, grows the buffer when a single
// line fills it, then reads one more chunk. Always leaves room for a NUL.
static gf_status gf_textscan_fill(gf_textscan *ts)
{
    if (ts->beg > 0) {
        memmove(ts->buf, ts->buf + ts->beg, ts->end - ts->beg);
        ts->base += (long long)ts->beg;
        ts->end -= ts->beg;
        ts->beg = 0;
    }
    if (ts->cap - ts->end < (size_t)GF_TEXTSCAN_CHUNK + 1) {
        char *nb = gf_realloc(ts->buf, ts->cap, 2 * ts->cap);
        if (!nb) return gf_error_set(GF_ERR_NOMEM, "out of memory reading %s", ts->path);
        ts->buf = nb;
        ts->cap *= 2;
    }
    int got = gzread(ts->f, ts->buf + ts->end, GF_TEXTSCAN_CHUNK);
    if (got < 0) {
        int code;
        const char *msg = gzerror(ts->f, &code);
        if (code == Z_ERRNO)
            return gf_error_set(GF_ERR_IO, "%s:%ld: read error: %s", ts->path, ts->line + 1, strerror(errno));
        return gf_error_set(GF_ERR_FORMAT, "%s:%ld: corrupt gzip data (%s)", ts->path, ts->line + 1, msg);
    }
    ts->end += (size_t)got;
    if (got < GF_TEXTSCAN_CHUNK) {
        // gzread returns short reads only at the end; a gzip stream cut off
        // before its trailer ends with Z_BUF_ERROR ("unexpected end of file").
        // The data before the cut is whole: the line named is the one the
        // cut falls in, not the first line of this chunk (issue 26: ":1:").
        int code;
        const char *msg = gzerror(ts->f, &code);
        if (code == Z_BUF_ERROR) {
            long line = ts->line + 1;
            for (size_t k = ts->beg; k < ts->end; k++) line += ts->buf[k] == '\n';
            return gf_error_set(GF_ERR_FORMAT,
                                "%s:%ld: truncated gzip file (%s): the data stops there, after %lld bytes", ts->path,
                                line, msg, ts->base + (long long)ts->end);
        }
        if (code != Z_OK)
            return gf_error_set(GF_ERR_FORMAT, "%s:%ld: corrupt gzip data (%s)", ts->path, ts->line + 1, msg);
        if (ts->gz && ts->seekable) { // a regular file, which can be opened again (not a FIFO)
            gf_status st = gf_textscan_check_trailer(ts, ts->base + (long long)ts->end);
            if (st != GF_OK) return st;
        }
        ts->eof = 1;
    }
    return GF_OK;
}

int gf_textscan_next(gf_textscan *ts, char **line, size_t *len, gf_status *st)
{
    *st = GF_OK;
    size_t scanned = 0; // bytes of the current line already searched for '\n'
    for (;;) {
        char *start = ts->buf + ts->beg;
        size_t avail = ts->end - ts->beg;
        char *nl = memchr(start + scanned, '\n', avail - scanned);
        size_t n = nl ? (size_t)(nl - start) : avail; // the line, or what there is of it so far
        // The cap, checked before the buffer grows: a file without line ends
        // (/dev/zero) stops here, whatever memory there is.
        if (n > ts->max_line) {
            *st = gf_error_set(GF_ERR_FORMAT, "%s:%ld: line longer than %zu bytes (not a text file?)", ts->path,
                               ts->line + 1, ts->max_line);
            return -1;
        }
        ts->partial = !nl;
        if (nl) {
            ts->beg += n + 1;
        } else if (ts->eof) {
            if (avail == 0) return 0;
            ts->beg = ts->end; // last line without a newline
        } else {
            scanned = avail;
            *st = gf_textscan_fill(ts);
            if (*st != GF_OK) return -1;
            continue;
        }
        ts->line_off = ts->base + (long long)(start - ts->buf);
        ts->line++;
        if (n > 0 && start[n - 1] == '\r') n--;
        start[n] = '\0'; // the '\n' slot, or the spare byte fill() keeps
        *line = start;
        *len = n;
        return 1;
    }
}

gf_status gf_textscan_seek(gf_textscan *ts, long long offset, long line_no)
{
    if (!ts->seekable || gzseek(ts->f, (z_off_t)offset, SEEK_SET) != (z_off_t)offset)
        return gf_error_set(GF_ERR_IO, "%s: cannot seek back to line %ld: %s", ts->path, line_no,
                            strerror(errno));
    gzclearerr(ts->f);
    ts->beg = ts->end = 0;
    ts->base = offset;
    ts->eof = 0;
    ts->line = line_no - 1;
    return GF_OK;
}

int gf_textscan_has_ext(const char *name, const char *ext)
{
    size_t n = strlen(name), k = strlen(ext);
    if (n > k + 3 && strcasecmp(name + n - 3, ".gz") == 0) n -= 3;
    return n > k && strncasecmp(name + n - k, ext, k) == 0;
}

static int gf_textscan_is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

const char *gf_textscan_skip_blank(const char *s)
{
    while (gf_textscan_is_blank(*s)) s++;
    return s;
}

size_t gf_textscan_split(char *s, char **tok, size_t max)
{
    size_t n = 0;
    for (;;) {
        while (gf_textscan_is_blank(*s)) s++;
        if (!*s) return n;
        if (n == max) return n + gf_textscan_count(s);
        tok[n++] = s;
        while (*s && !gf_textscan_is_blank(*s)) s++;
        if (!*s) return n;
        *s++ = '\0';
    }
}

size_t gf_textscan_count(const char *s)
{
    size_t n = 0;
    for (;;) {
        while (gf_textscan_is_blank(*s)) s++;
        if (!*s) return n;
        n++;
        while (*s && !gf_textscan_is_blank(*s)) s++;
    }
}

int gf_textscan_double(const char *tok, double *v)
{
    char *end;
    if (!*tok) return -1;
    *v = strtod(tok, &end);
    if (end == tok || *end != '\0') return -1;
    if (!isfinite(*v)) return -2;
    return 0;
}

int gf_textscan_int(const char *tok, long long *v)
{
    char *end;
    if (!*tok) return -1;
    errno = 0;
    *v = strtoll(tok, &end, 10);
    if (end == tok || *end != '\0' || errno == ERANGE) return -1;
    return 0;
}
