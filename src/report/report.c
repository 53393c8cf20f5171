// SPDX-License-Identifier: MIT
// gf_report_write: a run directory as one self-contained HTML page.
#include "granflow/report.h"

#include <dirent.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/alloc.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "granflow/analysis.h"
#include "report/html.h"
#include "report/omit.h"

#define GF_REPORT_PATH 4096                  // a directory's path
#define GF_REPORT_FILE (GF_REPORT_PATH + 256) // a file in it
#define GF_REPORT_ENTRIES 256                // keys of one summary.json (the analysis writes up to 256)

// The contact sheet spans the window (labels readable); every picture opens
// at full size on a click and closes on another, by a hidden checkbox and its
// label: no script, and the page stays one file.
static const char gf_report_css[] =
    "body{font-family:'DejaVu Sans',sans-serif;margin:2em auto;max-width:1200px;color:#222;padding:0 1em}"
    "h1{font-size:1.6em;border-bottom:2px solid #36c;padding-bottom:.2em}"
    "h2{font-size:1.25em;margin-top:2em;color:#235}"
    "table{border-collapse:collapse;margin:.5em 0;font-size:.9em}"
    "th,td{border:1px solid #ccc;padding:.2em .6em;text-align:left}"
    "td.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}"
    "table.kv tr:first-child th,table.csv tr:first-child th{background:#e8edf7;font-weight:bold}"
    "table.kv th,table.csv td:first-child,table.csv th:first-child{background:#f3f5f9;font-weight:normal}"
    "td code{color:#667;font-size:.9em}"
    "p.omit{margin:.8em 0 .2em;color:#555;font-size:.9em}ul.omit{margin:0;color:#555;font-size:.9em}"
    ".cols{display:flex;flex-wrap:wrap;gap:1em}.cols>div{flex:1 1 45%;min-width:300px}"
    ".figs{display:grid;grid-template-columns:repeat(auto-fill,minmax(540px,1fr));gap:1em}"
    "figure{margin:0}figure img{max-width:100%;border:1px solid #ddd}"
    "figure.sheet{width:calc(100vw - 2em);margin:1em 0 1.5em calc(50% - 50vw + 1em)}"
    "figure.sheet img{width:100%;max-width:none;box-sizing:border-box}"
    "input.zoom{display:none}label.zoom{display:block;cursor:zoom-in}"
    "input.zoom:checked+label.zoom{position:fixed;top:0;left:0;right:0;bottom:0;z-index:9;overflow:auto;"
    "background:rgba(30,30,30,.96);padding:1em;box-sizing:border-box;cursor:zoom-out}"
    "input.zoom:checked+label.zoom img{width:auto;max-width:none;min-width:100%;background:#fff}"
    "figcaption{font-size:.85em;color:#555}"
    "pre{background:#f6f6f6;padding:.8em;font-size:.8em;overflow-x:auto}"
    ".meta{color:#666;font-size:.9em}";

typedef struct gf_report {
    FILE *out;
    gf_report_info info;
    gf_status st; // first failure (an image, a summary.json that is not JSON); the page is not written
    gf_report_context ctx; // what is left out, and why
} gf_report;

// dir/name into out; false (out truncated) when it does not fit. gf_report_write
// refuses directories long enough for that to happen.
static bool gf_report_join(char *out, size_t n, const char *dir, const char *name)
{
    int w = snprintf(out, n, "%s/%s", dir, name);
    return w >= 0 && (size_t)w < n;
}

static bool gf_report_exists(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0;
}

// A picture with its caption; a click shows it at full size (the checkbox's
// id numbers the pictures). `cls` is the figure's class (NULL: none).
static void gf_report_figure_as(gf_report *r, const char *path, const char *caption, const char *cls)
{
    size_t id = r->info.images;
    if (cls) fprintf(r->out, "<figure class=\"%s\">", cls);
    else fputs("<figure>", r->out);
    fprintf(r->out, "<input type=\"checkbox\" class=\"zoom\" id=\"zoom%zu\"><label class=\"zoom\" for=\"zoom%zu\">", id, id);
    gf_status st = gf_html_image(r->out, path, caption);
    if (st != GF_OK && r->st == GF_OK) r->st = st;
    fputs("</label><figcaption>", r->out);
    gf_html_text(r->out, caption);
    fputs("</figcaption></figure>\n", r->out);
    r->info.images++;
}

