// SPDX-License-Identifier: MIT
// gf_render_dir: the pictures of a run directory (or of LAMMPS dumps): which
// snapshots, which colouring, the contact sheet, and where the files go.
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "core/alloc.h"
#include "core/error.h"
#include "core/stop.h"
#include "granflow/defs.h"
#include "granflow/render.h"
#include "render/stress.h"

enum { GF_RENDER_PATH = GF_PATH_MAX + 64 };

gf_render_dir_opts gf_render_dir_opts_default(void)
{
    return (gf_render_dir_opts){.colour = GF_RENDER_LAYER, .format = "png", .scale = 10.0, .panels = 8};
}

/// The run's name for the pictures: the last component of its directory (NULL for . and ..).
static const char *gf_render_name(const char *dir, char *buf, size_t n)
{
    snprintf(buf, n, "%s", dir);
    size_t len = strlen(buf);
    while (len > 1 && buf[len - 1] == '/') buf[--len] = '\0';
    const char *slash = strrchr(buf, '/');
    const char *name = slash && slash[1] ? slash + 1 : buf;
    return strcmp(name, ".") && strcmp(name, "..") && strcmp(name, "/") ? name : NULL; // no useful name
}

static size_t gf_render_nearest(const gf_series *s, double t)
{
    size_t best = 0;
    for (size_t k = 1; k < s->nframes; k++)
        if (fabs(s->frames[k].time - t) < fabs(s->frames[best].time - t)) best = k;
    return best;
}

/// Radius of the averaged packing-fraction field, d (2009 paper Fig. 4; the
/// default of `analyze voronoi`, option voronoi.radius).
#define GF_RENDER_PHI_RADIUS 2.2

/// Length of a frame's packing-fraction array (one value at least).
static size_t gf_render_phi_len(const gf_packing *pk) { return pk->n ? pk->n : 1; }

/// Packing fractions of frame k (computed once, kept in phi[k]): the field
/// averaged within GF_RENDER_PHI_RADIUS, or with `raw` each particle's volume
/// over its Voronoi cell's. The cells' open top is 1 d above the highest
/// centre in the container, as `granflow analyze voronoi` has it, so the
/// pictures show the phi and phi_avg columns of its voronoi.csv.
static gf_status gf_render_phi(const gf_series *s, size_t k, bool raw, double **phi)
{
    if (phi[k]) return GF_OK;
    const gf_packing *pk = &s->frames[k].pk;
    phi[k] = GF_NEW(double, gf_render_phi_len(pk));
    if (!phi[k]) return gf_error_set(GF_ERR_NOMEM, "render: out of memory");
    gf_container_defs cd;
    gf_config_container_defs(&s->cfg, &cd);
    const double W = cd.width, D = cd.depth;
    if (!raw) return gf_voronoi_field(pk, W, D, NAN, GF_RENDER_PHI_RADIUS, phi[k]);
    double top = -INFINITY;
    for (size_t i = 0; i < pk->n; i++)
        if (pk->z[i] >= 0.0 && isfinite(pk->x[i]) && isfinite(pk->y[i])) top = fmax(top, pk->z[i] + 1.0);
    if (!isfinite(top)) { // nothing in the container: every value unknown
        for (size_t i = 0; i < pk->n; i++) phi[k][i] = NAN;
        return GF_OK;
    }
    return gf_voronoi_fraction(pk, W, D, top, phi[k]);
}

/// File-name suffix of a picture: "", "_phi" or "_phi_raw".
static const char *gf_render_suffix(gf_render_colour colour, bool raw)
{
    return colour != GF_RENDER_PHI ? "" : raw ? "_phi_raw" : "_phi";
}

typedef struct gf_render_job {
    const gf_render_dir_opts *o;
    const gf_series *s;
    double **phi;
    gf_render_opts opts;
    char outdir[GF_RENDER_PATH];
} gf_render_job;

static void gf_render_written(const gf_render_job *j, const char *path)
{
    if (j->o->written) j->o->written(j->o->ctx, path);
}

static gf_status gf_render_one(gf_render_job *j, size_t k, gf_render_colour colour)
{
    char path[GF_RENDER_PATH + 64];
    snprintf(path, sizeof path, "%s/slice_%06zu%s.%s", j->outdir, k, gf_render_suffix(colour, j->o->raw),
             j->o->format);
    gf_render_opts o = j->opts;
    o.colour = colour;
    gf_status st = gf_stop_check(j->o->stop, "render");
    if (st == GF_OK && colour == GF_RENDER_PHI) st = gf_render_phi(j->s, k, j->o->raw, j->phi);
    if (st == GF_OK) st = gf_render_slice(&j->s->frames[k].pk, j->s->frames[k].time, &j->s->cfg,
                                          j->phi[k], &o, path);
    if (st == GF_OK) gf_render_written(j, path);
    return st;
}

