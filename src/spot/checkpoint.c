// SPDX-License-Identifier: MIT
// Checkpoints: the whole engine state in one file, so a run resumes exactly.
// Layout: "GFCKPT\r\n", u32 version, u32 byte-order mark, u64 payload size,
// u32 CRC-32 of the payload, then the payload (native doubles and integers).
#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "core/alloc.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/fs.h"
#include "geom/meshshape.h"
#include "packing/import.h"
#include "spot/sim_internal.h"

#define GF_CKPT_MAGIC "GFCKPT\r\n"
/// Marks the domain engine's spot clocks at the end of the payload.
#define GF_CKPT_CLOCKS "GFCLOCKS"
#define GF_CKPT_VERSION 4u
#define GF_CKPT_BOM 0x01020304u

typedef struct gf_buf {
    unsigned char *data;
    size_t len, cap;
    bool oom;
    bool count; // only count the bytes (the size of a checkpoint, before it is allocated)
} gf_buf;

static void gf_put(gf_buf *b, const void *src, size_t n)
{
    if (b->count) {
        b->len += n;
        return;
    }
    if (b->oom) return;
    if (b->len + n > b->cap) {
        size_t cap = b->cap ? b->cap : 4096;
        while (cap < b->len + n) cap *= 2;
        unsigned char *q = gf_realloc(b->data, b->cap, cap);
        if (!q) {
            b->oom = true;
            return;
        }
        b->data = q;
        b->cap = cap;
    }
    if (n) memcpy(b->data + b->len, src, n); // src may be NULL when n = 0 (no exits yet)
    b->len += n;
}

#define GF_PUT(b, v) gf_put((b), &(v), sizeof(v))

typedef struct gf_rd {
    const unsigned char *data;
    size_t len, pos;
    bool bad;
} gf_rd;

static void gf_get(gf_rd *r, void *dst, size_t n)
{
    if (r->bad || n > r->len - r->pos) {
        r->bad = true;
        if (n) memset(dst, 0, n);
        return;
    }
    if (n) memcpy(dst, r->data + r->pos, n);
    r->pos += n;
}

#define GF_GET(r, v) gf_get((r), &(v), sizeof(v))

// CRC-32 of a buffer of any size (zlib's crc32 takes uInt lengths).
static uint32_t gf_crc32(const unsigned char *data, size_t len)
{
    uLong crc = crc32(0L, Z_NULL, 0);
    for (size_t off = 0; off < len;) {
        size_t chunk = len - off > (1u << 30) ? (1u << 30) : len - off;
        crc = crc32(crc, data + off, (uInt)chunk);
        off += chunk;
    }
    return (uint32_t)crc;
}

// Physics part of a config as text: the keys that must not change on resume.
// Written into a block of the core allocator (*cap bytes, *len used), grown
// until the text fits.
static gf_status gf_ckpt_physics(const gf_config *cfg, char **text, size_t *len, size_t *cap)
{
    gf_config c = *cfg;
    gf_config_reset_run_keys(&c);
    gf_container_defs cd;
    gf_config_container_defs(&c, &cd);
    const gf_container box = gf_container_build(&cd);
    uint64_t digest;
    if (gf_container_reads_key(&box, "container.mesh") && gf_meshshape_digest(&cd, &digest) == GF_OK) {
        char name[64];
        snprintf(name, sizeof name, "stl-fnv1a-%016" PRIx64, digest); // a run's copy is the same mesh
        gf_config_set_mesh_path(&c, name);
    }
    for (size_t size = (size_t)1 << 16; size <= (size_t)1 << 26; size *= 2) {
        char *buf = gf_alloc(size);
        FILE *f = buf ? fmemopen(buf, size, "w") : NULL;
        if (!f) {
            gf_free(buf, size);
            return gf_error_set(GF_ERR_NOMEM, "out of memory");
        }
        gf_status st = gf_config_write(&c, f);
        bool flushed = fflush(f) == 0 && !ferror(f);
        long at = ftell(f);
        fclose(f);
        // fmemopen keeps a NUL after the text: a text of size - 1 bytes may have been cut.
        bool full = !flushed || at < 0 || (size_t)at >= size - 1;
        if (st == GF_OK && !full) {
            *text = buf;
            *len = (size_t)at;
            *cap = size;
            return GF_OK;
        }
        gf_free(buf, size);
        if (st != GF_OK && st != GF_ERR_IO) return st;
    }
    return gf_error_set(GF_ERR_NOMEM, "configuration text too long for a checkpoint");
}

