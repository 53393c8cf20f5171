// SPDX-License-Identifier: MIT
// `granflow render DIR`: pictures of a run's snapshots (central slices and a contact sheet).
#include <getopt.h>
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

enum { GF_RENDER_MAX_TIMES = 256 };

typedef struct gf_render_cli {
    const char *dir;
    gf_render_dir_opts o;
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
    *c = (gf_render_cli){.o = gf_render_dir_opts_default()};
    c->o.times = c->times;
    enum { OPT_COLOUR = 256, OPT_TIMES, OPT_FORMAT, OPT_SCALE, OPT_PANELS, OPT_ALL, OPT_SHEET };
    static const struct option longs[] = {
        {"colour", required_argument, NULL, OPT_COLOUR}, {"color", required_argument, NULL, OPT_COLOUR},
        {"times", required_argument, NULL, OPT_TIMES},   {"format", required_argument, NULL, OPT_FORMAT},
        {"scale", required_argument, NULL, OPT_SCALE},   {"panels", required_argument, NULL, OPT_PANELS},
        {"output", required_argument, NULL, 'o'},        {"all", no_argument, NULL, OPT_ALL},
        {"sheet", no_argument, NULL, OPT_SHEET},         {"quiet", no_argument, NULL, 'q'},
        {"help", no_argument, NULL, 'h'},                {0},
    };
    optind = 0;
    opterr = 0;
    int o;
    while ((o = getopt_long(argc, argv, ":o:qh", longs, NULL)) != -1) {
        const char *val = optarg;
        switch (o) {
        case 'h': return gf_cli_help("render");
        case OPT_COLOUR:
            c->o.raw = !strcmp(val, "phi-raw");
            if (!strcmp(val, "layer")) c->o.colour = GF_RENDER_LAYER;
            else if (!strcmp(val, "phi") || c->o.raw) c->o.colour = GF_RENDER_PHI;
            else return gf_render_bad("--colour is layer, phi or phi-raw, not '%s'", val);
            break;
        case OPT_TIMES: {
            int rc = gf_render_parse_times(val, c);
            if (rc) return rc;
            break;
        }
        case OPT_FORMAT:
            if (strcmp(val, "png") && strcmp(val, "svg") && strcmp(val, "pdf"))
                return gf_render_bad("--format is png, svg or pdf, not '%s'", val);
            c->o.format = val;
            break;
        case OPT_SCALE: {
            char *end;
            c->o.scale = strtod(val, &end);
            if (end == val || *end || !(c->o.scale >= 1 && c->o.scale <= 200))
                return gf_render_bad("--scale takes pixels per d from 1 to 200, not '%s'", val);
            break;
        }
        case OPT_PANELS: {
            char *end;
            long n = strtol(val, &end, 10);
            if (end == val || *end || n < 1 || n > 40)
                return gf_render_bad("--panels takes a number of snapshots from 1 to 40, not '%s'", val);
            c->o.panels = (size_t)n;
            break;
        }
        case 'o': c->o.outdir = val; break;
        case OPT_ALL: c->o.all = true; break;
        case OPT_SHEET: c->o.sheet = true; break;
        case 'q': c->quiet = true; break;
        default: return gf_cli_getopt_error("render", o, argv);
        }
    }
    for (int i = optind; i < argc; i++) {
        if (c->dir) return gf_render_bad("unexpected argument '%s' (one run directory)", argv[i]);
        c->dir = argv[i];
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
