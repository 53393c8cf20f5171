// SPDX-License-Identifier: MIT
// A time series of snapshots and the exits of a run: what every measurement reads.
//
// gf_series_load accepts three inputs:
//  - a run directory (DIR/snapshots/ exists): the dumps in DIR/snapshots;
//  - any other directory: the dumps in it (regular files named *.dump,
//    *.lammpstrj, *.txt or dump.*, hidden files skipped), read in name order;
//  - one LAMMPS dump file, with one or many frames.
// In the two directory cases DIR/config.ini and DIR/exits.csv are read when
// present. Frames are sorted by time (ITEM: TIME, else TIMESTEP x dump_dt);
// two frames at the same time are an error.
//
// Without config.ini the container is fitted to the particles: granflow's
// container is centred on x = y = 0, so a BOX BOUNDS not centred there (a DEM
// box 0..50, say) is moved there (every frame's x and y, and the exits', are
// shifted by minus the box centre); then the walls are put where the
// particles end (gf_series_fit_walls): a DEM box is the simulation's domain,
// often wider than the silo's walls. Dumps in other units than d and tau are
// converted as they are read (gf_series_opts.units: dump.diameter, dump.gravity).
// Without a `type` column the layer tags are made from the first frame
// (1 + floor(z / packing.layer_thickness)) and carried to later frames by id.
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/alloc.h"
#include "core/error.h"
#include "core/stop.h"
#include "geom/container.h"
#include "granflow/analysis.h"
#include "granflow/defs.h"
#include "io/exits_read.h"
#include "io/packing_frames.h"
#include "core/textscan.h"
#include "packing/layer.h"

enum { GF_SERIES_PATH = GF_PATH_MAX + 512 };

void gf_series_free(gf_series *s)
{
    for (size_t k = 0; k < s->nframes; k++) gf_packing_free(&s->frames[k].pk);
    if (s->frames) GF_DELETE(s->frames, s->nframes);
    if (s->exits) GF_DELETE(s->exits, s->nexits);
    memset(s, 0, sizeof *s);
}

// ---------------------------------------------------------------------------
// Collecting frames from files.

typedef struct gf_load_frame {
    double time;          ///< tau
    size_t file, seq;     ///< which file, and the order read (for a stable sort)
    gf_packing_frame hdr; ///< timestep, line, box, type column
    gf_packing pk;
} gf_load_frame;

typedef struct gf_loader {
    char (*files)[GF_SERIES_PATH];
    size_t nfiles, cap_files;
    gf_load_frame *fr;
    size_t nfr, cap_fr;
    size_t cur; ///< file being read
    double dump_dt;     ///< the dumps' time per TIMESTEP, in their time unit
    double length_unit; ///< the particle diameter in the dumps' length unit
    double time_unit;   ///< tau in the dumps' time unit
    volatile sig_atomic_t *stop; ///< polled at every frame (may be NULL)
} gf_loader;

static void gf_loader_free(gf_loader *L)
{
    for (size_t k = 0; k < L->nfr; k++) gf_packing_free(&L->fr[k].pk);
    if (L->fr) GF_DELETE(L->fr, L->cap_fr);
    if (L->files) GF_DELETE(L->files, L->cap_files);
    memset(L, 0, sizeof *L);
}

static gf_status gf_loader_add_file(gf_loader *L, const char *dir, const char *name)
{
    if (L->nfiles == L->cap_files) {
        size_t nc = L->cap_files ? 2 * L->cap_files : 16;
        void *p = gf_realloc(L->files, sizeof *L->files * L->cap_files, sizeof *L->files * nc);
        if (!p) return gf_error_set(GF_ERR_NOMEM, "out of memory listing %s", dir ? dir : name);
        L->files = p;
        L->cap_files = nc;
    }
    int w = dir ? snprintf(L->files[L->nfiles], GF_SERIES_PATH, "%s/%s", dir, name)
                : snprintf(L->files[L->nfiles], GF_SERIES_PATH, "%s", name);
    if (w < 0 || w >= GF_SERIES_PATH) return gf_error_set(GF_ERR_PARAM, "path too long: %s/%s", dir ? dir : "", name);
    L->nfiles++;
    return GF_OK;
}

