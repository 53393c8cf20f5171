// SPDX-License-Identifier: MIT
// gf_packing_read: LAMMPS text dumps (last frame, any column order), XYZ, CSV.
//
// LAMMPS dumps are read in two passes so that a 100-frame pour costs little
// more than its last frame: the first pass checks the structure of every frame
// (sections present, atom counts, columns per line) without converting
// numbers, and remembers where the last complete frame's ITEM: ATOMS line
// starts; the second pass seeks back there and converts that frame only.
// Files that cannot seek (pipes) are converted frame by frame in one pass.
//
// gf_packing_read_frames (io/packing_frames.h) uses the same reader in that
// one-pass mode and hands every frame over, with its TIME and the `type`
// column; gf_packing_read itself ignores both, as it always has.
#include "granflow/particles.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/alloc.h"
#include "core/error.h"
#include "io/packing_frames.h"
#include "core/textscan.h"

enum {
    GF_READ_MAX_COLS = 256,     // columns per line we accept (LAMMPS dumps have ~5-20)
    GF_READ_MAX_HINT = 1 << 16, // most particles reserved up front on an unverified count (more grow as read:
                                // a 1 M reserve per frame made hostile counts cost ~100 MB each, issue 26 fuzzing)
};

// ---------------------------------------------------------------------------
// Ids seen in the frame being converted, with the line of each (open
// addressing, linear probing, key 0 = empty since ids are positive).

typedef struct gf_idset {
    int64_t *key;
    long *line;
    size_t cap; // power of two
    size_t used;
} gf_idset;

static void gf_idset_free(gf_idset *s)
{
    GF_DELETE(s->key, s->cap);
    GF_DELETE(s->line, s->cap);
    memset(s, 0, sizeof *s);
}

static gf_status gf_idset_alloc(gf_idset *s, size_t cap)
{
    s->key = GF_NEW(int64_t, cap);
    s->line = GF_NEW(long, cap);
    s->cap = cap;
    s->used = 0;
    if (!s->key || !s->line) {
        gf_idset_free(s);
        return gf_error_set(GF_ERR_NOMEM, "out of memory for the particle id table");
    }
    return GF_OK;
}

/// Empties the set and makes room for about n ids.
static gf_status gf_idset_reset(gf_idset *s, size_t n)
{
    size_t want = 64;
    while (want < 2 * n) want <<= 1;
    if (want <= s->cap) {
        memset(s->key, 0, sizeof *s->key * s->cap);
        s->used = 0;
        return GF_OK;
    }
    gf_idset_free(s);
    return gf_idset_alloc(s, want);
}

static size_t gf_idset_slot(const gf_idset *s, int64_t id)
{
    uint64_t h = (uint64_t)id * 0x9E3779B97F4A7C15u;
    h ^= h >> 29;
    size_t i = (size_t)h & (s->cap - 1);
    while (s->key[i] != 0 && s->key[i] != id) i = (i + 1) & (s->cap - 1);
    return i;
}

/// Adds id (seen on `line`). Returns GF_OK, or GF_ERR_NOMEM; *first is the
/// line where the id was seen before, or 0 when it is new.
static gf_status gf_idset_add(gf_idset *s, int64_t id, long line, long *first)
{
    *first = 0;
    if (2 * (s->used + 1) > s->cap) {
        gf_idset old = *s;
        gf_status st = gf_idset_alloc(s, old.cap ? 2 * old.cap : 64);
        if (st != GF_OK) {
            *s = old;
            return st;
        }
        for (size_t j = 0; j < old.cap; j++) {
            if (!old.key[j]) continue;
            size_t i = gf_idset_slot(s, old.key[j]);
            s->key[i] = old.key[j];
            s->line[i] = old.line[j];
            s->used++;
        }
        gf_idset_free(&old);
    }
    size_t i = gf_idset_slot(s, id);
    if (s->key[i] == id) {
        *first = s->line[i];
        return GF_OK;
    }
    s->key[i] = id;
    s->line[i] = line;
    s->used++;
    return GF_OK;
}

// ---------------------------------------------------------------------------
// Column layout and row conversion, shared by the three formats.

typedef struct gf_columns {
    int ncols;  // fields every row must have
    int pos[3]; // columns of x, y, z (or their scaled forms)
    const char *pos_name[3];
    int scaled;               // positions are fractions of the box (xs ys zs, xsu ysu zsu)
    int id, radius, diameter; // column index or -1
    int type;                 // LAMMPS `type` column or -1 (read only by gf_packing_read_frames)
    int pass;                 // granflow's `pass` column (recirculation) or -1 (gf_packing_read_frames_pass only)
    const char *radius_name, *diameter_name;
} gf_columns;

typedef struct gf_reader {
    gf_textscan ts;
    gf_packing *out;
    gf_idset ids;
    gf_packing_frame_fn each; // non-NULL: convert every frame, read TIME and type, call this
    void *each_ctx;
    int64_t find_id;          // > 0: note the line of the particle with this id
    long found_line;          // its line in the last frame converted, 0: not seen
    int want_pass;            // with `each`: read granflow's pass column (gf_packing_read_frames_pass)
    int32_t *pass;            // its values in the frame being converted
    size_t pass_cap;
    double unit;              // the file's length unit is this many d: lengths read are divided by it (0: 1)
    gf_packing_keep_fn keep;  // non-NULL: only the rows it keeps are appended (gf_packing_read_where)
    void *keep_ctx;
    size_t rows;              // rows of the frame converted so far, kept or not
} gf_reader;

