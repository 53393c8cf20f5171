// SPDX-License-Identifier: MIT
// `granflow render DIR`: pictures of a run's snapshots (central slices and a contact sheet).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
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

enum { GF_RENDER_MAX_TIMES = 256 };

typedef struct gf_render_cli {
    const char *dir;
    gf_render_options o;
    double times[GF_RENDER_MAX_TIMES];
    bool quiet;
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
        if (c->o.ntimes == GF_RENDER_MAX_TIMES) return gf_render_bad("--times: too many times in '%s'", s);
        c->times[c->o.ntimes++] = t;
        p = *end ? end + 1 : end;
        if (*end && !*p) return gf_render_bad("--times: trailing comma in '%s'", s);
    }
    if (!c->o.ntimes) return gf_render_bad("--times needs at least one time%s", "");
    return 0;
}

/// Parses argv into c; returns -1 to go on, or the exit code to return now.
static int gf_render_parse(int argc, char **argv, gf_render_cli *c)
{
    *c = (gf_render_cli){.o = gf_render_options_default()};
    c->o.times = c->times;
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
            c->o.raw = !strcmp(val, "phi-raw");
            if (!strcmp(val, "layer")) c->o.colour = GF_RENDER_LAYER;
            else if (!strcmp(val, "phi") || c->o.raw) c->o.colour = GF_RENDER_PHI;
            else return gf_render_bad("--colour is layer, phi or phi-raw, not '%s'", val);
        } else if (!strcmp(a, "--times")) {
            int rc = gf_render_parse_times(val, c);
            if (rc) return rc;
        } else if (!strcmp(a, "--format")) {
            if (strcmp(val, "png") && strcmp(val, "svg") && strcmp(val, "pdf"))
                return gf_render_bad("--format is png, svg or pdf, not '%s'", val);
            c->o.format = val;
        } else if (!strcmp(a, "--scale")) {
            char *end;
            c->o.scale = strtod(val, &end);
            if (end == val || *end || !(c->o.scale >= 1 && c->o.scale <= 200))
                return gf_render_bad("--scale takes pixels per d from 1 to 200, not '%s'", val);
        } else if (!strcmp(a, "--panels")) {
            char *end;
            long n = strtol(val, &end, 10);
            if (end == val || *end || n < 1 || n > 40)
                return gf_render_bad("--panels takes a number of snapshots from 1 to 40, not '%s'", val);
            c->o.panels = (size_t)n;
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            c->o.outdir = val;
        } else if (!strcmp(a, "--all")) {
            c->o.all = true;
        } else if (!strcmp(a, "--sheet")) {
            c->o.sheet = true;
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
    if (c->o.all && c->o.ntimes) return gf_render_bad("--all and --times%s exclude each other", "");
    return -1;
}

static void gf_render_print(void *ctx, const char *path)
{
    (void)ctx;
    printf("%s\n", path);
}

int gf_cmd_render(int argc, char **argv)
{
    gf_render_cli c;
    int rc = gf_render_parse(argc, argv, &c);
    if (rc >= 0) return rc;
    if (!c.quiet) c.o.written = gf_render_print;
    c.o.stop = gf_cli_catch_stop();
    gf_status st = gf_render_dir(c.dir, &c.o);
    if (st == GF_ERR_INTERRUPTED) return gf_cli_interrupted("render", "each picture written is whole; the rest not drawn");
    return st == GF_OK ? GF_EXIT_OK : gf_cli_fail("render", st);
}