static void gf_report_figure(gf_report *r, const char *path, const char *caption)
{
    gf_report_figure_as(r, path, caption, NULL);
}

static bool gf_report_is_picture(const char *name)
{
    size_t n = strlen(name);
    return n > 4 && (!strcmp(name + n - 4, ".png") || !strcmp(name + n - 4, ".svg"));
}

typedef char gf_report_name[256];

static int gf_report_name_cmp(const void *a, const void *b) { return strcmp(a, b); }

// Every picture of `sub` except those already shown (`skip`, by stem), sorted.
static void gf_report_pictures(gf_report *r, const char *sub, const char *const *skip, size_t nskip)
{
    DIR *d = opendir(sub);
    if (!d) return;
    gf_report_name *list = NULL;
    size_t n = 0, cap = 0;
    for (struct dirent *e; (e = readdir(d)) != NULL;) {
        if (!gf_report_is_picture(e->d_name) || strlen(e->d_name) >= sizeof *list) continue;
        if (n == cap) {
            size_t grown = cap ? 2 * cap : 32;
            gf_report_name *q = gf_realloc(list, cap * sizeof *list, grown * sizeof *list);
            if (!q) break; // out of memory: the pictures found so far
            list = q;
            cap = grown;
        }
        snprintf(list[n++], sizeof *list, "%s", e->d_name);
    }
    closedir(d);
    if (n) qsort(list, n, sizeof *list, gf_report_name_cmp);
    for (size_t i = 0; i < n; i++) {
        bool shown = false;
        for (size_t k = 0; k < nskip; k++) {
            size_t len = strlen(skip[k]);
            if (!strncmp(list[i], skip[k], len) && list[i][len] == '.') shown = true;
        }
        if (!shown) {
            char path[GF_REPORT_FILE];
            gf_report_join(path, sizeof path, sub, list[i]);
            gf_report_figure(r, path, list[i]);
        }
    }
    gf_free(list, cap * sizeof *list);
}

// A summary.json as a table in words with units, the numbers that mean
// nothing for this run left out with the reason. False when it is absent.
static bool gf_report_summary(gf_report *r, const char *path)
{
    gf_html_entry *e = GF_NEW(gf_html_entry, GF_REPORT_ENTRIES);
    const char **why = GF_NEW(const char *, GF_REPORT_ENTRIES);
    int n = -1;
    gf_status st = e && why ? gf_html_json_load(path, e, GF_REPORT_ENTRIES, &n) : GF_OK;
    // Not JSON, or not a regular file (gf_last_error names it): the page is not written.
    if (st != GF_OK && r->st == GF_OK) r->st = st;
    if (n >= 0) {
        gf_report_omit(&r->ctx, e, (size_t)n, why);
        gf_html_kv_table(r->out, e, (size_t)n, why);
    }
    if (e) GF_DELETE(e, GF_REPORT_ENTRIES);
    if (why) GF_DELETE(why, GF_REPORT_ENTRIES);
    return n >= 0;
}