static gf_status gf_read_bad_number(const gf_textscan *ts, const char *col, const char *tok,
                                    int code)
{
    return gf_error_set(GF_ERR_FORMAT, "%s:%ld: column '%s': '%.64s' is not a %snumber", ts->path,
                        ts->line, col, tok, code == -2 ? "finite " : "");
}

/// Converts one row (tokens already split) and appends the particle.
/// lo/hi: box bounds, used only for scaled positions.
static gf_status gf_read_row(gf_reader *rd, const gf_columns *c, char **tok, const double *lo,
                             const double *hi)
{
    const gf_textscan *ts = &rd->ts;
    double v[3];
    for (int k = 0; k < 3; k++) {
        int code = gf_textscan_double(tok[c->pos[k]], &v[k]);
        if (code) return gf_read_bad_number(ts, c->pos_name[k], tok[c->pos[k]], code);
        if (c->scaled) v[k] = lo[k] + v[k] * (hi[k] - lo[k]);
        if (rd->unit > 0) v[k] /= rd->unit;
    }
    double r = 0.5;
    if (c->radius >= 0 || c->diameter >= 0) {
        int col = c->radius >= 0 ? c->radius : c->diameter;
        const char *name = c->radius >= 0 ? c->radius_name : c->diameter_name;
        int code = gf_textscan_double(tok[col], &r);
        if (code) return gf_read_bad_number(ts, name, tok[col], code);
        if (!(r > 0))
            return gf_error_set(GF_ERR_FORMAT,
                                "%s:%ld: column '%s': %s must be positive, got '%.64s'", ts->path,
                                ts->line, name, c->radius >= 0 ? "radius" : "diameter", tok[col]);
        if (c->radius < 0) r *= 0.5;
        if (rd->unit > 0) r /= rd->unit; // a radius without a column is 0.5 d whatever the unit
    }
    // Without an id column, id k is the k-th row, whichever rows are kept.
    int64_t id = (int64_t)rd->rows + 1;
    rd->rows++;
    // A row not kept is not checked further (its id is not in the table:
    // a rank reading its region of a packing checks the ids of that region).
    if (rd->keep && !rd->keep(rd->keep_ctx, v, r)) return GF_OK;
    if (c->id >= 0) {
        long long t;
        if (gf_textscan_int(tok[c->id], &t) != 0)
            return gf_error_set(GF_ERR_FORMAT, "%s:%ld: column 'id': '%.64s' is not an integer",
                                ts->path, ts->line, tok[c->id]);
        if (t <= 0)
            return gf_error_set(GF_ERR_FORMAT, "%s:%ld: id %lld is not positive (ids must be >= 1)",
                                ts->path, ts->line, t);
        long first;
        gf_status st = gf_idset_add(&rd->ids, (int64_t)t, ts->line, &first);
        if (st != GF_OK) return st;
        if (first)
            return gf_error_set(GF_ERR_FORMAT, "%s:%ld: duplicate id %lld (already on line %ld)",
                                ts->path, ts->line, t, first);
        id = (int64_t)t;
    }
    if (rd->find_id > 0 && id == rd->find_id) rd->found_line = ts->line;
    int32_t layer = 0;
    if (rd->each && c->type >= 0) {
        long long t;
        if (gf_textscan_int(tok[c->type], &t) != 0 || t < INT32_MIN || t > INT32_MAX)
            return gf_error_set(GF_ERR_FORMAT, "%s:%ld: column 'type': '%.64s' is not an integer",
                                ts->path, ts->line, tok[c->type]);
        layer = (int32_t)t;
    }
    if (rd->want_pass && c->pass >= 0) {
        long long t;
        if (gf_textscan_int(tok[c->pass], &t) != 0 || t < 1 || t > INT32_MAX)
            return gf_error_set(GF_ERR_FORMAT, "%s:%ld: column 'pass': '%.64s' is not a positive integer",
                                ts->path, ts->line, tok[c->pass]);
        size_t i = rd->out->n;
        if (i >= rd->pass_cap) {
            size_t cap = rd->pass_cap ? 2 * rd->pass_cap : 1024;
            int32_t *grown = GF_NEW(int32_t, cap);
            if (!grown) return gf_error_set(GF_ERR_NOMEM, "out of memory for the pass column");
            if (rd->pass) memcpy(grown, rd->pass, sizeof *grown * i);
            GF_DELETE(rd->pass, rd->pass_cap);
            rd->pass = grown;
            rd->pass_cap = cap;
        }
        rd->pass[i] = (int32_t)t;
    }
    return gf_packing_push(rd->out, id, layer, v[0], v[1], v[2], r);
}