static gf_status gf_loader_on_frame(void *ctx, const gf_packing_frame *f, gf_packing *pk)
{
    gf_loader *L = ctx;
    const char *path = L->files[L->cur];
    gf_status stop = gf_stop_check(L->stop, "reading the snapshots");
    if (stop != GF_OK) return stop;
    double t = f->time;
    if (!f->have_time) {
        if (!(L->dump_dt > 0))
            return gf_error_set(GF_ERR_PARAM,
                                "%s:%ld: the frame at timestep %lld has no ITEM: TIME; pass dump.dt "
                                "(the time per TIMESTEP in the dump's unit: tau, or seconds with "
                                "dump.diameter and dump.gravity in SI) to turn its TIMESTEP into a time",
                                path, f->line, f->timestep);
        t = (double)f->timestep * L->dump_dt;
    }
    t /= L->time_unit;
    if (L->nfr == L->cap_fr) {
        size_t nc = L->cap_fr ? 2 * L->cap_fr : 16;
        gf_load_frame *p = gf_realloc(L->fr, sizeof *p * L->cap_fr, sizeof *p * nc);
        if (!p) return gf_error_set(GF_ERR_NOMEM, "%s:%ld: out of memory for frames", path, f->line);
        L->fr = p;
        L->cap_fr = nc;
    }
    gf_load_frame *d = &L->fr[L->nfr];
    d->time = t;
    d->file = L->cur;
    d->seq = L->nfr;
    d->hdr = *f;
    d->pk = *pk; // take the particles; the reader starts a fresh packing
    memset(pk, 0, sizeof *pk);
    L->nfr++;
    return GF_OK;
}

static int gf_frame_cmp(const void *pa, const void *pb)
{
    const gf_load_frame *a = pa, *b = pb;
    if (a->time != b->time) return a->time < b->time ? -1 : 1;
    return (a->seq > b->seq) - (a->seq < b->seq);
}

static int gf_name_cmp(const void *a, const void *b) { return strcmp(a, b); }

static int gf_is_dump_name(const char *name)
{
    if (name[0] == '.') return 0;
    return gf_textscan_has_ext(name, ".dump") || gf_textscan_has_ext(name, ".lammpstrj") ||
           gf_textscan_has_ext(name, ".txt") ||
           (strncmp(name, "dump.", 5) == 0 && name[5] != '\0');
}

static int gf_is_dir(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0 && S_ISDIR(sb.st_mode);
}

static int gf_is_file(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0 && S_ISREG(sb.st_mode);
}

/// Lists the dumps of `dir` into L->files, in name order.
static gf_status gf_list_dumps(gf_loader *L, const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return gf_error_set(GF_ERR_IO, "cannot open directory %s: %s", dir, strerror(errno));
    gf_status st = GF_OK;
    bool vtu = false; // VTK snapshots only (output.format = vtk): say so
    for (struct dirent *e; st == GF_OK && (e = readdir(d)) != NULL;) {
        vtu = vtu || gf_textscan_has_ext(e->d_name, ".vtu");
        if (!gf_is_dump_name(e->d_name)) continue;
        char path[GF_SERIES_PATH];
        if (snprintf(path, sizeof path, "%s/%s", dir, e->d_name) >= (int)sizeof path) continue;
        if (!gf_is_file(path)) continue;
        st = gf_loader_add_file(L, dir, e->d_name);
    }
    closedir(d);
    if (st != GF_OK) return st;
    // Nothing to read where the command was pointed: a wrong directory or a
    // run made without dumps, so the command line (exit 2), not an I/O
    // failure (issue 26: both exited 1, "the run failed").
    if (L->nfiles == 0 && vtu)
        return gf_error_set(GF_ERR_PARAM,
                            "%s: only VTK (.vtu) snapshots, which are for ParaView: analysis and pictures read the "
                            "LAMMPS dumps (run with output.format = dump or both)",
                            dir);
    if (L->nfiles == 0)
        return gf_error_set(GF_ERR_PARAM,
                            "%s: no LAMMPS dumps in this directory (looked for *.dump, *.lammpstrj, *.txt, dump.*, each possibly .gz)",
                            dir);
    qsort(L->files, L->nfiles, sizeof *L->files, gf_name_cmp);
    return GF_OK;
}

// ---------------------------------------------------------------------------
// Layers and container.

typedef struct gf_id_layer {
    int64_t id;
    int32_t layer;
} gf_id_layer;

static int gf_id_layer_cmp(const void *pa, const void *pb)
{
    const gf_id_layer *a = pa, *b = pb;
    return (a->id > b->id) - (a->id < b->id);
}

