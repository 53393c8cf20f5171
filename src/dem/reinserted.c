// SPDX-License-Identifier: MIT
// exits.csv of a recirculating DEM run (run.recirculate = on; issue 27): its
// in.drain (lammps_recirculate.c) appends a line to reinserted.txt for each
// particle it puts back, `id time x y z vz x_new y_new z_new` (where it was
// below the orifice, z, and its vertical velocity there); this turns them into
// the exits.csv a recirculating spot run writes (src/run/rundir.c:
// id,time,x,y,pass,entry_time,entry_r, sorted by time then id), so that
// analyze, calibrate and compare read the DEM's outflow and residence times
// from exact exits rather than off the snapshots, which a count that stays
// constant would hide. LAMMPS puts a particle back some time after it
// crossed the exit plane (it is then 2 d or more below the base, and LAMMPS
// looks every 0.1 tau); its exit time is when it crossed, from its height
// and velocity at the reinsertion by free fall back up to the exit plane
// (gf_reins_fall), so that residence times compare with a spot run's.
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/alloc.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/textscan.h"
#include "dem/dem_internal.h"
#include "granflow/exit.h"
#include "granflow/particles.h"

/// One line of reinserted.txt: the exit and where the particle went.
typedef struct gf_reins {
    gf_exit e;
    double t_back;  ///< when it was put back, tau
    double px, py;  ///< where
} gf_reins;

/// An id with the index of its line (or packing row) and a radius from the axis.
typedef struct gf_idr {
    int64_t id;
    size_t k;
    double r;
} gf_idr;

static int gf_idr_cmp_id(const void *pa, const void *pb)
{
    const gf_idr *a = pa, *b = pb;
    return (a->id > b->id) - (a->id < b->id);
}

/// By id, then by index (the lines' time order; a packing's file order).
static int gf_idr_cmp(const void *pa, const void *pb)
{
    int c = gf_idr_cmp_id(pa, pb);
    if (c) return c;
    const gf_idr *a = pa, *b = pb;
    return (a->k > b->k) - (a->k < b->k);
}

/// How long ago a particle now `h` below the exit plane, falling at speed
/// u (> 0 down), crossed it in free fall (g = 1): h = u t - t^2 / 2, the
/// smaller root; when collisions slowed it below free fall (u^2 < 2 h), the
/// root's vertex t = u, and 0 for a particle not below the plane.
double gf_dem_fall_time(double h, double u)
{
    if (!(h > 0.0) || !(u > 0.0)) return 0.0;
    double disc = u * u - 2.0 * h;
    return disc >= 0.0 ? u - sqrt(disc) : u;
}

static int gf_reins_cmp(const void *pa, const void *pb)
{
    const gf_reins *a = pa, *b = pb;
    if (a->e.time != b->e.time) return a->e.time < b->e.time ? -1 : 1;
    return (a->e.id > b->e.id) - (a->e.id < b->e.id);
}

/// Reads reinserted.txt (its first line names the exit plane). A last line
/// cut short (LAMMPS stopped while writing it) is dropped; any other line
/// that is not 9 numbers is an error.
static gf_status gf_reins_read(const char *path, gf_reins **out, size_t *n, size_t *capacity)
{
    gf_textscan ts;
    gf_status st = gf_textscan_open_regular(&ts, path, 0);
    size_t cap = 0, cnt = 0;
    gf_reins *a = NULL;
    double z_exit = NAN;
    while (st == GF_OK) {
        char *line, *tok[10];
        size_t len;
        int r = gf_textscan_next(&ts, &line, &len, &st);
        if (r <= 0) break;
        const char *s = gf_textscan_skip_blank(line);
        if (ts.line == 1 && sscanf(s, "# granflow reinsertions, exit plane z = %lf", &z_exit) != 1) {
            st = gf_error_set(GF_ERR_FORMAT, "%s:1: expected '# granflow reinsertions, exit plane z = Z'", path);
            break;
        }
        if (!*s || *s == '#') continue;
        size_t nt = gf_textscan_split(line, tok, 10);
        double v[9];
        long long id = 0;
        bool ok = nt == 9 && gf_textscan_int(tok[0], &id) == 0 && id > 0;
        for (size_t k = 1; ok && k < 9; k++) ok = gf_textscan_double(tok[k], &v[k]) == 0;
        if (!ok) {
            if (ts.partial) break; // the last line, cut off
            st = gf_error_set(GF_ERR_FORMAT, "%s:%ld: expected 'id time x y z vz x_new y_new z_new' (9 numbers)", path,
                              ts.line);
            break;
        }
        if (cnt == cap) {
            size_t nc = cap ? 2 * cap : 256;
            gf_reins *b = gf_realloc(a, sizeof *a * cap, sizeof *a * nc);
            if (!b) {
                st = gf_error_set(GF_ERR_NOMEM, "%s: out of memory at line %ld", path, ts.line);
                break;
            }
            a = b;
            cap = nc;
        }
        const double back = gf_dem_fall_time(z_exit - v[4], -v[5]);
        a[cnt++] = (gf_reins){.e = {.id = id, .time = v[1] - back, .x = v[2], .y = v[3]},
                              .t_back = v[1], .px = v[6], .py = v[7]};
    }
    gf_textscan_close(&ts);
    if (st == GF_OK && isnan(z_exit))
        st = gf_error_set(GF_ERR_FORMAT, "%s: empty, expected '# granflow reinsertions, exit plane z = Z'", path);
    if (st != GF_OK) {
        if (a) GF_DELETE(a, cap);
        return st;
    }
    *out = a;
    *n = cnt;
    *capacity = cap;
    return GF_OK;
}