/// Finds the position, id and radius columns among `names`. With `lammps`,
/// unwrapped and scaled positions count too. Returns 0, or -1 without x/y/z.
static int gf_columns_resolve(gf_columns *c, char **names, int n, int lammps)
{
    static const char *const triples[4][3] = {
        {"x", "y", "z"}, {"xu", "yu", "zu"}, {"xs", "ys", "zs"}, {"xsu", "ysu", "zsu"}};
    memset(c, 0, sizeof *c);
    c->ncols = n;
    c->id = c->radius = c->diameter = c->type = c->pass = -1;
    int found = 0;
    for (int t = 0; t < (lammps ? 4 : 1) && !found; t++) {
        int idx[3] = {-1, -1, -1};
        for (int k = 0; k < 3; k++)
            for (int i = 0; i < n && idx[k] < 0; i++)
                if (strcasecmp(names[i], triples[t][k]) == 0) idx[k] = i;
        if (idx[0] >= 0 && idx[1] >= 0 && idx[2] >= 0) {
            for (int k = 0; k < 3; k++) {
                c->pos[k] = idx[k];
                c->pos_name[k] = triples[t][k];
            }
            c->scaled = t >= 2;
            found = 1;
        }
    }
    for (int i = n - 1; i >= 0; i--) { // backwards: the first occurrence wins
        const char *s = names[i];
        if (strcasecmp(s, "id") == 0) {
            c->id = i;
        } else if (lammps && strcasecmp(s, "type") == 0) {
            c->type = i;
        } else if (lammps && strcasecmp(s, "pass") == 0) {
            c->pass = i;
        } else if (strcasecmp(s, "radius") == 0 || (!lammps && strcasecmp(s, "r") == 0)) {
            c->radius = i;
            c->radius_name = strcasecmp(s, "r") == 0 ? "r" : "radius";
        } else if (strcasecmp(s, "diameter") == 0 || (!lammps && strcasecmp(s, "d") == 0)) {
            c->diameter = i;
            c->diameter_name = strcasecmp(s, "d") == 0 ? "d" : "diameter";
        }
    }
    return found ? 0 : -1;
}

/// "a b c" from names, shortened to fit buf.
static const char *gf_join(char *buf, size_t size, char **names, int n, const char *sep)
{
    size_t len = 0;
    buf[0] = '\0';
    for (int i = 0; i < n; i++) {
        int w = snprintf(buf + len, size - len, "%s%s", i ? sep : "", names[i]);
        if (w < 0 || (size_t)w >= size - len) {
            if (size > 4) strcpy(buf + size - 4, "...");
            break;
        }
        len += (size_t)w;
    }
    if (n == 0) snprintf(buf, size, "none");
    return buf;
}

static int gf_is_blank_line(const char *s) { return *gf_textscan_skip_blank(s) == '\0'; }

// ---------------------------------------------------------------------------
// LAMMPS text dump.

typedef struct gf_lmp_frame {
    int started; // some section of this frame has been read
    long start_line;
    int have_ts, have_time, have_n, have_box, have_units;
    long long timestep, natoms;
    double time; // ITEM: TIME, converted only for gf_packing_read_frames
    long natoms_line;
    double lo[3], hi[3];
} gf_lmp_frame;

typedef struct gf_lmp_atoms {
    gf_lmp_frame hdr;
    gf_columns cols;
    long long off; // file offset of the ITEM: ATOMS line
    long line;     // its line number
} gf_lmp_atoms;

static const char *gf_lmp_frame_name(const gf_lmp_frame *f, char *buf, size_t size)
{
    if (f->have_ts)
        snprintf(buf, size, "frame at timestep %lld", f->timestep);
    else
        snprintf(buf, size, "frame starting on line %ld", f->start_line);
    return buf;
}

/// Reads the value line(s) of an ITEM section: the next non-blank line, which
/// must not be another ITEM.
static gf_status gf_lmp_value(gf_reader *rd, const gf_lmp_frame *f, const char *item, char **line)
{
    gf_textscan *ts = &rd->ts;
    size_t len;
    gf_status st;
    char name[64];
    for (;;) {
        int r = gf_textscan_next(ts, line, &len, &st);
        if (r < 0) return st;
        if (r == 0)
            return gf_error_set(GF_ERR_FORMAT,
                                "%s:%ld: file ends inside ITEM: %s of the %s (truncated file?)",
                                ts->path, ts->line, item, gf_lmp_frame_name(f, name, sizeof name));
        if (gf_is_blank_line(*line)) continue;
        if (strncmp(gf_textscan_skip_blank(*line), "ITEM:", 5) == 0)
            return gf_error_set(GF_ERR_FORMAT, "%s:%ld: ITEM: %s of the %s has no value", ts->path,
                                ts->line, item, gf_lmp_frame_name(f, name, sizeof name));
        return GF_OK;
    }
}

static gf_status gf_lmp_int(const gf_textscan *ts, char *line, const char *item, long long *v)
{
    char *tok[2];
    size_t n = gf_textscan_split(line, tok, 2);
    if (n != 1 || gf_textscan_int(tok[0], v) != 0 || *v < 0)
        return gf_error_set(GF_ERR_FORMAT,
                            "%s:%ld: ITEM: %s: '%.64s' is not a non-negative integer", ts->path,
                            ts->line, item, n ? tok[0] : "");
    return GF_OK;
}