/// How many of n snapshots go on the sheet, at most `panels`: the largest
/// count from about half of `panels` up that splits the run into equal steps
/// of whole snapshots (11 snapshots, 8 panels: 6, every second one), else `panels`.
static size_t gf_render_panels(size_t panels, size_t n)
{
    if (n <= panels) return n;
    for (size_t m = panels; m >= 2 && 2 * m >= panels; m--)
        if ((n - 1) % (m - 1) == 0) return m;
    return panels;
}

static gf_status gf_render_contact_sheet(gf_render_job *j)
{
    const gf_series *s = j->s;
    const gf_render_dir_opts *c = j->o;
    size_t want = gf_render_panels(c->panels, s->nframes), n = 0;
    gf_frame *fr = GF_NEW(gf_frame, want);
    const double **phi = GF_NEW(const double *, want);
    gf_status st = fr && phi ? GF_OK : gf_error_set(GF_ERR_NOMEM, "render: out of memory");
    for (size_t k = 0; st == GF_OK && k < want; k++) { // evenly spaced, first and last included
        size_t idx = want == 1 ? s->nframes - 1 : (size_t)llround((double)k * (double)(s->nframes - 1) / (double)(want - 1));
        fr[n] = s->frames[idx]; // a shallow copy: the series keeps the particles
        if (c->colour == GF_RENDER_PHI && (st = gf_stop_check(c->stop, "render")) == GF_OK) {
            st = gf_render_phi(s, idx, c->raw, j->phi);
            phi[n] = j->phi[idx];
        }
        n++;
    }
    char path[GF_RENDER_PATH + 64];
    snprintf(path, sizeof path, "%s/sheet%s.%s", j->outdir, gf_render_suffix(c->colour, c->raw), c->format);
    gf_render_opts o = j->opts;
    o.colour = c->colour;
    o.px_per_d = fmax(1.0, 0.5 * c->scale);
    if (st == GF_OK) st = gf_render_sheet(fr, n, &s->cfg, c->colour == GF_RENDER_PHI ? phi : NULL, &o, path);
    if (st == GF_OK) gf_render_written(j, path);
    if (fr) GF_DELETE(fr, want);
    if (phi) GF_DELETE(phi, want);
    return st;
}

static gf_status gf_render_check(const gf_render_dir_opts *o)
{
    if (o->colour != GF_RENDER_LAYER && o->colour != GF_RENDER_PHI)
        return gf_error_set(GF_ERR_PARAM, "render: unknown colouring %d", (int)o->colour);
    if (!o->format || (strcmp(o->format, "png") && strcmp(o->format, "svg") && strcmp(o->format, "pdf")))
        return gf_error_set(GF_ERR_PARAM, "render: the format is png, svg or pdf, not '%s'",
                            o->format ? o->format : "(null)");
    if (!(o->scale >= 1 && o->scale <= 200))
        return gf_error_set(GF_ERR_PARAM, "render: the scale is 1 to 200 pixels per d, not %g", o->scale);
    if (o->panels < 1 || o->panels > 40)
        return gf_error_set(GF_ERR_PARAM, "render: a contact sheet has 1 to 40 panels, not %zu", o->panels);
    if (o->ntimes && !o->times) return gf_error_set(GF_ERR_PARAM, "render: %zu times but no array", o->ntimes);
    for (size_t t = 0; t < o->ntimes; t++)
        if (!isfinite(o->times[t])) return gf_error_set(GF_ERR_PARAM, "render: the times must be finite");
    if (o->all && o->ntimes) return gf_error_set(GF_ERR_PARAM, "render: every snapshot or chosen times, not both");
    return GF_OK;
}

// Where the pictures go: opts->outdir, else DIR/render, or render/ beside a dump file.
static gf_status gf_render_outdir(const char *dir, const gf_render_dir_opts *o, char *out, size_t n)
{
    struct stat sb;
    int w;
    if (o->outdir) {
        w = snprintf(out, n, "%s", o->outdir);
    } else if (stat(dir, &sb) == 0 && !S_ISDIR(sb.st_mode)) { // one dump file: render/ beside it
        const char *slash = strrchr(dir, '/');
        w = slash ? snprintf(out, n, "%.*s/render", (int)(slash - dir), dir) : snprintf(out, n, "render");
    } else {
        w = snprintf(out, n, "%s/render", dir);
    }
    if (w < 0 || (size_t)w >= n) return gf_error_set(GF_ERR_IO, "path too long: %s", out);
    return gf_fs_mkdirs(out);
}