// The payload of a checkpoint into b (or its size, with b->count).
static gf_status gf_ckpt_fill(const gf_sim *sim, gf_buf *b_out)
{
    gf_buf b = *b_out;
    char *phys = NULL;
    size_t plen = 0, pcap = 0;
    gf_status st = gf_ckpt_physics(&sim->cfg, &phys, &plen, &pcap);
    if (st != GF_OK) return st;
    uint64_t n64 = plen;
    GF_PUT(&b, n64);
    gf_put(&b, phys, plen);
    gf_free(phys, pcap);

    GF_PUT(&b, sim->t);
    GF_PUT(&b, sim->t_reached);
    GF_PUT(&b, sim->t_pending);
    uint8_t pending = sim->pending;
    GF_PUT(&b, pending);
    GF_PUT(&b, sim->rng.s);
    GF_PUT(&b, sim->next_snap);
    GF_PUT(&b, sim->next_ckpt);
    GF_PUT(&b, sim->st);
    uint64_t counts[5] = {sim->n, sim->n_alive, sim->n_initial, sim->ns, sim->nexit};
    GF_PUT(&b, counts);
    GF_PUT(&b, sim->rmax);
    GF_PUT(&b, sim->grid_ztop);
    GF_PUT(&b, sim->next_birth);
    GF_PUT(&b, sim->nl_built_at);
    GF_PUT(&b, sim->fstep);
    uint32_t shift = sim->nl_shift;
    GF_PUT(&b, shift);
    gf_put(&b, sim->p, sizeof(gf_pos) * sim->n);
    gf_put(&b, sim->p0, sizeof(gf_ref) * sim->n);
    gf_put(&b, sim->id, sizeof(int64_t) * sim->n);
    gf_put(&b, sim->layer, sizeof(int32_t) * sim->n);
    gf_put(&b, sim->alive, sizeof(uint8_t) * sim->n);
    gf_put(&b, sim->hist, sizeof(gf_hist) * sim->n);
    gf_put(&b, sim->sx, sizeof(double) * sim->ns);
    gf_put(&b, sim->sy, sizeof(double) * sim->ns);
    gf_put(&b, sim->sz, sizeof(double) * sim->ns);
    gf_put(&b, sim->sbirth, sizeof(uint64_t) * sim->ns);
    gf_put(&b, sim->scount, sizeof(uint32_t) * sim->ns);
    gf_put(&b, sim->exits, sizeof(gf_exit) * sim->nexit);
    uint64_t ncell = sim->grid.ncell;
    GF_PUT(&b, ncell);
    gf_put(&b, sim->grid.count, sizeof(uint32_t) * ncell);
    for (size_t c = 0; c < ncell; c++) // only the used slots, so unused ones cannot make files differ
        gf_put(&b, sim->grid.slot + c * GF_CELL_CAP, sizeof(uint32_t) * sim->grid.count[c]);
    // The domain engine's spot clocks, last (a checkpoint of another engine
    // ends before them, as those of earlier versions do).
    if (sim->d.order == GF_ORDER_DOMAINS || sim->d.order == GF_ORDER_SWEEP) {
        gf_put(&b, GF_CKPT_CLOCKS, 8);
        gf_put(&b, sim->snext, sizeof(double) * sim->ns);
    }
    *b_out = b;
    return GF_OK;
}

// Bytes before the payload: magic, version, byte-order mark, size, CRC.
#define GF_CKPT_HEADER (8 + 4 + 4 + 8 + 4)

size_t gf_sim_checkpoint_bound(const gf_sim *sim)
{
    gf_buf m = {.count = true};
    if (gf_ckpt_fill(sim, &m) != GF_OK) return 0;
    // Every particle still inside may yet leave (with recirculation, leave
    // again: a run that long is beyond this estimate).
    return GF_CKPT_HEADER + m.len + sizeof(gf_exit) * (sim->d.recirculate ? sim->n : sim->n_alive);
}