static gf_status gf_lmp_box(gf_reader *rd, gf_lmp_frame *f, char *header)
{
    gf_textscan *ts = &rd->ts;
    char *tok[16];
    size_t n = gf_textscan_split(header, tok, 16);
    for (size_t i = 0; i < n && i < 16; i++)
        if (!strcmp(tok[i], "xy") || !strcmp(tok[i], "xz") || !strcmp(tok[i], "yz") ||
            !strcmp(tok[i], "abc"))
            return gf_error_set(
                GF_ERR_FORMAT,
                "%s:%ld: triclinic box (ITEM: BOX BOUNDS with '%s') is not supported: "
                "granflow needs an orthogonal box",
                ts->path, ts->line, tok[i]);
    static const char *const axis[3] = {"x", "y", "z"};
    for (int k = 0; k < 3; k++) {
        char *line;
        gf_status st = gf_lmp_value(rd, f, "BOX BOUNDS", &line);
        if (st != GF_OK) return st;
        n = gf_textscan_split(line, tok, 4);
        if (n == 3 || n == 4)
            return gf_error_set(GF_ERR_FORMAT,
                                "%s:%ld: triclinic box (%zu values on a BOX BOUNDS line) is not "
                                "supported: granflow needs an orthogonal box",
                                ts->path, ts->line, n);
        if (n != 2)
            return gf_error_set(GF_ERR_FORMAT,
                                "%s:%ld: BOX BOUNDS line for %s has %zu values, expected 'lo hi'",
                                ts->path, ts->line, axis[k], n);
        int c0 = gf_textscan_double(tok[0], &f->lo[k]);
        if (c0) return gf_read_bad_number(ts, k == 0 ? "xlo" : k == 1 ? "ylo" : "zlo", tok[0], c0);
        int c1 = gf_textscan_double(tok[1], &f->hi[k]);
        if (c1) return gf_read_bad_number(ts, k == 0 ? "xhi" : k == 1 ? "yhi" : "zhi", tok[1], c1);
    }
    f->have_box = 1;
    return GF_OK;
}

/// Reads the ITEM: ATOMS header (already in `line`): resolves the columns.
static gf_status gf_lmp_atoms_header(gf_reader *rd, const gf_lmp_frame *f, char *cols_text,
                                     gf_columns *cols)
{
    gf_textscan *ts = &rd->ts;
    char name[64];
    if (!f->have_n)
        return gf_error_set(GF_ERR_FORMAT,
                            "%s:%ld: ITEM: ATOMS without ITEM: NUMBER OF ATOMS in the %s", ts->path,
                            ts->line, gf_lmp_frame_name(f, name, sizeof name));
    if (!f->have_ts)
        return gf_error_set(GF_ERR_FORMAT, "%s:%ld: ITEM: ATOMS without ITEM: TIMESTEP in the %s",
                            ts->path, ts->line, gf_lmp_frame_name(f, name, sizeof name));
    char *tok[GF_READ_MAX_COLS];
    size_t n = gf_textscan_split(cols_text, tok, GF_READ_MAX_COLS);
    if (n > GF_READ_MAX_COLS)
        return gf_error_set(GF_ERR_FORMAT,
                            "%s:%ld: ITEM: ATOMS names %zu columns (at most %d supported)",
                            ts->path, ts->line, n, GF_READ_MAX_COLS);
    if (gf_columns_resolve(cols, tok, (int)n, 1) != 0) {
        char list[400];
        return gf_error_set(GF_ERR_FORMAT,
                            "%s:%ld: ITEM: ATOMS has no x y z (or xu yu zu, xs ys zs, xsu ysu zsu) "
                            "columns; found: %s",
                            ts->path, ts->line, gf_join(list, sizeof list, tok, (int)n, " "));
    }
    if (cols->scaled && !f->have_box)
        return gf_error_set(
            GF_ERR_FORMAT, "%s:%ld: scaled coordinates (%s) but no ITEM: BOX BOUNDS in the %s",
            ts->path, ts->line, cols->pos_name[0], gf_lmp_frame_name(f, name, sizeof name));
    return GF_OK;
}

/// Reads the atom lines of a frame: checks their number and column counts,
/// and with `convert` appends the particles to rd->out.
static gf_status gf_lmp_atom_lines(gf_reader *rd, const gf_lmp_atoms *a, int convert)
{
    gf_textscan *ts = &rd->ts;
    char *tok[GF_READ_MAX_COLS];
    char name[64];
    long long have = 0, want = a->hdr.natoms;
    while (have < want) {
        char *line;
        size_t len;
        gf_status st;
        int r = gf_textscan_next(ts, &line, &len, &st);
        if (r < 0) return st;
        int item = r > 0 && strncmp(gf_textscan_skip_blank(line), "ITEM:", 5) == 0;
        if (r == 0 || item)
            return gf_error_set(
                GF_ERR_FORMAT, "%s:%ld: %s ends after %lld of %lld atoms (truncated file?)",
                ts->path, ts->line, gf_lmp_frame_name(&a->hdr, name, sizeof name), have, want);
        size_t n =
            convert ? gf_textscan_split(line, tok, (size_t)a->cols.ncols) : gf_textscan_count(line);
        if (n == 0) continue;                          // blank line
        if (n != (size_t)a->cols.ncols && ts->partial) // file cut in the middle of a line
            return gf_error_set(
                GF_ERR_FORMAT, "%s:%ld: %s ends after %lld of %lld atoms (truncated file?)",
                ts->path, ts->line, gf_lmp_frame_name(&a->hdr, name, sizeof name), have, want);
        if (n != (size_t)a->cols.ncols)
            return gf_error_set(
                GF_ERR_FORMAT,
                "%s:%ld: atom line has %zu columns, but ITEM: ATOMS on line %ld names %d", ts->path,
                ts->line, n, a->line, a->cols.ncols);
        if (convert) {
            st = gf_read_row(rd, &a->cols, tok, a->hdr.lo, a->hdr.hi);
            if (st != GF_OK) return st;
        }
        have++;
    }
    return GF_OK;
}

/// Makes rd->out and the id table ready for a frame of `n` particles
/// (`trusted`: the count has been checked against the file).
static gf_status gf_read_begin_frame(gf_reader *rd, long long n, int trusted)
{
    size_t hint = (size_t)n;
    if ((!trusted || rd->keep) && hint > GF_READ_MAX_HINT) hint = GF_READ_MAX_HINT;
    rd->out->n = 0;
    rd->rows = 0;
    gf_status st = gf_packing_reserve(rd->out, hint);
    if (st != GF_OK) return st;
    return gf_idset_reset(&rd->ids, hint);
}

