// SPDX-License-Identifier: MIT
// `granflow render DIR`: pictures of a run's snapshots (central slices and a contact sheet).
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"
#include "granflow/analysis.h"
#include "granflow/render.h"

#if defined(__SANITIZE_ADDRESS__)
// fontconfig, reached through cairo's text, keeps a few hundred bytes of font
// patterns for the life of the process (freed only by FcFini); not our leak.
const char *__lsan_default_suppressions(void);
__attribute__((visibility("default"))) const char *__lsan_default_suppressions(void) { return "leak:libfontconfig.so\n"; }
#endif

static const char gf_render_usage[] =
    "usage: granflow render DIR [options]\n"
    "Draws the central slice (y > 0, seen from -y) of a run's snapshots.\n"
    "By default: DIR/render/slice_NNNNNN.png for the first, middle and last snapshots\n"
    "coloured by initial layer, slice_NNNNNN_phi.png for the last one coloured by\n"
    "local packing fraction (averaged within 2.2 d), and sheet.png, a contact sheet\n"
    "of the run over time.\n"
    "NNNNNN is the snapshot's index in time order. DIR may also be a directory of\n"
    "LAMMPS dumps or one dump file (then the pictures go to render/ beside it).\n"
    "\n"
    "options:\n"
    "  --colour layer|phi|phi-raw\n"
    "                         colour by initial layer (default), by the local packing\n"
    "                         fraction averaged over the bulk particles within 2.2 d\n"
    "                         (phi: the 2009 paper's Fig. 4; files *_phi.*), or by each\n"
    "                         particle's volume over its Voronoi cell's volume\n"
    "                         (phi-raw: the paper's Fig. 6; files *_phi_raw.*)\n"
    "  --times T1,T2,...      the snapshots nearest these times (tau)\n"
    "  --all                  every snapshot\n"
    "  --sheet                the contact sheet (only it, unless --times or --all)\n"
    "  --panels N             snapshots on the contact sheet, evenly spaced (default 8)\n"
    "  --format png|svg|pdf   file format (default png)\n"
    "  --scale PX             pixels per particle diameter (default 10; the sheet uses half)\n"
    "  -o OUTDIR              where the pictures go (default DIR/render)\n"
    "  -q, --quiet            do not list the files written\n";

enum { GF_RENDER_MAX_TIMES = 256, GF_RENDER_PATH = GF_PATH_MAX + 64 };

typedef struct gf_render_cli {
    const char *dir, *outdir;
    gf_render_colour colour;
    bool raw; ///< phi mode: each particle's own packing fraction, not the 2.2 d average
    const char *ext;
    double scale;
    double times[GF_RENDER_MAX_TIMES];
    size_t ntimes;
    bool all, sheet, quiet;
    size_t panels;
} gf_render_cli;

static int gf_render_bad(const char *fmt, const char *what)
{
    fprintf(stderr, "granflow render: error: ");
    fprintf(stderr, fmt, what);
    fprintf(stderr, " (see granflow render --help)\n");
    return GF_EXIT_USAGE;
}

/// Parses a comma-separated list of times. Returns 0 or an exit code.
static int gf_render_parse_times(const char *s, gf_render_cli *c)
{
    const char *p = s;
    while (*p) {
        char *end;
        double t = strtod(p, &end);
        if (end == p || !isfinite(t) || (*end && *end != ','))
            return gf_render_bad("--times takes numbers separated by commas, not '%s'", s);
        if (c->ntimes == GF_RENDER_MAX_TIMES) return gf_render_bad("--times: too many times in '%s'", s);
        c->times[c->ntimes++] = t;
        p = *end ? end + 1 : end;
        if (*end && !*p) return gf_render_bad("--times: trailing comma in '%s'", s);
    }
    if (!c->ntimes) return gf_render_bad("--times needs at least one time%s", "");
    return 0;
}

