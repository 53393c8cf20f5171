// SPDX-License-Identifier: MIT
// Exits read off the snapshots of a drain (SPEC 1.6, 1.8: residence times of
// a DEM run, whose LAMMPS dumps come without exits.csv). A particle present
// in frame k and absent from frame k + 1 (deleted, or dropped by the reader
// for being below the exit plane) left between the two: its exit time is the
// midpoint (t_k + t_k+1) / 2, within +- half that frame interval of the true
// crossing, and (x, y) its position in frame k. Only a particle's first
// disappearance counts (one that comes back is not followed again).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "granflow/analysis.h"

static int gf_derive_by_id_time(const void *pa, const void *pb)
{
    const gf_exit *a = pa, *b = pb;
    if (a->id != b->id) return a->id < b->id ? -1 : 1;
    return (a->time > b->time) - (a->time < b->time);
}

static int gf_derive_by_time_id(const void *pa, const void *pb)
{
    const gf_exit *a = pa, *b = pb;
    if (a->time != b->time) return a->time < b->time ? -1 : 1;
    return (a->id > b->id) - (a->id < b->id);
}

/// Appends one exit, growing the array by doubling.
static gf_status gf_derive_push(gf_exit **e, size_t *n, size_t *cap, gf_exit x)
{
    if (*n == *cap) {
        size_t nc = *cap ? 2 * *cap : 256;
        gf_exit *p = gf_realloc(*e, sizeof *p * *cap, sizeof *p * nc);
        if (!p) return gf_error_set(GF_ERR_NOMEM, "out of memory for %zu exits", nc);
        *e = p;
        *cap = nc;
    }
    (*e)[(*n)++] = x;
    return GF_OK;
}

/// Keeps each id's first exit (e sorted by id, then time): returns the count kept.
static size_t gf_derive_first_only(gf_exit *e, size_t n)
{
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (m == 0 || e[m - 1].id != e[i].id) e[m++] = e[i];
    return m;
}

gf_status gf_series_derive_exits(gf_series *s)
{
    if (!s) return gf_error_set(GF_ERR_PARAM, "gf_series_derive_exits: NULL series");
    if (s->has_exits) return GF_OK; // exits.csv is exact: keep it
    gf_exit *e = NULL;
    size_t n = 0, cap = 0;
    double half = 0.0;
    gf_idmap first = {0}, next = {0};
    gf_status st = s->nframes ? gf_idmap_build(&s->frames[0].pk, &first) : GF_OK;
    const double t_first = s->nframes ? s->frames[0].time : 0.0;
    for (size_t k = 0; st == GF_OK && k + 1 < s->nframes; k++) {
        const gf_packing *a = &s->frames[k].pk;
        double ta = s->frames[k].time, tb = s->frames[k + 1].time;
        if ((st = gf_idmap_build(&s->frames[k + 1].pk, &next)) != GF_OK) {
            char why[256];
            snprintf(why, sizeof why, "%s", gf_last_error());
            gf_error_set(st, "the frame at t = %.10g tau: %s", tb, why);
            break;
        }
        size_t before = n;
        for (size_t i = 0; st == GF_OK && i < a->n; i++) {
            if (gf_idmap_find(&next, a->id[i]) != SIZE_MAX) continue;
            // Entry: the first frame, where the particle starts its only pass.
            size_t j = gf_idmap_find(&first, a->id[i]);
            const gf_packing *p0 = &s->frames[0].pk;
            gf_exit x = {.id = a->id[i],
                         .time = 0.5 * (ta + tb),
                         .x = a->x[i],
                         .y = a->y[i],
                         .pass = 1,
                         .entry_time = t_first,
                         .entry_r = j == SIZE_MAX ? NAN : hypot(p0->x[j], p0->y[j])};
            st = gf_derive_push(&e, &n, &cap, x);
        }
        if (n > before) half = fmax(half, 0.5 * (tb - ta));
        gf_idmap_free(&next);
    }
    gf_idmap_free(&first);
    if (st == GF_OK && n > 0) {
        qsort(e, n, sizeof *e, gf_derive_by_id_time);
        size_t m = gf_derive_first_only(e, n);
        qsort(e, m, sizeof *e, gf_derive_by_time_id);
        gf_exit *p = gf_realloc(e, sizeof *e * cap, sizeof *e * m); // exactly nexits (gf_series_free)
        if (!p) st = gf_error_set(GF_ERR_NOMEM, "out of memory for %zu exits", m);
        else {
            e = p;
            cap = n = m;
        }
    }
    if (st != GF_OK) {
        if (e) GF_DELETE(e, cap);
        return st;
    }
    s->exits = e;
    s->nexits = n;
    s->has_exits = true;
    s->exits_derived = true;
    s->exit_resolution = half;
    return GF_OK;
}