static gf_status gf_read_lammps(gf_reader *rd)
{
    gf_textscan *ts = &rd->ts;
    const int convert_all = !ts->seekable || rd->each != NULL;
    gf_lmp_frame f = {0};
    gf_lmp_atoms cur = {0}, last = {0};
    int nframes = 0;
    long long prev_natoms = -1; // atoms of the frame just completed, for messages
    char name[64];
    for (;;) {
        char *line;
        size_t len;
        gf_status st;
        int r = gf_textscan_next(ts, &line, &len, &st);
        if (r < 0) return st;
        if (r == 0) break;
        char *s = (char *)gf_textscan_skip_blank(line);
        if (!*s) continue;
        if (strncmp(s, "ITEM:", 5) != 0) {
            if (prev_natoms >= 0)
                return gf_error_set(GF_ERR_FORMAT,
                                    "%s:%ld: expected an ITEM: line after the %lld atoms of the %s "
                                    "(more atom lines than NUMBER OF ATOMS?)",
                                    ts->path, ts->line, prev_natoms,
                                    gf_lmp_frame_name(&last.hdr, name, sizeof name));
            return gf_error_set(
                GF_ERR_FORMAT,
                "%s:%ld: expected an ITEM: line (not a LAMMPS text dump?), found '%.40s'", ts->path,
                ts->line, s);
        }
        prev_natoms = -1;
        s = (char *)gf_textscan_skip_blank(s + 5);
        if (!f.started) {
            f.started = 1;
            f.start_line = ts->line;
        }
#define GF_LMP_ONCE(flag, item)                                                                    \
    if (f.flag)                                                                                    \
    return gf_error_set(GF_ERR_FORMAT,                                                             \
                        "%s:%ld: second ITEM: %s before ITEM: ATOMS in the %s (truncated or "      \
                        "corrupt frame header?)",                                                  \
                        ts->path, ts->line, item, gf_lmp_frame_name(&f, name, sizeof name))
        if (strncmp(s, "TIMESTEP", 8) == 0 && gf_is_blank_line(s + 8)) {
            GF_LMP_ONCE(have_ts, "TIMESTEP");
            st = gf_lmp_value(rd, &f, "TIMESTEP", &line);
            if (st != GF_OK) return st;
            st = gf_lmp_int(ts, line, "TIMESTEP", &f.timestep);
            if (st != GF_OK) return st;
            f.have_ts = 1;
        } else if (strncmp(s, "TIME", 4) == 0 && gf_is_blank_line(s + 4)) {
            GF_LMP_ONCE(have_time, "TIME");
            st = gf_lmp_value(rd, &f, "TIME", &line);
            if (st != GF_OK) return st;
            if (rd->each) {
                char *tok[2];
                size_t n = gf_textscan_split(line, tok, 2);
                if (n != 1 || gf_textscan_double(tok[0], &f.time) != 0)
                    return gf_error_set(GF_ERR_FORMAT,
                                        "%s:%ld: ITEM: TIME: '%.64s' is not a finite number",
                                        ts->path, ts->line, n ? tok[0] : "");
            }
            f.have_time = 1;
        } else if (strncmp(s, "UNITS", 5) == 0 && gf_is_blank_line(s + 5)) {
            GF_LMP_ONCE(have_units, "UNITS");
            st = gf_lmp_value(rd, &f, "UNITS", &line);
            if (st != GF_OK) return st;
            f.have_units = 1;
        } else if (strncmp(s, "NUMBER OF ATOMS", 15) == 0 && gf_is_blank_line(s + 15)) {
            GF_LMP_ONCE(have_n, "NUMBER OF ATOMS");
            st = gf_lmp_value(rd, &f, "NUMBER OF ATOMS", &line);
            if (st != GF_OK) return st;
            st = gf_lmp_int(ts, line, "NUMBER OF ATOMS", &f.natoms);
            if (st != GF_OK) return st;
            f.natoms_line = ts->line;
            f.have_n = 1;
        } else if (strncmp(s, "BOX BOUNDS", 10) == 0) {
            GF_LMP_ONCE(have_box, "BOX BOUNDS");
            st = gf_lmp_box(rd, &f, s + 10);
            if (st != GF_OK) return st;
        } else if (strncmp(s, "ATOMS", 5) == 0 && (s[5] == '\0' || s[5] == ' ' || s[5] == '\t')) {
            cur.off = ts->line_off;
            cur.line = ts->line;
            st = gf_lmp_atoms_header(rd, &f, s + 5, &cur.cols);
            if (st != GF_OK) return st;
            cur.hdr = f;
            if (convert_all) {
                st = gf_read_begin_frame(rd, f.natoms, 0);
                if (st != GF_OK) return st;
            }
            st = gf_lmp_atom_lines(rd, &cur, convert_all);
            if (st != GF_OK) return st;
            if (rd->each) {
                gf_packing_frame info = {.timestep = f.timestep,
                                         .have_time = f.have_time,
                                         .time = f.time,
                                         .have_box = f.have_box,
                                         .have_type = cur.cols.type >= 0,
                                         .pass = rd->want_pass && cur.cols.pass >= 0 ? rd->pass : NULL,
                                         .line = f.start_line};
                for (int k = 0; k < 3; k++) {
                    info.lo[k] = rd->unit > 0 ? f.lo[k] / rd->unit : f.lo[k];
                    info.hi[k] = rd->unit > 0 ? f.hi[k] / rd->unit : f.hi[k];
                }
                st = rd->each(rd->each_ctx, &info, rd->out);
                if (st != GF_OK) return st;
            }
            last = cur;
            nframes++;
            prev_natoms = f.natoms;
            memset(&f, 0, sizeof f);
        } else {
            return gf_error_set(GF_ERR_FORMAT,
                                "%s:%ld: unknown section 'ITEM: %.40s' in a LAMMPS dump", ts->path,
                                ts->line, s);
        }
#undef GF_LMP_ONCE
    }
    if (f.started)
        return gf_error_set(
            GF_ERR_FORMAT,
            "%s:%ld: file ends in the header of the %s, before ITEM: ATOMS (truncated file?)",
            ts->path, ts->line, gf_lmp_frame_name(&f, name, sizeof name));
    if (nframes == 0)
        return gf_error_set(GF_ERR_FORMAT, "%s: no particles in file (it is empty)", ts->path);
    if (last.hdr.natoms == 0 && !rd->each) // a drained silo's last snapshot is a valid frame
        return gf_error_set(GF_ERR_FORMAT, "%s:%ld: no particles in file (the last %s has 0 atoms)",
                            ts->path, last.hdr.natoms_line,
                            gf_lmp_frame_name(&last.hdr, name, sizeof name));
    if (convert_all) return GF_OK;

    // Second pass: convert the last frame only.
    gf_status st = gf_textscan_seek(ts, last.off, last.line);
    if (st != GF_OK) return st;
    char *line;
    size_t len;
    if (gf_textscan_next(ts, &line, &len, &st) != 1) // the ITEM: ATOMS line again
        return st != GF_OK ? st
                           : gf_error_set(GF_ERR_IO, "%s: file changed while being read", ts->path);
    st = gf_read_begin_frame(rd, last.hdr.natoms, 1);
    if (st != GF_OK) return st;
    return gf_lmp_atom_lines(rd, &last, 1);
}

