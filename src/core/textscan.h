// SPDX-License-Identifier: MIT
// Internal: THE line reader of the library (every text file it reads: packings,
// snapshots, exits.csv, config files, summary.json, the tables of a report).
// One growing buffer, no allocation per line, \n or \r\n endings, line
// numbers and byte offsets so a reader can come back to a line, and
// in-place whitespace tokenising. Every line has a cap (a file with no line
// end, such as /dev/zero, is an error naming the file and line, never a
// buffer that grows until memory runs out), and running out of memory is an
// error, never the end of the file.
// Files are read through zlib's gzread, so a gzip-compressed file (any name)
// reads as its plain text and a plain file reads unchanged.
#ifndef GF_CORE_TEXTSCAN_H
#define GF_CORE_TEXTSCAN_H

#include <stddef.h>
#include <stdio.h>
#include <zlib.h>

#include "granflow/core.h"

/// A file being read line by line. Fields are private to textscan.c except
/// `path` and `line`, which error messages use.
typedef struct gf_textscan {
    gzFile f;
    const char *path;   ///< as given to gf_textscan_open (not copied)
    char *buf;          ///< gf_alloc'd; the current line lives here
    size_t cap;         ///< bytes allocated for buf
    size_t beg, end;    ///< unread bytes are buf[beg, end)
    long long base;     ///< file offset of buf[0]
    long long line_off; ///< file offset of the line last returned
    long line;          ///< 1-based number of the line last returned (0 before the first)
    int eof;            ///< gzread has reached the end of the file
    int partial;        ///< the line last returned had no newline (a cut-off last line?)
    int seekable;       ///< gf_textscan_seek can be used (regular file)
    int gz;             ///< the file is gzip-compressed (not read transparently)
    size_t max_line;    ///< longest line accepted, bytes (GF_TEXTSCAN_MAX_LINE; a caller may lower it after open)
} gf_textscan;

/// Longest line of a data file by default: longer means a binary or broken file.
#define GF_TEXTSCAN_MAX_LINE ((size_t)64 * 1024 * 1024)
/// Longest line of the small text files granflow writes and reads back
/// (config files, summary.json, CSV tables): theirs are below 1 kB.
#define GF_TEXTSCAN_MAX_SHORT_LINE ((size_t)64 * 1024)

/// Opens `path` for reading, plain or gzip-compressed (detected from the
/// content). GF_ERR_IO ("cannot open <path>: <strerror>") on failure. A
/// truncated or corrupt gzip stream is reported by gf_textscan_next as
/// GF_ERR_FORMAT naming the file and line.
gf_status gf_textscan_open(gf_textscan *ts, const char *path);

/// gf_textscan_open for a file that must be a regular one of at most
/// `max_bytes` bytes on disk (0: any size): a FIFO, device or directory is
/// refused without blocking on it (gf_fs_open_regular). For files a run or
/// analysis wrote, which a link to /dev/zero or a FIFO would make endless.
gf_status gf_textscan_open_regular(gf_textscan *ts, const char *path, long long max_bytes);

/// Closes the file and frees the buffer (safe on a zeroed or closed scanner).
void gf_textscan_close(gf_textscan *ts);

/// Reads the next line into *line (NUL-terminated, without its \n or \r\n;
/// valid until the next call, and the caller may modify it in place).
/// Returns 1 for a line, 0 at the end of the file, or -1 on failure with the
/// last error set, naming the file and line (GF_ERR_IO for a read error,
/// GF_ERR_NOMEM, GF_ERR_FORMAT for a line longer than ts->max_line or bad
/// gzip data); *st gets the status.
int gf_textscan_next(gf_textscan *ts, char **line, size_t *len, gf_status *st);

/// Repositions at a line start recorded earlier from `line_off`, so that the
/// next gf_textscan_next returns that line with number `line_no`.
gf_status gf_textscan_seek(gf_textscan *ts, long long offset, long line_no);

/// Whether the file name `name` ends in `ext` (e.g. ".dump"), or in `ext`
/// followed by ".gz" (ignoring case).
int gf_textscan_has_ext(const char *name, const char *ext);

/// Splits `s` at blanks (space, tab, \r, \v, \f) in place. Stores up to `max`
/// token pointers in tok and returns the total number of tokens (which may
/// exceed max; the tail is then left unsplit).
size_t gf_textscan_split(char *s, char **tok, size_t max);

/// Number of blank-separated tokens in `s`, without modifying it.
size_t gf_textscan_count(const char *s);

/// Pointer to the first non-blank character of `s`.
const char *gf_textscan_skip_blank(const char *s);

/// Parses a whole token as a double (strtod). 0 on success, -1 when the token
/// is not a number, -2 when it is one but not finite (nan, inf, overflow).
int gf_textscan_double(const char *tok, double *v);

/// Parses a whole token as a decimal integer (strtoll). 0 on success, -1 otherwise.
int gf_textscan_int(const char *tok, long long *v);

#endif