// analysis/: the headline numbers, then the plots in the order of the measurements.
static void gf_report_analysis(gf_report *r, const char *dir)
{
    char sub[GF_REPORT_PATH], path[GF_REPORT_FILE];
    gf_report_join(sub, sizeof sub, dir, "analysis");
    gf_report_join(path, sizeof path, sub, "summary.json");
    if (!gf_report_exists(sub)) {
        // (an LGA run has no analysis to run: its numbers are in its summary)
        if (!r->ctx.scenario[0])
            fputs("<h2>Analysis</h2><p>Not analysed yet (<code>granflow analyze DIR</code>).</p>\n", r->out);
        return;
    }
    fputs("<h2>Analysis</h2>\n", r->out);
    gf_report_summary(r, path);
    fputs("<div class=\"figs\">\n", r->out);
    size_t nm;
    const gf_measure_def *m = gf_measures(&nm);
    const char *names[64];
    size_t nn = 0;
    for (size_t k = 0; k < nm && nn < 64; k++) {
        names[nn++] = m[k].name;
        if (gf_report_omit_plot(&r->ctx, m[k].name)) continue; // said under the table
        char name[128];
        snprintf(name, sizeof name, "%.100s.png", m[k].name);
        gf_report_join(path, sizeof path, sub, name);
        if (!gf_report_exists(path)) continue;
        char caption[256];
        snprintf(caption, sizeof caption, "%s: %s", m[k].name, m[k].what);
        gf_report_figure(r, path, caption);
    }
    gf_report_pictures(r, sub, names, nn);
    fputs("</div>\n", r->out);
    size_t off = 0;
    for (size_t k = 0; k < nm; k++) {
        char name[128];
        snprintf(name, sizeof name, "%.100s.png", m[k].name);
        gf_report_join(path, sizeof path, sub, name);
        if (!gf_report_omit_plot(&r->ctx, m[k].name) || !gf_report_exists(path)) continue;
        fputs(off++ ? ", " : "<p class=\"omit\">Plots left out with their numbers (above) or as empty: ", r->out);
        gf_html_text(r->out, m[k].name);
    }
    if (off) fputs(".</p>\n", r->out);
}

// The comparison with the DEM run: the headline table, the overlay figure,
// and the two runs' slices side by side.
static void gf_report_compare(gf_report *r, const char *cmp)
{
    char path[GF_REPORT_FILE], dem[GF_REPORT_FILE];
    gf_report_join(path, sizeof path, cmp, "summary.csv");
    if (!gf_report_exists(path)) return;
    r->info.compared = 1;
    fputs("<h2>DEM and spot model side by side</h2>\n<p class=\"meta\">From ", r->out);
    gf_html_text(r->out, cmp);
    fputs(" (<code>granflow compare</code>).</p>\n", r->out);
    bool found;
    gf_status st = gf_html_csv_table(r->out, path, 100, &found);
    if (st != GF_OK && r->st == GF_OK) r->st = st;
    gf_report_join(path, sizeof path, cmp, "compare.png");
    if (gf_report_exists(path)) gf_report_figure(r, path, "the measurements of both runs (DEM and spot)");
    gf_report_join(dem, sizeof dem, cmp, "slices_dem.png");
    gf_report_join(path, sizeof path, cmp, "slices_spot.png");
    if (gf_report_exists(dem) || gf_report_exists(path)) {
        fputs("<div class=\"cols\">\n<div>", r->out);
        if (gf_report_exists(dem)) gf_report_figure(r, dem, "DEM: central slices");
        fputs("</div>\n<div>", r->out);
        if (gf_report_exists(path)) gf_report_figure(r, path, "spot model: central slices at the same times");
        fputs("</div>\n</div>\n", r->out);
    }
    static const char *const shown[] = {"compare", "slices_dem", "slices_spot"};
    fputs("<div class=\"figs\">\n", r->out);
    gf_report_pictures(r, cmp, shown, 3);
    fputs("</div>\n", r->out);
}

static void gf_report_title(FILE *out, const char *title, const char *dir)
{
    if (!title) fputs("granflow run ", out);
    gf_html_text(out, title ? title : dir);
}

gf_report_opts gf_report_opts_default(void) { return (gf_report_opts){0}; }