// ---------------------------------------------------------------------------
// XYZ: count line, comment line, `name x y z [...]` lines; concatenated
// frames are allowed, the last one is kept. A comment line in the extended
// XYZ form (`Properties=species:S:1:pos:R:3:radius:R:1`, as granflow writes
// it, and OVITO and ASE read it) places the positions and the radius;
// without one the columns are `name x y z` and every radius is 1/2.

static int gf_xyz_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/// The columns that the comment line's `Properties=` announces, into `c`
/// (left as it is without one). Returns GF_OK, or an error naming the line.
static gf_status gf_xyz_properties(const gf_textscan *ts, const char *comment, gf_columns *c)
{
    const char *p = strstr(comment, "Properties=");
    if (!p || (p > comment && !gf_xyz_blank(p[-1]))) return GF_OK;
    p += strlen("Properties=");
    int col = 0, pos = -1, radius = -1;
    while (*p && !gf_xyz_blank(*p)) {
        char name[64], type[8];
        long count;
        int used = 0;
        if (sscanf(p, "%63[^:]:%7[^:]:%ld%n", name, type, &count, &used) != 3 || count < 1 ||
            count > GF_READ_MAX_COLS || col + count > GF_READ_MAX_COLS)
            return gf_error_set(GF_ERR_FORMAT,
                                "%s:%ld: the comment line's Properties= is not a list of NAME:TYPE:COUNT "
                                "(at '%.40s')",
                                ts->path, ts->line, p);
        if (strcmp(name, "pos") == 0 && count == 3) pos = col;
        if (strcmp(name, "radius") == 0 && count == 1) radius = col;
        col += (int)count;
        p += used;
        if (*p == ':') p++;
        else if (*p && !gf_xyz_blank(*p))
            return gf_error_set(GF_ERR_FORMAT,
                                "%s:%ld: the comment line's Properties= is not a list of NAME:TYPE:COUNT "
                                "(at '%.40s')",
                                ts->path, ts->line, p);
    }
    if (pos < 0)
        return gf_error_set(GF_ERR_FORMAT, "%s:%ld: the comment line's Properties= has no pos:R:3",
                            ts->path, ts->line);
    c->ncols = col;
    for (int k = 0; k < 3; k++) c->pos[k] = pos + k;
    c->radius = radius;
    return GF_OK;
}