gf_status gf_sim_save(const gf_sim *sim, const char *path)
{
    // Saves come between events, when every exit has been put back.
    if (sim->nreins != 0) return gf_error_set(GF_ERR_STATE, "checkpoint while re-insertions are pending");
    // Measured first and allocated once, at its size: a buffer grown by
    // doubling took up to twice that, at the end of a run (issue 26).
    gf_buf m = {.count = true};
    gf_status st = gf_ckpt_fill(sim, &m);
    if (st != GF_OK) return st;
    gf_buf b = {.data = gf_alloc(m.len ? m.len : 1), .cap = m.len ? m.len : 1};
    if (!b.data) return gf_error_set(GF_ERR_NOMEM, "out of memory writing checkpoint %s (%zu bytes)", path, m.len);
    st = gf_ckpt_fill(sim, &b);
    if (st != GF_OK || b.oom) {
        gf_free(b.data, b.cap);
        return st != GF_OK ? st : gf_error_set(GF_ERR_NOMEM, "out of memory writing checkpoint %s", path);
    }

    char tmp[GF_PATH_MAX + 8];
    FILE *f;
    gf_status st2 = gf_atomic_open(path, tmp, sizeof tmp, &f);
    if (st2 != GF_OK) {
        gf_free(b.data, b.cap);
        return st2;
    }
    uint32_t version = GF_CKPT_VERSION, bom = GF_CKPT_BOM;
    uint64_t size = b.len;
    uint32_t crc = gf_crc32(b.data, b.len);
    errno = 0;
    bool ok = fwrite(GF_CKPT_MAGIC, 1, 8, f) == 8 && fwrite(&version, 4, 1, f) == 1 &&
              fwrite(&bom, 4, 1, f) == 1 && fwrite(&size, 8, 1, f) == 1 && fwrite(&crc, 4, 1, f) == 1 &&
              fwrite(b.data, 1, b.len, f) == b.len;
    int err = ok ? 0 : (errno ? errno : EIO);
    gf_free(b.data, b.cap);
    if (!ok) {
        gf_atomic_abort(f, tmp);
        return gf_error_set(GF_ERR_IO, "%s: cannot write checkpoint: %s", tmp, strerror(err));
    }
    return gf_atomic_commit(f, tmp, path);
}

// Values the engine relies on (a checkpoint is checksummed, so only a
// deliberately made file gets here with others): times, particles inside
// the container (or over the hole, down to the exit plane), radii the
// engine takes (from GF_IMPORT_RMIN: a radius of 1e-200 made the step's
// scratch size (0.5 / r)^3 infinite, cast to size_t; found by the
// checkpoint fuzzer), spots at finite places.
static gf_status gf_ckpt_check_values(const gf_sim *sim, const char *path)
{
    const gf_container *b = &sim->box;
    const double zlo = fmin(0.0, b->z_exit) - 2.0, zhi = 1e7;
    if (!(isfinite(sim->t) && sim->t >= 0 && isfinite(sim->t_reached) && isfinite(sim->t_pending) &&
          sim->grid_ztop > 0 && sim->grid_ztop <= zhi && sim->rmax > 0 && sim->rmax <= 1.0))
        return gf_error_set(GF_ERR_FORMAT, "%s: checkpoint holds impossible times or sizes", path);
    for (size_t i = 0; i < sim->n; i++) {
        if (!sim->alive[i]) continue;
        const gf_pos *q = &sim->p[i];
        const gf_ref *a = &sim->p0[i];
        if (!(fabs(q->x) <= b->xhi + 1.0 && fabs(q->y) <= b->yhi + 1.0 && q->z >= zlo && q->z <= zhi &&
              q->r >= GF_IMPORT_RMIN && q->r <= sim->rmax && fabs(a->x) <= b->xhi + 1.0 && fabs(a->y) <= b->yhi + 1.0 &&
              a->z >= zlo && a->z <= zhi && a->h >= 0 && a->h <= 1.0))
            return gf_error_set(GF_ERR_FORMAT, "%s: particle id %lld is at an impossible place or size", path,
                                (long long)sim->id[i]);
    }
    for (size_t k = 0; k < sim->ns; k++)
        if (!(fabs(sim->sx[k]) <= b->xhi + 1.0 && fabs(sim->sy[k]) <= b->yhi + 1.0 && sim->sz[k] >= zlo - 100.0 &&
              sim->sz[k] <= zhi))
            return gf_error_set(GF_ERR_FORMAT, "%s: spot %zu is at an impossible place", path, k);
    return GF_OK;
}

