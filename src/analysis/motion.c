// SPDX-License-Identifier: MIT
// Particle motion between snapshots: id matching (particles leave through the
// orifice, so frames shrink), velocities between frames, the binned mean field.
#include "analysis/motion.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "core/stop.h"

static int gf_idmap_cmp(const void *pa, const void *pb)
{
    const struct gf_idmap_entry *a = pa, *b = pb;
    return (a->id > b->id) - (a->id < b->id);
}

gf_status gf_idmap_build(const gf_packing *pk, gf_idmap *m)
{
    memset(m, 0, sizeof *m);
    if (pk->n == 0) return GF_OK;
    m->e = GF_NEW(struct gf_idmap_entry, pk->n);
    if (!m->e) return gf_error_set(GF_ERR_NOMEM, "out of memory for an id map of %zu particles", pk->n);
    m->n = pk->n;
    for (size_t i = 0; i < pk->n; i++) {
        m->e[i].id = pk->id[i];
        m->e[i].idx = i;
    }
    qsort(m->e, m->n, sizeof *m->e, gf_idmap_cmp);
    for (size_t i = 1; i < m->n; i++)
        if (m->e[i].id == m->e[i - 1].id) {
            int64_t id = m->e[i].id;
            gf_idmap_free(m);
            return gf_error_set(GF_ERR_PARAM, "particle id %lld occurs twice in one frame", (long long)id);
        }
    return GF_OK;
}

size_t gf_idmap_find(const gf_idmap *m, int64_t id)
{
    size_t lo = 0, hi = m->n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (m->e[mid].id < id) lo = mid + 1;
        else hi = mid;
    }
    return lo < m->n && m->e[lo].id == id ? m->e[lo].idx : SIZE_MAX;
}

void gf_idmap_free(gf_idmap *m)
{
    if (m->e) GF_DELETE(m->e, m->n);
    memset(m, 0, sizeof *m);
}

size_t gf_window_frames(const gf_series *s, double t0, double t1, size_t *k0, size_t *k1)
{
    double eps = 1e-9 * fmax(1.0, fmax(fabs(t0), fabs(t1)));
    size_t a = 0;
    while (a < s->nframes && s->frames[a].time < t0 - eps) a++;
    size_t b = a;
    while (b < s->nframes && s->frames[b].time <= t1 + eps) b++;
    *k0 = a;
    *k1 = b;
    return b - a;
}

/// Room for n steps; the old contents are dropped (st->n is reset by the caller).
static gf_status gf_steps_reserve(gf_steps *st, size_t n)
{
    if (n <= st->cap) return GF_OK;
    gf_steps_free(st);
    double **arr[6] = {&st->x, &st->y, &st->z, &st->vx, &st->vy, &st->vz};
    st->cap = n;
    for (size_t k = 0; k < 6; k++) {
        *arr[k] = GF_NEW(double, n);
        if (!*arr[k]) {
            gf_steps_free(st); // frees the ones allocated so far (gf_free of NULL is skipped)
            return gf_error_set(GF_ERR_NOMEM, "out of memory for %zu particle velocities", n);
        }
    }
    return GF_OK;
}

gf_status gf_steps_between(const gf_frame *a, const gf_frame *b, gf_steps *st)
{
    double dt = b->time - a->time;
    if (!(dt > 0.0))
        return gf_error_set(GF_ERR_PARAM, "frames at t = %g and %g are not in time order", a->time, b->time);
    st->n = 0;
    st->dt = dt;
    gf_idmap m;
    gf_status rc = gf_idmap_build(&a->pk, &m);
    if (rc != GF_OK) return rc;
    rc = gf_steps_reserve(st, b->pk.n);
    if (rc != GF_OK) {
        gf_idmap_free(&m);
        return rc;
    }
    const gf_packing *pa = &a->pk, *pb = &b->pk;
    for (size_t j = 0; j < pb->n; j++) {
        size_t i = gf_idmap_find(&m, pb->id[j]);
        if (i == SIZE_MAX || pb->z[j] - pa->z[i] > GF_MOTION_JUMP) continue;
        size_t k = st->n++;
        st->x[k] = 0.5 * (pa->x[i] + pb->x[j]);
        st->y[k] = 0.5 * (pa->y[i] + pb->y[j]);
        st->z[k] = 0.5 * (pa->z[i] + pb->z[j]);
        st->vx[k] = (pb->x[j] - pa->x[i]) / dt;
        st->vy[k] = (pb->y[j] - pa->y[i]) / dt;
        st->vz[k] = (pb->z[j] - pa->z[i]) / dt;
    }
    gf_idmap_free(&m);
    return GF_OK;
}

void gf_steps_free(gf_steps *st)
{
    double *arr[6] = {st->x, st->y, st->z, st->vx, st->vy, st->vz};
    for (size_t k = 0; k < 6; k++)
        if (arr[k]) gf_free(arr[k], sizeof(double) * st->cap);
    memset(st, 0, sizeof *st);
}