// Which slices: every one, those nearest the times, or by default the first,
// middle and last by layer and the last by packing fraction; then the sheet.
static gf_status gf_render_pictures(gf_render_job *j)
{
    const gf_render_dir_opts *c = j->o;
    const gf_series *s = j->s;
    gf_status st = GF_OK;
    bool dflt = !c->all && !c->ntimes && !c->sheet;
    size_t last = s->nframes - 1;
    for (size_t k = 0; st == GF_OK && k < s->nframes; k++) {
        bool pick = c->all || (dflt && (k == 0 || k == last / 2 || k == last));
        for (size_t t = 0; t < c->ntimes && !pick; t++) pick = gf_render_nearest(s, c->times[t]) == k;
        if (pick) st = gf_render_one(j, k, c->colour);
    }
    for (size_t t = 0; st == GF_OK && t < c->ntimes; t++) {
        size_t k = gf_render_nearest(s, c->times[t]);
        if (fabs(s->frames[k].time - c->times[t]) > 1e-6 * fmax(1.0, fabs(c->times[t])))
            gf_warn("no snapshot at t = %g; drew the nearest, t = %g", c->times[t], s->frames[k].time);
    }
    if (st == GF_OK && dflt && c->colour == GF_RENDER_LAYER) st = gf_render_one(j, last, GF_RENDER_PHI);
    if (st == GF_OK && (dflt || c->sheet)) st = gf_render_contact_sheet(j);
    return st;
}

// A chosen time must lie within the run, give or take half the interval at
// its end: "the nearest snapshot" to t = 1e17 was whichever came first in
// the rounding (t = 0, issue 26), and any far time names no snapshot.
static gf_status gf_render_check_times(const char *dir, const gf_render_dir_opts *o, const gf_series *s)
{
    const size_t n = s->nframes;
    const double t0 = s->frames[0].time, t1 = s->frames[n - 1].time;
    const double before = n > 1 ? 0.5 * (s->frames[1].time - t0) : 1e-6 * fmax(1.0, fabs(t0));
    const double after = n > 1 ? 0.5 * (t1 - s->frames[n - 2].time) : 1e-6 * fmax(1.0, fabs(t1));
    for (size_t t = 0; t < o->ntimes; t++)
        if (!(o->times[t] >= t0 - before && o->times[t] <= t1 + after))
            return gf_error_set(GF_ERR_PARAM, "render: no snapshot of %s near t = %g tau: its %zu snapshot%s go%s from "
                                              "t = %g to %g tau",
                                dir, o->times[t], n, n == 1 ? "" : "s", n == 1 ? "es" : "", t0, t1);
    return GF_OK;
}

gf_status gf_render_dir(const char *dir, const gf_render_dir_opts *opt)
{
    if (!dir || !opt) return gf_error_set(GF_ERR_PARAM, "gf_render_dir: NULL argument");
    gf_status st = gf_render_check(opt);
    if (st != GF_OK) return st;
    gf_series s;
    if ((st = gf_series_load(dir, 0.0, &(gf_series_opts){.stop = opt->stop}, &s)) != GF_OK) return st;
    if (s.nframes == 0) {
        gf_series_free(&s);
        return gf_error_set(GF_ERR_STATE, "%s: no snapshots", dir);
    }
    if ((st = gf_render_check_times(dir, opt, &s)) != GF_OK) {
        gf_series_free(&s);
        return st;
    }
    gf_render_job j = {.o = opt, .s = &s};
    if ((st = gf_render_outdir(dir, opt, j.outdir, sizeof j.outdir)) != GF_OK) {
        gf_series_free(&s);
        return st;
    }
    char name[GF_RENDER_PATH];
    j.opts = gf_render_opts_default();
    j.opts.px_per_d = opt->scale;
    j.opts.title = gf_render_name(dir, name, sizeof name);
    gf_container_defs cd;
    gf_config_container_defs(&s.cfg, &cd);
    double zmax = cd.orifice.diameter; // one height for every picture: the highest top of the run
    for (size_t k = 0; k < s.nframes; k++)
        for (size_t i = 0; i < s.frames[k].pk.n; i++)
            zmax = fmax(zmax, s.frames[k].pk.z[i] + s.frames[k].pk.r[i]);
    j.opts.zmax = zmax;
    j.phi = GF_NEW(double *, s.nframes);
    st = j.phi ? gf_render_pictures(&j) : gf_error_set(GF_ERR_NOMEM, "render: out of memory");
    if (st == GF_OK) { // a run with spot.flow_rule = sfr: the stress field it followed
        const char *pic = NULL;
        st = gf_render_stress_of_run(dir, &s.cfg, j.outdir, opt->format, j.opts.title, &pic);
        if (st == GF_OK && pic) gf_render_written(&j, pic);
    }
    if (j.phi) {
        for (size_t k = 0; k < s.nframes; k++)
            if (j.phi[k]) GF_DELETE(j.phi[k], gf_render_phi_len(&s.frames[k].pk));
        GF_DELETE(j.phi, s.nframes);
    }
    gf_series_free(&s);
    return st;
}