static gf_status gf_read_xyz(gf_reader *rd)
{
    gf_textscan *ts = &rd->ts;
    const gf_columns plain = {.ncols = 4,
                              .pos = {1, 2, 3},
                              .pos_name = {"x", "y", "z"},
                              .id = -1,
                              .radius = -1,
                              .diameter = -1,
                              .type = -1,
                              .pass = -1,
                              .radius_name = "radius"};
    int nframes = 0;
    long count_line = 0;
    for (;;) {
        char *line, *tok[GF_READ_MAX_COLS];
        size_t len;
        gf_status st;
        int r;
        while ((r = gf_textscan_next(ts, &line, &len, &st)) == 1 && gf_is_blank_line(line)) {
        }
        if (r < 0) return st;
        if (r == 0) break;
        long long want;
        size_t n = gf_textscan_split(line, tok, 1);
        if (n != 1 || gf_textscan_int(tok[0], &want) != 0 || want < 0) {
            if (nframes > 0)
                return gf_error_set(GF_ERR_FORMAT,
                                    "%s:%ld: expected the atom count of a new frame after the %zu "
                                    "atoms announced on line %ld (more atom lines than the count?)",
                                    ts->path, ts->line, rd->rows, count_line);
            return gf_error_set(GF_ERR_FORMAT,
                                "%s:%ld: expected the number of atoms, found '%.40s'", ts->path,
                                ts->line, n ? tok[0] : "");
        }
        count_line = ts->line;
        r = gf_textscan_next(ts, &line, &len, &st); // comment line
        if (r < 0) return st;
        if (r == 0)
            return gf_error_set(GF_ERR_FORMAT,
                                "%s:%ld: file ends after the atom count (truncated file?)",
                                ts->path, ts->line);
        gf_columns cols = plain;
        if ((st = gf_xyz_properties(ts, line, &cols)) != GF_OK) return st;
        st = gf_read_begin_frame(rd, want, 0);
        if (st != GF_OK) return st;
        long long have = 0;
        while (have < want) {
            r = gf_textscan_next(ts, &line, &len, &st);
            if (r < 0) return st;
            if (r == 0)
                return gf_error_set(
                    GF_ERR_FORMAT,
                    "%s:%ld: file ends after %lld of the %lld atoms announced on line "
                    "%ld (truncated file?)",
                    ts->path, ts->line, have, want, count_line);
            n = gf_textscan_split(line, tok, (size_t)cols.ncols);
            if (n == 0) continue;
            if (n < (size_t)cols.ncols && ts->partial)
                return gf_error_set(
                    GF_ERR_FORMAT,
                    "%s:%ld: file ends in the middle of atom %lld of the %lld announced "
                    "on line %ld (truncated file?)",
                    ts->path, ts->line, have + 1, want, count_line);
            if (n < (size_t)cols.ncols)
                return gf_error_set(
                    GF_ERR_FORMAT,
                    "%s:%ld: atom line has %zu columns, expected %s (atom %lld "
                    "of the %lld announced on line %ld)",
                    ts->path, ts->line, n,
                    cols.ncols == 4 ? "'name x y z'" : "those of the comment line's Properties=", have + 1,
                    want, count_line);
            st = gf_read_row(rd, &cols, tok, NULL, NULL);
            if (st != GF_OK) return st;
            have++;
        }
        nframes++;
    }
    if (nframes == 0)
        return gf_error_set(GF_ERR_FORMAT, "%s: no particles in file (it is empty)", ts->path);
    if (rd->rows == 0)
        return gf_error_set(GF_ERR_FORMAT,
                            "%s:%ld: no particles in file (the last frame has 0 atoms)", ts->path,
                            count_line);
    return GF_OK;
}

// ---------------------------------------------------------------------------
// CSV: a header naming the columns, then one row per particle.

static char *gf_csv_trim(char *s)
{
    s = (char *)gf_textscan_skip_blank(s);
    size_t n = strlen(s);
    while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\r')) s[--n] = '\0';
    if (n >= 2 && s[0] == '"' && s[n - 1] == '"') {
        s[n - 1] = '\0';
        s++;
    }
    return s;
}

/// Splits at commas in place, trimming each field. Returns the field count
/// (which may exceed max; then only max fields are stored).
static size_t gf_csv_split(char *s, char **tok, size_t max)
{
    size_t n = 0;
    for (;;) {
        char *comma = strchr(s, ',');
        if (comma) *comma = '\0';
        if (n < max) tok[n] = gf_csv_trim(s);
        n++;
        if (!comma) return n;
        s = comma + 1;
    }
}

static gf_status gf_read_csv(gf_reader *rd)
{
    gf_textscan *ts = &rd->ts;
    char *tok[GF_READ_MAX_COLS];
    gf_columns cols;
    int have_header = 0;
    long header_line = 0;
    gf_status st = gf_read_begin_frame(rd, 0, 0);
    if (st != GF_OK) return st;
    for (;;) {
        char *line;
        size_t len;
        int r = gf_textscan_next(ts, &line, &len, &st);
        if (r < 0) return st;
        if (r == 0) break;
        if (ts->line == 1 && (unsigned char)line[0] == 0xEF && (unsigned char)line[1] == 0xBB &&
            (unsigned char)line[2] == 0xBF)
            line += 3; // UTF-8 byte order mark
        const char *s = gf_textscan_skip_blank(line);
        if (!*s || *s == '#') continue;
        size_t n = gf_csv_split(line, tok, GF_READ_MAX_COLS);
        if (!have_header) {
            if (n > GF_READ_MAX_COLS)
                return gf_error_set(GF_ERR_FORMAT,
                                    "%s:%ld: header has %zu columns (at most %d supported)",
                                    ts->path, ts->line, n, GF_READ_MAX_COLS);
            if (gf_columns_resolve(&cols, tok, (int)n, 0) != 0) {
                char list[400];
                return gf_error_set(GF_ERR_FORMAT,
                                    "%s:%ld: header has no x, y and z columns; found: %s", ts->path,
                                    ts->line, gf_join(list, sizeof list, tok, (int)n, ","));
            }
            have_header = 1;
            header_line = ts->line;
            continue;
        }
        if (n < (size_t)cols.ncols && ts->partial)
            return gf_error_set(GF_ERR_FORMAT,
                                "%s:%ld: last row has %zu of %d fields (truncated file?)", ts->path,
                                ts->line, n, cols.ncols);
        if (n != (size_t)cols.ncols)
            return gf_error_set(GF_ERR_FORMAT,
                                "%s:%ld: row has %zu fields, but the header on line %ld has %d",
                                ts->path, ts->line, n, header_line, cols.ncols);
        st = gf_read_row(rd, &cols, tok, NULL, NULL);
        if (st != GF_OK) return st;
    }
    if (!have_header)
        return gf_error_set(GF_ERR_FORMAT, "%s: no particles in file (it is empty)", ts->path);
    if (rd->rows == 0)
        return gf_error_set(GF_ERR_FORMAT, "%s:%ld: no particles in file (only a header)", ts->path,
                            header_line);
    return GF_OK;
}