/// Parses argv into c; returns -1 to go on, or the exit code to return now.
static int gf_render_parse(int argc, char **argv, gf_render_cli *c)
{
    *c = (gf_render_cli){.colour = GF_RENDER_LAYER, .ext = "png", .scale = 10.0, .panels = 8};
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
        int takes = !strcmp(a, "--colour") || !strcmp(a, "--color") || !strcmp(a, "--times") ||
                    !strcmp(a, "--format") || !strcmp(a, "--scale") || !strcmp(a, "-o") ||
                    !strcmp(a, "--output") || !strcmp(a, "--panels");
        if (takes && !val) return gf_render_bad("%s needs a value", a);
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            fputs(gf_render_usage, stdout);
            return GF_EXIT_OK;
        } else if (!strcmp(a, "--colour") || !strcmp(a, "--color")) {
            c->raw = !strcmp(val, "phi-raw");
            if (!strcmp(val, "layer")) c->colour = GF_RENDER_LAYER;
            else if (!strcmp(val, "phi") || c->raw) c->colour = GF_RENDER_PHI;
            else return gf_render_bad("--colour is layer, phi or phi-raw, not '%s'", val);
        } else if (!strcmp(a, "--times")) {
            int rc = gf_render_parse_times(val, c);
            if (rc) return rc;
        } else if (!strcmp(a, "--format")) {
            if (strcmp(val, "png") && strcmp(val, "svg") && strcmp(val, "pdf"))
                return gf_render_bad("--format is png, svg or pdf, not '%s'", val);
            c->ext = val;
        } else if (!strcmp(a, "--scale")) {
            char *end;
            c->scale = strtod(val, &end);
            if (end == val || *end || !(c->scale >= 1 && c->scale <= 200))
                return gf_render_bad("--scale takes pixels per d from 1 to 200, not '%s'", val);
        } else if (!strcmp(a, "--panels")) {
            char *end;
            long n = strtol(val, &end, 10);
            if (end == val || *end || n < 1 || n > 40)
                return gf_render_bad("--panels takes a number of snapshots from 1 to 40, not '%s'", val);
            c->panels = (size_t)n;
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            c->outdir = val;
        } else if (!strcmp(a, "--all")) {
            c->all = true;
        } else if (!strcmp(a, "--sheet")) {
            c->sheet = true;
        } else if (!strcmp(a, "-q") || !strcmp(a, "--quiet")) {
            c->quiet = true;
        } else if (a[0] == '-' && a[1]) {
            return gf_render_bad("unknown option '%s'", a);
        } else if (!c->dir) {
            c->dir = a;
        } else {
            return gf_render_bad("unexpected argument '%s' (one run directory)", a);
        }
        if (takes) i++;
    }
    if (!c->dir) return gf_render_bad("which run? give its directory%s", "");
    if (c->all && c->ntimes) return gf_render_bad("--all and --times%s exclude each other", "");
    return -1;
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

/// Packing fractions of frame k (computed once, kept in phi[k]): the field
/// averaged within GF_RENDER_PHI_RADIUS, or with `raw` each particle's volume
/// over its Voronoi cell's. The cells' open top is 1 d above the highest
/// centre in the container, as `granflow analyze voronoi` has it, so the
/// pictures show the phi and phi_avg columns of its voronoi.csv.
static gf_status gf_render_phi(const gf_series *s, size_t k, bool raw, double **phi)
{
    if (phi[k]) return GF_OK;
    const gf_packing *pk = &s->frames[k].pk;
    phi[k] = calloc(pk->n ? pk->n : 1, sizeof **phi);
    if (!phi[k]) return GF_ERR_NOMEM;
    const double W = s->cfg.container_width, D = s->cfg.container_depth;
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
    const gf_render_cli *c;
    const gf_series *s;
    double **phi;
    gf_render_opts opts;
    char outdir[GF_RENDER_PATH];
} gf_render_job;

static gf_status gf_render_one(gf_render_job *j, size_t k, gf_render_colour colour)
{
    char path[GF_RENDER_PATH + 64];
    snprintf(path, sizeof path, "%s/slice_%06zu%s.%s", j->outdir, k, gf_render_suffix(colour, j->c->raw),
             j->c->ext);
    gf_render_opts o = j->opts;
    o.colour = colour;
    gf_status st = colour == GF_RENDER_PHI ? gf_render_phi(j->s, k, j->c->raw, j->phi) : GF_OK;
    if (st == GF_OK) st = gf_render_slice(&j->s->frames[k].pk, j->s->frames[k].time, &j->s->cfg,
                                          j->phi[k], &o, path);
    if (st == GF_OK && !j->c->quiet) printf("%s\n", path);
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
    size_t want = gf_render_panels(j->c->panels, s->nframes), n = 0;
    gf_frame *fr = calloc(want, sizeof *fr);
    const double **phi = calloc(want, sizeof *phi);
    gf_status st = fr && phi ? GF_OK : GF_ERR_NOMEM;
    for (size_t k = 0; st == GF_OK && k < want; k++) { // evenly spaced, first and last included
        size_t idx = want == 1 ? s->nframes - 1 : (size_t)llround((double)k * (double)(s->nframes - 1) / (double)(want - 1));
        fr[n] = s->frames[idx]; // a shallow copy: the series keeps the particles
        if (j->c->colour == GF_RENDER_PHI) {
            st = gf_render_phi(s, idx, j->c->raw, j->phi);
            phi[n] = j->phi[idx];
        }
        n++;
    }
    char path[GF_RENDER_PATH + 64];
    snprintf(path, sizeof path, "%s/sheet%s.%s", j->outdir, gf_render_suffix(j->c->colour, j->c->raw), j->c->ext);
    gf_render_opts o = j->opts;
    o.colour = j->c->colour;
    o.px_per_d = fmax(1.0, 0.5 * j->c->scale);
    if (st == GF_OK) st = gf_render_sheet(fr, n, &s->cfg, j->c->colour == GF_RENDER_PHI ? phi : NULL, &o, path);
    if (st == GF_OK && !j->c->quiet) printf("%s\n", path);
    free(fr);
    free(phi);
    return st;
}