gf_status gf_vfield_init(gf_vfield *f, const gf_series *s, size_t k0, size_t k1, double bin, bool radial)
{
    memset(f, 0, sizeof *f);
    if (!(bin > 0.0)) return gf_error_set(GF_ERR_PARAM, "velocity bin must be positive, got %g", bin);
    double xlo = INFINITY, xhi = -INFINITY, zlo = INFINITY, zhi = -INFINITY;
    double far = -1.0; // the particle farthest from the origin, named when the field is too large
    size_t far_k = k0, far_i = 0;
    for (size_t k = k0; k < k1; k++) {
        const gf_packing *pk = &s->frames[k].pk;
        for (size_t i = 0; i < pk->n; i++) {
            double x = radial ? hypot(pk->x[i], pk->y[i]) : pk->x[i];
            xlo = fmin(xlo, x);
            xhi = fmax(xhi, x);
            zlo = fmin(zlo, pk->z[i]);
            zhi = fmax(zhi, pk->z[i]);
            double d = fmax(fabs(x), fabs(pk->z[i]));
            if (d > far) {
                far = d;
                far_k = k;
                far_i = i;
            }
        }
    }
    f->bin = bin;
    f->radial = radial;
    if (!(xlo <= xhi) || !(zlo <= zhi)) return GF_OK; // no particles: an empty field
    double nx = floor(xhi / bin) - floor(xlo / bin) + 1.0, nz = floor(zhi / bin) - floor(zlo / bin) + 1.0;
    if (!(nx * nz <= 1e8)) {
        const gf_packing *pk = &s->frames[far_k].pk;
        return gf_error_set(GF_ERR_PARAM,
                            "velocity field of %.3g x %.3g bins of %g d is too large: particle id %lld at (%g, %g, "
                            "%g) in the snapshot at t = %g tau is that far out",
                            nx, nz, bin, (long long)pk->id[far_i], pk->x[far_i], pk->y[far_i], pk->z[far_i],
                            s->frames[far_k].time);
    }
    f->ix0 = (long)floor(xlo / bin);
    f->iz0 = (long)floor(zlo / bin);
    f->nx = (size_t)nx;
    f->nz = (size_t)nz;
    f->sum = GF_NEW(double, 4 * f->nx * f->nz);
    if (!f->sum) return gf_error_set(GF_ERR_NOMEM, "out of memory for a %zu x %zu velocity field", f->nx, f->nz);
    return GF_OK;
}

/// Bin index of (x, z), or SIZE_MAX outside the field.
static size_t gf_vfield_cell(const gf_vfield *f, double x, double z)
{
    double i = floor(x / f->bin) - (double)f->ix0, k = floor(z / f->bin) - (double)f->iz0;
    if (!(i >= 0.0 && i < (double)f->nx && k >= 0.0 && k < (double)f->nz)) return SIZE_MAX;
    return (size_t)k * f->nx + (size_t)i;
}

void gf_vfield_add(gf_vfield *f, const gf_steps *st)
{
    for (size_t j = 0; j < st->n; j++) {
        if (f->radial) {
            // (v_r, v_theta) at the step's midpoint azimuth; on the axis any azimuth.
            double r = hypot(st->x[j], st->y[j]);
            double c = r > 0.0 ? st->x[j] / r : 1.0, sn = r > 0.0 ? st->y[j] / r : 0.0;
            size_t cr = gf_vfield_cell(f, r, st->z[j]);
            if (cr == SIZE_MAX) continue;
            double *b = f->sum + 4 * cr;
            b[0] += c * st->vx[j] + sn * st->vy[j];
            b[1] += c * st->vy[j] - sn * st->vx[j];
            b[2] += st->vz[j];
            b[3] += 1.0;
            continue;
        }
        size_t c = gf_vfield_cell(f, st->x[j], st->z[j]);
        if (c == SIZE_MAX) continue;
        double *b = f->sum + 4 * c;
        b[0] += st->vx[j];
        b[1] += st->vy[j];
        b[2] += st->vz[j];
        b[3] += 1.0;
    }
}

double gf_vfield_at(const gf_vfield *f, double x, double z, double v[3])
{
    size_t c = f->sum ? gf_vfield_cell(f, x, z) : SIZE_MAX;
    if (c == SIZE_MAX) return 0.0;
    const double *b = f->sum + 4 * c;
    if (b[3] > 0.0)
        for (int d = 0; d < 3; d++) v[d] = b[d] / b[3];
    return b[3];
}

double gf_vfield_mean(const gf_vfield *f, double x, double y, double z, double v[3])
{
    if (!f->radial) return gf_vfield_at(f, x, z, v);
    double r = hypot(x, y), m[3];
    double n = gf_vfield_at(f, r, z, m);
    if (!(n > 0.0)) return n;
    double c = r > 0.0 ? x / r : 1.0, sn = r > 0.0 ? y / r : 0.0;
    v[0] = c * m[0] - sn * m[1];
    v[1] = sn * m[0] + c * m[1];
    v[2] = m[2];
    return n;
}

void gf_vfield_free(gf_vfield *f)
{
    if (f->sum) GF_DELETE(f->sum, 4 * f->nx * f->nz);
    memset(f, 0, sizeof *f);
}

gf_status gf_vfield_window(const gf_series *s, double t0, double t1, double bin, bool radial,
                           volatile sig_atomic_t *stop, gf_vfield *f, size_t *pairs)
{
    size_t k0, k1;
    gf_window_frames(s, t0, t1, &k0, &k1);
    *pairs = 0;
    gf_status rc = gf_vfield_init(f, s, k0, k1, bin, radial);
    gf_steps st = {0};
    for (size_t k = k0; rc == GF_OK && k + 1 < k1; k++) {
        if ((rc = gf_stop_check(stop, "velocity field")) != GF_OK) break;
        rc = gf_steps_between(&s->frames[k], &s->frames[k + 1], &st);
        if (rc != GF_OK) break;
        gf_vfield_add(f, &st);
        (*pairs)++;
    }
    gf_steps_free(&st);
    if (rc != GF_OK) gf_vfield_free(f);
    return rc;
}
