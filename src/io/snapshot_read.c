// SPDX-License-Identifier: MIT
// gf_snapshot_*: one frame of a LAMMPS dump as flat arrays, for bindings
// (Python's read_snapshot) that must not depend on struct layouts. The
// reading itself is gf_packing_read_frames's, so the checks and messages are
// the ones `granflow analyze` gives.
#include "granflow/particles.h"

#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "io/packing_frames.h"

struct gf_snapshot {
    gf_packing pk;
    int32_t *pass; ///< NULL: the file has no pass column
    size_t pass_cap;
    gf_packing_frame info;
    size_t frames; ///< frames in the file
};

typedef struct gf_snapshot_pick {
    gf_snapshot *s;
    long want; ///< frame to keep, -1: the last
} gf_snapshot_pick;

static void gf_snapshot_clear(gf_snapshot *s)
{
    gf_packing_free(&s->pk);
    GF_DELETE(s->pass, s->pass_cap);
    s->pass = NULL;
    s->pass_cap = 0;
}

// Keeps the frame asked for (every frame when the last is wanted: the
// count is known only at the end).
static gf_status gf_snapshot_keep(void *ctx, const gf_packing_frame *f, gf_packing *pk)
{
    gf_snapshot_pick *pick = ctx;
    gf_snapshot *s = pick->s;
    size_t k = s->frames++;
    if (pick->want >= 0 && (size_t)pick->want != k) return GF_OK;
    gf_snapshot_clear(s);
    s->pk = *pk;
    memset(pk, 0, sizeof *pk);
    s->info = *f;
    s->info.pass = NULL; // the callback's array; the copy is s->pass
    if (f->pass && s->pk.n) {
        if (!(s->pass = GF_NEW(int32_t, s->pk.n))) return gf_error_set(GF_ERR_NOMEM, "out of memory");
        s->pass_cap = s->pk.n;
        memcpy(s->pass, f->pass, sizeof *s->pass * s->pk.n);
    }
    return GF_OK;
}

gf_status gf_snapshot_read(const char *path, long frame, gf_snapshot **out)
{
    if (!path || !out) return gf_error_set(GF_ERR_PARAM, "gf_snapshot_read: NULL argument");
    *out = NULL;
    if (frame < -1) return gf_error_set(GF_ERR_PARAM, "%s: frame %ld: give 0, 1, ... or -1 (the last)", path, frame);
    gf_snapshot *s = gf_alloc(sizeof *s);
    if (!s) return gf_error_set(GF_ERR_NOMEM, "out of memory");
    gf_snapshot_pick pick = {s, frame};
    gf_status st = gf_packing_read_frames_pass(path, gf_snapshot_keep, &pick);
    if (st == GF_OK && s->frames == 0) st = gf_error_set(GF_ERR_FORMAT, "%s: no frame in the file", path);
    if (st == GF_OK && frame >= 0 && (size_t)frame >= s->frames)
        st = gf_error_set(GF_ERR_PARAM, "%s has %zu frame%s: there is no frame %ld", path, s->frames,
                          s->frames == 1 ? "" : "s", frame);
    if (st != GF_OK) {
        gf_snapshot_destroy(s);
        return st;
    }
    *out = s;
    return GF_OK;
}

void gf_snapshot_destroy(gf_snapshot *s)
{
    if (!s) return;
    gf_snapshot_clear(s);
    gf_free(s, sizeof *s);
}

size_t gf_snapshot_count(const gf_snapshot *s) { return s->pk.n; }

size_t gf_snapshot_frames(const gf_snapshot *s) { return s->frames; }

double gf_snapshot_time(const gf_snapshot *s) { return s->info.have_time ? s->info.time : NAN; }

int64_t gf_snapshot_step(const gf_snapshot *s) { return (int64_t)s->info.timestep; }

int gf_snapshot_box(const gf_snapshot *s, double lo[3], double hi[3])
{
    if (!s->info.have_box) return 0;
    memcpy(lo, s->info.lo, sizeof s->info.lo);
    memcpy(hi, s->info.hi, sizeof s->info.hi);
    return 1;
}

gf_status gf_snapshot_copy(const gf_snapshot *s, int64_t *id, int32_t *type, double *xyz, double *radius,
                           int32_t *pass, size_t cap, size_t *n)
{
    const gf_packing *p = &s->pk;
    if (p->n > cap) return gf_error_set(GF_ERR_PARAM, "gf_snapshot_copy: %zu particles, room for %zu", p->n, cap);
    for (size_t i = 0; i < p->n; i++) {
        if (id) id[i] = p->id[i];
        if (type) type[i] = p->layer[i];
        if (radius) radius[i] = p->r[i];
        if (pass) pass[i] = s->pass ? s->pass[i] : 1;
        if (xyz) {
            xyz[3 * i] = p->x[i];
            xyz[3 * i + 1] = p->y[i];
            xyz[3 * i + 2] = p->z[i];
        }
    }
    if (n) *n = p->n;
    return GF_OK;
}