int gf_cmd_render(int argc, char **argv)
{
    gf_render_cli c;
    int rc = gf_render_parse(argc, argv, &c);
    if (rc >= 0) return rc;

    gf_series s;
    gf_status st = gf_series_load(c.dir, 0.0, &s);
    if (st != GF_OK) return gf_cli_fail("render", st);
    if (s.nframes == 0) {
        gf_series_free(&s);
        fprintf(stderr, "granflow render: error: %s: no snapshots\n", c.dir);
        return GF_EXIT_FAIL;
    }

    gf_render_job j = {.c = &c, .s = &s};
    struct stat sb;
    int w;
    if (c.outdir) {
        w = snprintf(j.outdir, sizeof j.outdir, "%s", c.outdir);
    } else if (stat(c.dir, &sb) == 0 && !S_ISDIR(sb.st_mode)) { // one dump file: render/ beside it
        const char *slash = strrchr(c.dir, '/');
        w = slash ? snprintf(j.outdir, sizeof j.outdir, "%.*s/render", (int)(slash - c.dir), c.dir)
                  : snprintf(j.outdir, sizeof j.outdir, "render");
    } else {
        w = snprintf(j.outdir, sizeof j.outdir, "%s/render", c.dir);
    }
    if (w < 0 || w >= (int)sizeof j.outdir) {
        fprintf(stderr, "granflow render: error: path too long: %s\n", j.outdir);
        gf_series_free(&s);
        return GF_EXIT_FAIL;
    }
    if ((st = gf_fs_mkdirs(j.outdir)) != GF_OK) {
        gf_series_free(&s);
        return gf_cli_fail("render", st);
    }
    char name[GF_RENDER_PATH];
    j.opts = gf_render_opts_default();
    j.opts.px_per_d = c.scale;
    j.opts.title = gf_render_name(c.dir, name, sizeof name);
    double zmax = s.cfg.orifice_diameter; // one height for every picture: the highest top of the run
    for (size_t k = 0; k < s.nframes; k++)
        for (size_t i = 0; i < s.frames[k].pk.n; i++)
            zmax = fmax(zmax, s.frames[k].pk.z[i] + s.frames[k].pk.r[i]);
    j.opts.zmax = zmax;
    j.phi = calloc(s.nframes, sizeof *j.phi);
    if (!j.phi) st = GF_ERR_NOMEM;

    // which slices
    bool dflt = !c.all && !c.ntimes && !c.sheet;
    size_t last = s.nframes - 1;
    for (size_t k = 0; st == GF_OK && k < s.nframes; k++) {
        bool pick = c.all || (dflt && (k == 0 || k == last / 2 || k == last));
        for (size_t t = 0; t < c.ntimes && !pick; t++) pick = gf_render_nearest(&s, c.times[t]) == k;
        if (pick) st = gf_render_one(&j, k, c.colour);
    }
    for (size_t t = 0; st == GF_OK && t < c.ntimes; t++) {
        size_t k = gf_render_nearest(&s, c.times[t]);
        if (fabs(s.frames[k].time - c.times[t]) > 1e-6 * fmax(1.0, fabs(c.times[t])))
            fprintf(stderr, "granflow render: note: no snapshot at t = %g; drew the nearest, t = %g\n",
                    c.times[t], s.frames[k].time);
    }
    if (st == GF_OK && dflt && c.colour == GF_RENDER_LAYER) st = gf_render_one(&j, last, GF_RENDER_PHI);
    if (st == GF_OK && (dflt || c.sheet)) st = gf_render_contact_sheet(&j);

    if (j.phi)
        for (size_t k = 0; k < s.nframes; k++) free(j.phi[k]);
    free(j.phi);
    gf_series_free(&s);
    return st == GF_OK ? GF_EXIT_OK : gf_cli_fail("render", st);
}