// The header of a checkpoint read into `data` (len bytes): magic, byte order,
// version, payload size and CRC; on success `r` reads the payload.
static gf_status gf_ckpt_header(const char *path, const unsigned char *data, size_t len, gf_rd *r)
{
    const size_t head = GF_CKPT_HEADER;
    uint32_t version, bom, crc;
    uint64_t size;
    if (len < head || memcmp(data, GF_CKPT_MAGIC, 8) != 0)
        return gf_error_set(GF_ERR_FORMAT, "%s: not a granflow checkpoint", path);
    memcpy(&version, data + 8, 4);
    memcpy(&bom, data + 12, 4);
    memcpy(&size, data + 16, 8);
    memcpy(&crc, data + 24, 4);
    if (bom != GF_CKPT_BOM)
        return gf_error_set(GF_ERR_FORMAT, "%s: checkpoint written on a machine of other byte order", path);
    if (version != GF_CKPT_VERSION)
        return gf_error_set(GF_ERR_FORMAT, "%s: checkpoint version %u, this granflow reads version %u", path,
                            version, GF_CKPT_VERSION);
    if (size != len - head)
        return gf_error_set(GF_ERR_FORMAT, "%s: checkpoint %s (%zu payload bytes, header says %llu)", path,
                            len - head < size ? "truncated" : "has trailing bytes", len - head,
                            (unsigned long long)size);
    if (gf_crc32(data + head, size) != crc)
        return gf_error_set(GF_ERR_FORMAT, "%s: checkpoint checksum mismatch (file corrupted)", path);
    *r = (gf_rd){data + head, size, 0, false};
    return GF_OK;
}

// The settings: `cfg` validated into sim->cfg, and the physics the
// checkpoint was written with (its first record) compared with it.
static gf_status gf_ckpt_read_settings(gf_sim *sim, const gf_config *cfg, gf_rd *r, const char *path)
{
    sim->cfg = *cfg;
    gf_status st = gf_config_validate(&sim->cfg);
    if (st != GF_OK) return st;
    uint64_t plen = 0;
    GF_GET(r, plen);
    char *mine = NULL;
    size_t mlen = 0, mcap = 0;
    if ((st = gf_ckpt_physics(&sim->cfg, &mine, &mlen, &mcap)) != GF_OK) return st;
    gf_config dcfg = gf_config_default();
    char *def = NULL;
    size_t dlen = 0, dcap = 0;
    if ((st = gf_config_validate(&dcfg)) != GF_OK || (st = gf_ckpt_physics(&dcfg, &def, &dlen, &dcap)) != GF_OK) {
        gf_free(mine, mcap);
        return st;
    }
    if (r->bad || plen > r->len - r->pos)
        st = gf_error_set(GF_ERR_FORMAT, "%s: the checkpoint's configuration text runs past its payload", path);
    else
        st = gf_ckpt_compare_settings(path, (const char *)r->data + r->pos, (size_t)plen, mine, mlen, def, dlen);
    gf_free(def, dcap);
    gf_free(mine, mcap);
    if (st == GF_OK) r->pos += plen;
    return st;
}

// The engine's scalars (times, RNG, counters, list parameters) and the
// counts of the arrays: particles, alive, initial, spots, exits.
static gf_status gf_ckpt_read_scalars(gf_sim *sim, gf_rd *r, const char *path, uint64_t counts[5])
{
    uint8_t pending;
    GF_GET(r, sim->t);
    GF_GET(r, sim->t_reached);
    GF_GET(r, sim->t_pending);
    GF_GET(r, pending);
    GF_GET(r, sim->rng.s);
    GF_GET(r, sim->next_snap);
    GF_GET(r, sim->next_ckpt);
    GF_GET(r, sim->st);
    gf_get(r, counts, sizeof(uint64_t) * 5);
    GF_GET(r, sim->rmax);
    GF_GET(r, sim->grid_ztop);
    GF_GET(r, sim->next_birth);
    GF_GET(r, sim->nl_built_at);
    GF_GET(r, sim->fstep);
    uint32_t shift = 0;
    GF_GET(r, shift);
    if (shift < 4 || (1u << (shift < 31 ? shift : 31)) > GF_NL_CAP_MAX)
        return gf_error_set(GF_ERR_FORMAT, "%s: inconsistent checkpoint header", path);
    sim->nl_shift = shift;
    sim->pending = pending;
    return GF_OK;
}