/// Frames without a `type` column: tag the first frame by height, later ones by id.
static gf_status gf_series_fill_layers(gf_series *s, const gf_load_frame *src)
{
    gf_packing_defs pd;
    gf_config_packing_defs(&s->cfg, &pd);
    double thick = pd.layer_thickness > 0 ? pd.layer_thickness : 10.0;
    gf_packing *p0 = &s->frames[0].pk;
    if (!src[0].hdr.have_type) gf_packing_tag_layers(p0, thick);
    int need = 0;
    for (size_t k = 1; k < s->nframes; k++) need |= !src[k].hdr.have_type;
    if (!need || p0->n == 0) {
        for (size_t k = 1; k < s->nframes; k++)
            if (!src[k].hdr.have_type) gf_packing_tag_layers(&s->frames[k].pk, thick);
        return GF_OK;
    }
    gf_id_layer *map = GF_NEW(gf_id_layer, p0->n);
    if (!map) return gf_error_set(GF_ERR_NOMEM, "out of memory for the layer tags");
    for (size_t i = 0; i < p0->n; i++) map[i] = (gf_id_layer){p0->id[i], p0->layer[i]};
    qsort(map, p0->n, sizeof *map, gf_id_layer_cmp);
    for (size_t k = 1; k < s->nframes; k++) {
        if (src[k].hdr.have_type) continue;
        gf_packing *p = &s->frames[k].pk;
        for (size_t i = 0; i < p->n; i++) {
            gf_id_layer key = {p->id[i], 0};
            const gf_id_layer *hit = bsearch(&key, map, p0->n, sizeof *map, gf_id_layer_cmp);
            p->layer[i] = hit ? hit->layer : gf_packing_layer_of(p->z[i], thick);
        }
    }
    GF_DELETE(map, p0->n);
    return GF_OK;
}

/// The widest |coordinate| + radius of the particles of `s` at or above
/// the base `zmin`, along x (axis 0) or y (1); 0 when there is none.
static double gf_series_reach(const gf_series *s, int axis, double zmin)
{
    double m = 0.0;
    for (size_t k = 0; k < s->nframes; k++) {
        const gf_packing *p = &s->frames[k].pk;
        const double *c = axis ? p->y : p->x;
        for (size_t i = 0; i < p->n; i++)
            if (p->z[i] >= zmin) m = fmax(m, fabs(c[i]) + p->r[i]);
    }
    return m;
}

gf_status gf_series_fit_walls(const gf_series *s, gf_config *cfg)
{
    if (!s || !cfg) return gf_error_set(GF_ERR_PARAM, "gf_series_fit_walls: NULL series or config");
    const gf_container c = gf_container_make(cfg);
    if (!gf_container_rectangular(&c)) return GF_OK; // the walls of other shapes are not where particles reach
    static const char *const keys[2] = {"container.width", "container.depth"};
    for (int axis = 0; axis < 2; axis++) {
        if (gf_config_is_set(cfg, keys[axis])) continue;
        double half = gf_series_reach(s, axis, gf_config_exit_plane(cfg));
        if (!(half > 0)) continue;
        char kv[96];
        snprintf(kv, sizeof kv, "%s=%.17g", keys[axis], 2.0 * half);
        gf_status st = gf_config_set(cfg, kv, "particle extent");
        if (st != GF_OK) return st;
    }
    return GF_OK;
}

/// No config.ini: the papers' defaults, centred on the first frame's box,
/// with the walls where the particles end (or, with no particle above the
/// base in any frame, the box's).
static gf_status gf_series_fit_container(gf_series *s, const gf_packing_frame *h)
{
    gf_config c = gf_config_default();
    double cx = 0.0, cy = 0.0;
    if (h->have_box) {
        cx = 0.5 * (h->lo[0] + h->hi[0]);
        cy = 0.5 * (h->lo[1] + h->hi[1]);
    }
    // Shift a box not centred on x = y = 0 there (rounding-level offsets are left alone).
    double tol = 1e-9 * fmax(1.0, fmax(fabs(h->hi[0] - h->lo[0]), fabs(h->hi[1] - h->lo[1])));
    if (fabs(cx) > tol || fabs(cy) > tol) {
        for (size_t k = 0; k < s->nframes; k++) {
            gf_packing *p = &s->frames[k].pk;
            for (size_t i = 0; i < p->n; i++) {
                p->x[i] -= cx;
                p->y[i] -= cy;
            }
        }
        for (size_t k = 0; k < s->nexits; k++) {
            s->exits[k].x -= cx;
            s->exits[k].y -= cy;
        }
    }
    gf_status st = gf_series_fit_walls(s, &c);
    if (st != GF_OK) return st;
    static const char *const keys[2] = {"container.width", "container.depth"};
    for (int axis = 0; axis < 2 && h->have_box; axis++) {
        double w = h->hi[axis] - h->lo[axis];
        if (gf_config_is_set(&c, keys[axis]) || !(w > 0)) continue;
        char kv[96];
        snprintf(kv, sizeof kv, "%s=%.17g", keys[axis], w);
        if ((st = gf_config_set(&c, kv, "dump box")) != GF_OK) return st;
    }
    // Resolve derived defaults when the fitted box allows; a box too small for
    // the papers' orifice is still measurable, so its config is kept as it is.
    gf_config v = c;
    if (gf_config_validate(&v) == GF_OK) c = v;
    else gf_error_clear();
    s->cfg = c;
    return GF_OK;
}