gf_status gf_dem_write_exits(const char *dir)
{
    char path[GF_PATH_MAX + 64], tmp[GF_PATH_MAX + 80];
    snprintf(path, sizeof path, "%s/%s", dir, GF_DEM_REINSERTED);
    if (access(path, F_OK) != 0) return GF_OK; // no recirculation (or nothing ran)
    gf_reins *a = NULL;
    size_t n = 0, cap = 0;
    gf_status st = gf_reins_read(path, &a, &n, &cap);
    if (st != GF_OK) return st;
    if (n) qsort(a, n, sizeof *a, gf_reins_cmp); // a header alone: no lines, a NULL array
    // Where each pass began: pass 1 at t = 0 where the particle stood in the
    // settled packing (packing.dump), then where it was put back. The lines
    // are walked by (id, time) through a sorted index, not tables indexed by
    // id: a broken file's id of 10^18 must not size an allocation.
    gf_packing pk = {0};
    snprintf(path, sizeof path, "%s/packing.dump", dir);
    bool have_pk = gf_packing_read(path, GF_FORMAT_LAMMPS, &pk) == GF_OK;
    if (!have_pk)
        gf_warn("%s: cannot read it (%s): the first pass of each particle in exits.csv starts where it first left "
                "(entry_r)",
                path, gf_last_error());
    gf_idr *start = have_pk && pk.n ? GF_NEW(gf_idr, pk.n) : NULL;
    gf_idr *by_id = n ? GF_NEW(gf_idr, n) : NULL;
    if ((have_pk && pk.n && !start) || (n && !by_id)) {
        st = gf_error_set(GF_ERR_NOMEM, "%s/exits.csv: out of memory", dir);
        goto done;
    }
    for (size_t i = 0; start && i < pk.n; i++) start[i] = (gf_idr){.id = pk.id[i], .k = i, .r = hypot(pk.x[i], pk.y[i])};
    if (start) qsort(start, pk.n, sizeof *start, gf_idr_cmp);
    for (size_t k = 0; k < n; k++) by_id[k] = (gf_idr){.id = a[k].e.id, .k = k};
    if (by_id) qsort(by_id, n, sizeof *by_id, gf_idr_cmp); // by id, then time order (k)
    for (size_t g = 0; g < n; g++) {
        gf_exit *e = &a[by_id[g].k].e;
        if (g > 0 && by_id[g - 1].id == e->id) { // a later pass: from where the last one put it back
            const gf_reins *prev = &a[by_id[g - 1].k];
            e->pass = prev->e.pass + 1;
            e->entry_time = prev->t_back;
            e->entry_r = hypot(prev->px, prev->py);
            continue;
        }
        gf_idr key = {.id = e->id};
        const gf_idr *at = start ? bsearch(&key, start, pk.n, sizeof *start, gf_idr_cmp_id) : NULL;
        e->pass = 1;
        e->entry_time = 0.0;
        e->entry_r = at ? at->r : hypot(e->x, e->y);
    }
    FILE *f;
    snprintf(path, sizeof path, "%s/exits.csv", dir);
    if ((st = gf_atomic_open(path, tmp, sizeof tmp, &f)) != GF_OK) goto done;
    fputs("id,time,x,y,pass,entry_time,entry_r\n", f);
    for (size_t k = 0; k < n; k++) {
        const gf_exit *e = &a[k].e;
        // The format of a spot run's exits.csv (src/run/rundir.c, gf_print_exit).
        fprintf(f, "%lld,%.9g,%.7f,%.7f,%lld,%.9g,%.7f\n", (long long)e->id, e->time, e->x, e->y,
                (long long)e->pass, e->entry_time, e->entry_r);
    }
    st = gf_atomic_commit(f, tmp, path);
done:
    if (start) GF_DELETE(start, pk.n);
    if (by_id) GF_DELETE(by_id, n);
    if (a) GF_DELETE(a, cap);
    gf_packing_free(&pk);
    return st;
}