// The arrays the counts announce, allocated once the counts are checked:
// they must be in the payload (a few bytes claiming 10^9 spots must not
// allocate gigabytes first).
static gf_status gf_ckpt_alloc_arrays(gf_sim *sim, const gf_rd *r, const char *path, const uint64_t counts[5])
{
    uint64_t n = counts[0];
    if (r->bad || n == 0 || n > GF_MAX_PARTICLES || counts[1] > n || counts[2] < n || counts[3] > (1ull << 40) ||
        (!sim->d.recirculate && counts[4] > counts[2]))
        return gf_error_set(GF_ERR_FORMAT, "%s: inconsistent checkpoint header", path);
    double need = (double)n * (double)(sizeof(gf_pos) + sizeof(gf_ref) + sizeof(int64_t) + sizeof(int32_t) + 1) +
                  (double)counts[3] * (double)(4 * sizeof(double) + sizeof(uint32_t)) +
                  (double)counts[4] * (double)sizeof(gf_exit);
    if (counts[2] > GF_MAX_PARTICLES || need > (double)(r->len - r->pos))
        return gf_error_set(GF_ERR_FORMAT, "%s: checkpoint header announces more than its payload holds", path);
    gf_status st = gf_sim_alloc_particles(sim, counts[2]);
    if (st != GF_OK) return st;
    sim->n = n;
    sim->n_alive = counts[1];
    sim->n_initial = counts[2];
    sim->ns = sim->ns_cap = counts[3];
    sim->nexit = 0;
    if (!gf_sim_exits_reserve(sim, counts[4])) return gf_error_set(GF_ERR_NOMEM, "out of memory");
    sim->nexit = counts[4];
    sim->sx = GF_NEW(double, sim->ns_cap);
    sim->sy = GF_NEW(double, sim->ns_cap);
    sim->sz = GF_NEW(double, sim->ns_cap);
    sim->sbirth = GF_NEW(uint64_t, sim->ns_cap);
    sim->scount = GF_NEW(uint32_t, sim->ns_cap);
    sim->snext = GF_NEW(double, sim->ns_cap);
    if (sim->ns_cap && (!sim->sx || !sim->sy || !sim->sz || !sim->sbirth || !sim->scount || !sim->snext))
        return gf_error_set(GF_ERR_NOMEM, "out of memory");
    return GF_OK;
}

// The particles, spots and exits, and their values checked.
static gf_status gf_ckpt_read_arrays(gf_sim *sim, gf_rd *r, const char *path)
{
    const size_t n = sim->n;
    gf_get(r, sim->p, sizeof(gf_pos) * n);
    gf_get(r, sim->p0, sizeof(gf_ref) * n);
    gf_get(r, sim->id, sizeof(int64_t) * n);
    gf_get(r, sim->layer, sizeof(int32_t) * n);
    gf_get(r, sim->alive, sizeof(uint8_t) * n);
    gf_get(r, sim->hist, sizeof(gf_hist) * n);
    gf_get(r, sim->sx, sizeof(double) * sim->ns);
    gf_get(r, sim->sy, sizeof(double) * sim->ns);
    gf_get(r, sim->sz, sizeof(double) * sim->ns);
    gf_get(r, sim->sbirth, sizeof(uint64_t) * sim->ns);
    gf_get(r, sim->scount, sizeof(uint32_t) * sim->ns);
    gf_get(r, sim->exits, sizeof(gf_exit) * sim->nexit);
    size_t live = 0;
    for (size_t i = 0; i < n; i++) live += sim->alive[i] != 0;
    if (r->bad || live != sim->n_alive)
        return gf_error_set(GF_ERR_FORMAT, "%s: inconsistent particle count", path);
    return gf_ckpt_check_values(sim, path);
}

// The domain engine's spot clocks, when the payload ends with them; a
// domain run resumed from another engine's checkpoint draws fresh ones.
static void gf_ckpt_read_clocks(gf_sim *sim, gf_rd *r)
{
    bool clocks = !r->bad && r->len - r->pos == 8 + sizeof(double) * sim->ns &&
                  !memcmp(r->data + r->pos, GF_CKPT_CLOCKS, 8);
    if (clocks) {
        r->pos += 8;
        gf_get(r, sim->snext, sizeof(double) * sim->ns);
        for (size_t k = 0; k < sim->ns; k++)
            if (!isfinite(sim->snext[k])) r->bad = true;
    } else if (sim->d.order == GF_ORDER_DOMAINS || sim->d.order == GF_ORDER_SWEEP) {
        for (size_t k = 0; k < sim->ns; k++) sim->snext[k] = sim->t + gf_rng_exp(&sim->rng, sim->d.move_rate);
    }
}