// ---------------------------------------------------------------------------

// gf_packing_read, noting in *line (when find_id > 0) the line of particle find_id.
static gf_status gf_packing_read_finding(const char *path, gf_packing_format format, double unit, gf_packing *out,
                                         int64_t find_id, long *line, gf_packing_keep_fn keep, void *keep_ctx)
{
    if (!out) return gf_error_set(GF_ERR_PARAM, "gf_packing_read: no output packing");
    if (!path || !*path) {
        gf_packing_free(out);
        return gf_error_set(GF_ERR_PARAM, "gf_packing_read: no file name");
    }
    if (format == GF_FORMAT_AUTO)
        format = gf_textscan_has_ext(path, ".xyz")   ? GF_FORMAT_XYZ
                 : gf_textscan_has_ext(path, ".csv") ? GF_FORMAT_CSV
                                                     : GF_FORMAT_LAMMPS;
    if (format != GF_FORMAT_LAMMPS && format != GF_FORMAT_XYZ && format != GF_FORMAT_CSV) {
        gf_packing_free(out);
        return gf_error_set(GF_ERR_PARAM, "gf_packing_read: unknown format %d for %s", (int)format,
                            path);
    }
    // Build into a private packing so that `out` never holds half a result.
    gf_packing tmp = {0};
    gf_reader rd = {.out = &tmp, .find_id = find_id, .unit = unit, .keep = keep, .keep_ctx = keep_ctx};
    gf_status st = gf_textscan_open(&rd.ts, path);
    if (st == GF_OK) {
        switch (format) {
        case GF_FORMAT_XYZ: st = gf_read_xyz(&rd); break;
        case GF_FORMAT_CSV: st = gf_read_csv(&rd); break;
        default: st = gf_read_lammps(&rd); break;
        }
    }
    gf_textscan_close(&rd.ts);
    gf_idset_free(&rd.ids);
    gf_packing_free(out);
    if (line) *line = rd.found_line;
    if (st != GF_OK) {
        gf_packing_free(&tmp);
        return st;
    }
    *out = tmp;
    return GF_OK;
}

gf_status gf_packing_read(const char *path, gf_packing_format format, gf_packing *out)
{
    return gf_packing_read_finding(path, format, 1.0, out, 0, NULL, NULL, NULL);
}

gf_status gf_packing_read_in(const char *path, gf_packing_format format, double unit, gf_packing *out)
{
    if (!(unit > 0) || !isfinite(unit))
        return gf_error_set(GF_ERR_PARAM, "%s: length unit %g: must be a positive number", path ? path : "?", unit);
    return gf_packing_read_finding(path, format, unit, out, 0, NULL, NULL, NULL);
}

gf_status gf_packing_read_where(const char *path, double unit, gf_packing_keep_fn keep, void *ctx, gf_packing *out)
{
    if (!(unit > 0) || !isfinite(unit))
        return gf_error_set(GF_ERR_PARAM, "%s: length unit %g: must be a positive number", path ? path : "?", unit);
    return gf_packing_read_finding(path, GF_FORMAT_AUTO, unit, out, 0, NULL, keep, ctx);
}

long gf_packing_line_of(const char *path, int64_t id)
{
    gf_packing pk = {0};
    long line = 0;
    if (gf_packing_read_finding(path, GF_FORMAT_AUTO, 1.0, &pk, id, &line, NULL, NULL) != GF_OK) line = 0;
    gf_packing_free(&pk);
    return line;
}

static gf_status gf_packing_read_each(const char *path, double unit, gf_packing_frame_fn fn, void *ctx, int want_pass)
{
    if (!(unit > 0) || !isfinite(unit))
        return gf_error_set(GF_ERR_PARAM, "%s: length unit %g: must be a positive number", path ? path : "?", unit);
    if (!path || !*path) return gf_error_set(GF_ERR_PARAM, "gf_packing_read_frames: no file name");
    if (!fn) return gf_error_set(GF_ERR_PARAM, "gf_packing_read_frames: no frame callback");
    gf_packing tmp = {0};
    gf_reader rd = {.out = &tmp, .each = fn, .each_ctx = ctx, .want_pass = want_pass, .unit = unit};
    gf_status st = gf_textscan_open(&rd.ts, path);
    if (st == GF_OK) st = gf_read_lammps(&rd);
    gf_textscan_close(&rd.ts);
    gf_idset_free(&rd.ids);
    GF_DELETE(rd.pass, rd.pass_cap);
    gf_packing_free(&tmp);
    return st;
}

gf_status gf_packing_read_frames(const char *path, gf_packing_frame_fn fn, void *ctx)
{
    return gf_packing_read_each(path, 1.0, fn, ctx, 0);
}

gf_status gf_packing_read_frames_in(const char *path, double unit, gf_packing_frame_fn fn, void *ctx)
{
    return gf_packing_read_each(path, unit, fn, ctx, 0);
}

gf_status gf_packing_read_frames_pass(const char *path, gf_packing_frame_fn fn, void *ctx)
{
    return gf_packing_read_each(path, 1.0, fn, ctx, 1);
}