gf_status gf_report_write(const char *dir, const gf_report_opts *opts, gf_report_info *info)
{
    gf_report_opts o = opts ? *opts : gf_report_opts_default();
    if (!dir) return gf_error_set(GF_ERR_PARAM, "gf_report_write: dir is NULL");
    // Room for every file name below dir (and below opts->compare).
    if (strlen(dir) > GF_REPORT_PATH - 256 || (o.compare && strlen(o.compare) > GF_REPORT_PATH - 256) ||
        (o.out && strlen(o.out) >= GF_REPORT_PATH))
        return gf_error_set(GF_ERR_PARAM, "gf_report_write: path too long: %.80s...", dir);
    char cfg[GF_REPORT_FILE], sum[GF_REPORT_FILE], outbuf[GF_REPORT_FILE], tmp[GF_REPORT_FILE + 8],
        cmpbuf[GF_REPORT_PATH], sub[GF_REPORT_PATH];
    gf_report_join(cfg, sizeof cfg, dir, "config.ini");
    gf_report_join(sum, sizeof sum, dir, "summary.json");
    if (!gf_report_exists(cfg) && !gf_report_exists(sum))
        return gf_error_set(GF_ERR_PARAM, "%s: not a run directory (no config.ini or summary.json)", dir);
    gf_report_join(outbuf, sizeof outbuf, dir, "report.html");
    gf_report_join(cmpbuf, sizeof cmpbuf, dir, "compare");
    const char *out = o.out ? o.out : outbuf, *cmp = o.compare ? o.compare : cmpbuf;
    if (o.compare && !gf_report_exists(cmp))
        return gf_error_set(GF_ERR_PARAM, "%s: no such comparison directory", o.compare);

    gf_report r = {0};
    gf_status st = gf_atomic_open(out, tmp, sizeof tmp, &r.out);
    if (st != GF_OK) return st;
    fputs("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>", r.out);
    gf_report_title(r.out, o.title, dir);
    fprintf(r.out, "</title>\n<style>%s</style>\n</head><body>\n<h1>", gf_report_css);
    gf_report_title(r.out, o.title, dir);
    fprintf(r.out, "</h1>\n<p class=\"meta\">Written by granflow %s from the files of ", gf_version());
    gf_html_text(r.out, dir);
    fputs(".</p>\n", r.out);

    // What is left out needs the run's scenario (an LGA run), config.ini and surface.csv.
    gf_html_entry *run = GF_NEW(gf_html_entry, GF_REPORT_ENTRIES);
    int nrun = run ? gf_html_json_read(sum, run, GF_REPORT_ENTRIES) : -1;
    gf_report_context_read(&r.ctx, dir, run, nrun > 0 ? (size_t)nrun : 0);
    if (run) GF_DELETE(run, GF_REPORT_ENTRIES);

    fputs("<h2>Run</h2>\n", r.out);
    if (!gf_report_summary(&r, sum)) fputs("<p>No summary.json.</p>\n", r.out);
    gf_report_analysis(&r, dir);
    // Pictures: render/ of a spot run; sheet.png and maps/ of an LGA run. The
    // contact sheet first, across the whole window.
    size_t before = r.info.images;
    fputs("<h2>Pictures</h2>\n", r.out);
    static const char *const sheet_dirs[] = {"render", "."};
    static const char *const sheet_skip[] = {"sheet"};
    for (size_t k = 0; k < 2; k++) {
        gf_report_join(sub, sizeof sub, dir, sheet_dirs[k]);
        char sheet[GF_REPORT_FILE];
        gf_report_join(sheet, sizeof sheet, sub, "sheet.png");
        if (gf_report_exists(sheet))
            gf_report_figure_as(&r, sheet, k == 0 ? "contact sheet: the central slice at each snapshot (render/sheet.png)"
                                                  : "contact sheet: the density maps over the run (sheet.png)",
                                "sheet");
    }
    fputs("<div class=\"figs\">\n", r.out);
    gf_report_pictures(&r, dir, sheet_skip, 1);
    static const char *const picture_dirs[] = {"render", "maps"};
    for (size_t k = 0; k < 2; k++) {
        gf_report_join(sub, sizeof sub, dir, picture_dirs[k]);
        gf_report_pictures(&r, sub, sheet_skip, 1);
    }
    fputs("</div>\n", r.out);
    if (r.info.images == before) fputs("<p>None yet (<code>granflow render DIR</code>).</p>\n", r.out);
    gf_report_compare(&r, cmp);
    fputs("<h2>Configuration</h2>\n", r.out);
    bool have_cfg;
    gf_status sc = gf_html_pre_file(r.out, cfg, &have_cfg);
    if (sc != GF_OK && r.st == GF_OK) r.st = sc;
    if (sc == GF_OK && !have_cfg) fputs("<p>No config.ini.</p>\n", r.out);
    fputs("</body></html>\n", r.out);

    if (r.st != GF_OK) {
        gf_atomic_abort(r.out, tmp);
        return r.st;
    }
    r.info.bytes = (size_t)ftell(r.out);
    if ((st = gf_atomic_commit(r.out, tmp, out)) != GF_OK) return st;
    if (info) *info = r.info;
    return GF_OK;
}