// The cell grid's contents (the order of particles within each cell, which
// the engine's sums depend on), then the clocks; the payload must end there.
static gf_status gf_ckpt_read_grid(gf_sim *sim, gf_rd *r, const char *path)
{
    uint64_t ncell = 0;
    GF_GET(r, ncell);
    if (r->bad || ncell != sim->grid.ncell)
        return gf_error_set(GF_ERR_FORMAT, "%s: grid does not match the container", path);
    uint32_t *slot = GF_NEW(uint32_t, ncell * GF_CELL_CAP), *cnt = GF_NEW(uint32_t, ncell);
    if (!slot || !cnt) {
        GF_DELETE(slot, ncell * GF_CELL_CAP);
        GF_DELETE(cnt, ncell);
        return gf_error_set(GF_ERR_NOMEM, "out of memory");
    }
    gf_get(r, cnt, sizeof(uint32_t) * ncell);
    for (size_t c = 0; !r->bad && c < ncell; c++) {
        if (cnt[c] > GF_CELL_CAP) r->bad = true;
        else gf_get(r, slot + c * GF_CELL_CAP, sizeof(uint32_t) * cnt[c]);
    }
    gf_ckpt_read_clocks(sim, r);
    gf_status st = r->bad || r->pos != r->len
                       ? gf_error_set(GF_ERR_FORMAT, "%s: checkpoint payload has the wrong size", path)
                       : gf_grid_restore(&sim->grid, cnt, slot, sim->n);
    GF_DELETE(slot, ncell * GF_CELL_CAP);
    GF_DELETE(cnt, ncell);
    return st;
}

// The whole payload into sim: settings, scalars, arrays, grid.
static gf_status gf_ckpt_read(gf_sim *sim, const gf_config *cfg, gf_rd *r, const char *path)
{
    gf_status st = gf_ckpt_read_settings(sim, cfg, r, path);
    if (st != GF_OK) return st;
    gf_sim_derive(sim);
    uint64_t counts[5];
    if ((st = gf_ckpt_read_scalars(sim, r, path, counts)) != GF_OK ||
        (st = gf_ckpt_alloc_arrays(sim, r, path, counts)) != GF_OK ||
        (st = gf_ckpt_read_arrays(sim, r, path)) != GF_OK || (st = gf_sim_make_grid(sim)) != GF_OK ||
        (st = gf_sim_alloc_scratch(sim)) != GF_OK || (st = gf_sim_make_stress(sim)) != GF_OK)
        return st;
    return gf_ckpt_read_grid(sim, r, path);
}

// Every live particle in the grid, and the neighbour lists rebuilt without
// re-sorting from the saved p0 (they are a function of it, see
// sim_internal.h): the very lists the run had, so the same order, the same
// sums, the same bits.
static gf_status gf_ckpt_relist(gf_sim *sim, const char *path)
{
    for (size_t i = 0; i < sim->n; i++)
        if (sim->alive[i] && sim->grid.cell_of[i] == GF_NO_CELL)
            return gf_error_set(GF_ERR_FORMAT, "%s: a particle is missing from the grid", path);
    uint64_t builds = sim->st.nlist_builds;
    gf_status st = gf_nlist_build(sim, false);
    sim->st.nlist_builds = builds;
    return st;
}

gf_status gf_sim_load(const gf_config *cfg, const char *path, gf_sim **out)
{
    *out = NULL;
    unsigned char *data = NULL;
    size_t len = 0, cap = 0;
    // A regular file only (a checkpoint.bin linked to /dev/zero would be read
    // until memory ran out), as big as it is on disk.
    gf_status st = gf_fs_read_all(path, 0, &data, &len, &cap);
    if (st != GF_OK) return st;
    gf_rd r;
    gf_sim *sim = NULL;
    if ((st = gf_ckpt_header(path, data, len, &r)) == GF_OK && !(sim = gf_alloc(sizeof *sim)))
        st = gf_error_set(GF_ERR_NOMEM, "out of memory");
    if (st == GF_OK) st = gf_ckpt_read(sim, cfg, &r, path);
    gf_free(data, cap);
    if (st == GF_OK) st = gf_ckpt_relist(sim, path);
    if (st != GF_OK) {
        gf_sim_destroy(sim);
        return st;
    }
    *out = sim;
    return GF_OK;
}