// ---------------------------------------------------------------------------

static int gf_series_id_cmp(const void *a, const void *b)
{
    int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
    return (x > y) - (x < y);
}

// A particle of the first frame that is gone from the last one has left
// (without recirculation nothing else removes one), so exits.csv must list
// it by then. One that it does not list makes the outflow and residence
// times read from exits.csv short without a word (issue 26: 100 particles
// lost from the last frame, rc 0): warn, naming the frame and a particle.
static gf_status gf_series_check_exits(const gf_series *s, const char *last_file, const char *exits_path)
{
    gf_rundir_defs rd;
    gf_config_rundir_defs(&s->cfg, &rd);
    if (!s->has_exits || rd.recirculate || s->nframes < 2) return GF_OK;
    const gf_packing *first = &s->frames[0].pk, *last = &s->frames[s->nframes - 1].pk;
    const double t = s->frames[s->nframes - 1].time, slack = 1e-9 * fmax(1.0, fabs(t));
    size_t nl = last->n, ne = 0;
    int64_t *kept = GF_NEW(int64_t, nl ? nl : 1), *left = GF_NEW(int64_t, s->nexits ? s->nexits : 1);
    if (!kept || !left) {
        GF_DELETE(kept, nl ? nl : 1);
        GF_DELETE(left, s->nexits ? s->nexits : 1);
        return gf_error_set(GF_ERR_NOMEM, "out of memory checking %s", exits_path);
    }
    memcpy(kept, last->id, nl * sizeof *kept);
    for (size_t k = 0; k < s->nexits; k++)
        if (s->exits[k].time <= t + slack) left[ne++] = s->exits[k].id;
    qsort(kept, nl, sizeof *kept, gf_series_id_cmp);
    qsort(left, ne, sizeof *left, gf_series_id_cmp);
    size_t missing = 0;
    int64_t example = 0;
    for (size_t i = 0; i < first->n; i++) {
        const int64_t id = first->id[i];
        if (bsearch(&id, kept, nl, sizeof *kept, gf_series_id_cmp) ||
            bsearch(&id, left, ne, sizeof *left, gf_series_id_cmp))
            continue;
        if (missing++ == 0) example = id;
    }
    GF_DELETE(kept, nl ? nl : 1);
    GF_DELETE(left, s->nexits ? s->nexits : 1);
    if (missing)
        gf_warn("%s (t = %.6g tau): %zu particles of the first frame are gone (id %lld, ...) but %s does not list "
                "them leaving by then: it is incomplete or from another run, and the outflow and residence times "
                "read from it miss them",
                last_file, t, missing, (long long)example, exits_path);
    return GF_OK;
}

/// Whether `path` is a spot run's summary.json (it counts spot moves; a DEM
/// run directory has none). Only its first 4 KB are read: the counters come first.
static bool gf_series_is_spot_run(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return false;
    char buf[4097];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = 0;
    return strstr(buf, "\"spot_moves\"") != NULL;
}

static gf_status gf_series_build(gf_loader *L, const char *dir, gf_series *s)
{
    qsort(L->fr, L->nfr, sizeof *L->fr, gf_frame_cmp);
    for (size_t k = 1; k < L->nfr; k++)
        if (L->fr[k].time == L->fr[k - 1].time) {
            const gf_load_frame *a = &L->fr[k - 1], *b = &L->fr[k];
            return gf_error_set(GF_ERR_FORMAT,
                                "two frames at the same time %.10g tau: %s:%ld (timestep %lld) and %s:%ld "
                                "(timestep %lld)",
                                a->time, L->files[a->file], a->hdr.line, a->hdr.timestep, L->files[b->file],
                                b->hdr.line, b->hdr.timestep);
        }
    gf_status st = GF_OK;
    char path[GF_SERIES_PATH];
    bool have_cfg = false;
    s->cfg = gf_config_default();
    if (dir) {
        snprintf(path, sizeof path, "%s/config.ini", dir);
        if (gf_is_file(path)) {
            have_cfg = s->has_config = true;
            st = gf_config_load(&s->cfg, path);
            if (st == GF_OK) st = gf_config_validate(&s->cfg);
            if (st != GF_OK) return st;
        }
        snprintf(path, sizeof path, "%s/summary.json", dir);
        s->spot_run = gf_series_is_spot_run(path);
        snprintf(path, sizeof path, "%s/exits.csv", dir);
        if (gf_is_file(path)) {
            st = gf_exits_read(path, &s->exits, &s->nexits);
            if (st != GF_OK) return st;
            s->has_exits = true;
            for (size_t k = 0; k < s->nexits; k++) { // in the dumps' units, as they are
                gf_exit *e = &s->exits[k];
                e->time /= L->time_unit;
                e->entry_time /= L->time_unit;
                e->x /= L->length_unit;
                e->y /= L->length_unit;
                e->entry_r /= L->length_unit;
            }
        }
    }
    s->frames = GF_NEW(gf_frame, L->nfr);
    if (!s->frames) return gf_error_set(GF_ERR_NOMEM, "out of memory for %zu frames", L->nfr);
    s->nframes = L->nfr;
    for (size_t k = 0; k < L->nfr; k++) {
        s->frames[k].time = L->fr[k].time;
        s->frames[k].pk = L->fr[k].pk;
        memset(&L->fr[k].pk, 0, sizeof L->fr[k].pk);
    }
    s->n_initial = s->frames[0].pk.n;
    if (!have_cfg && (st = gf_series_fit_container(s, &L->fr[0].hdr)) != GF_OK) return st;
    st = gf_series_fill_layers(s, L->fr);
    if (st == GF_OK && dir) {
        snprintf(path, sizeof path, "%s/exits.csv", dir);
        st = gf_series_check_exits(s, L->files[L->fr[L->nfr - 1].file], path);
    }
    return st;
}

gf_series_opts gf_series_opts_default(void) { return (gf_series_opts){.units = NULL}; }

gf_status gf_series_load(const char *path, double dump_dt, const gf_series_opts *opts, gf_series *out)
{
    const gf_series_units *units = opts ? opts->units : NULL;
    volatile sig_atomic_t *stop = opts ? opts->stop : NULL;
    memset(out, 0, sizeof *out);
    if (!path || !*path) return gf_error_set(GF_ERR_PARAM, "gf_series_load: no path");
    if (!(dump_dt >= 0) || !isfinite(dump_dt))
        return gf_error_set(GF_ERR_PARAM, "dump.dt = %g must be a finite number >= 0", dump_dt);
    const gf_series_units u = units ? *units : (gf_series_units){1.0, 1.0};
    if (!(u.diameter > 0 && u.gravity > 0 && isfinite(u.diameter) && isfinite(u.gravity)))
        return gf_error_set(GF_ERR_PARAM, "dump.diameter = %g and dump.gravity = %g must be positive numbers",
                            u.diameter, u.gravity);
    gf_loader L = {.dump_dt = dump_dt, .stop = stop, .length_unit = u.diameter,
                   .time_unit = sqrt(u.diameter / u.gravity)};
    gf_status st = GF_OK;
    const char *dir = NULL;
    struct stat sb;
    if (stat(path, &sb) != 0) return gf_error_set(GF_ERR_IO, "cannot open %s: %s", path, strerror(errno));
    if (S_ISDIR(sb.st_mode)) {
        char snaps[GF_SERIES_PATH];
        if (snprintf(snaps, sizeof snaps, "%s/snapshots", path) >= (int)sizeof snaps)
            return gf_error_set(GF_ERR_PARAM, "path too long: %s", path);
        dir = path;
        st = gf_list_dumps(&L, gf_is_dir(snaps) ? snaps : path);
    } else {
        st = gf_loader_add_file(&L, NULL, path);
    }
    for (L.cur = 0; st == GF_OK && L.cur < L.nfiles; L.cur++)
        st = gf_packing_read_frames_in(L.files[L.cur], L.length_unit, gf_loader_on_frame, &L);
    if (st == GF_OK) st = gf_series_build(&L, dir, out);
    gf_loader_free(&L);
    if (st != GF_OK) gf_series_free(out);
    return st;
}
