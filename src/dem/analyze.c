// SPDX-License-Identifier: MIT
// `granflow analyze` as one library call (SPEC 1.6): a run, a directory of
// LAMMPS dumps or one dump read as a series, its window resolved to the
// steady flow, the measurements written out.
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "core/error.h"
#include "granflow/dem.h"

gf_status gf_dem_analyze_outdir(const char *path, char *out, size_t n)
{
    if (!path || !out || !n) return gf_error_set(GF_ERR_PARAM, "gf_dem_analyze_outdir: NULL path or buffer");
    struct stat sb;
    int len;
    if (stat(path, &sb) == 0 && !S_ISDIR(sb.st_mode)) {
        const char *slash = strrchr(path, '/');
        if (slash) len = snprintf(out, n, "%.*s/analysis", (int)(slash - path), path);
        else len = snprintf(out, n, "analysis");
    } else {
        len = snprintf(out, n, "%s/analysis", path);
    }
    if (len < 0 || (size_t)len >= n)
        return gf_error_set(GF_ERR_PARAM, "%s: path too long for its analysis directory", path);
    return GF_OK;
}

gf_status gf_dem_analyze(const char *path, const gf_dem_source *src, const gf_analysis_opts *o, const char *name,
                         const char *outdir, bool plots, gf_dem_analysis *info)
{
    if (!path || !o) return gf_error_set(GF_ERR_PARAM, "gf_dem_analyze: NULL path or options");
    gf_status sc = gf_analysis_opts_check(o); // before reading any data
    if (sc != GF_OK) return sc;
    gf_dem_analysis tmp;
    gf_dem_analysis *a = info ? info : &tmp;
    memset(a, 0, sizeof *a);
    if (outdir && snprintf(a->outdir, sizeof a->outdir, "%s", outdir) >= (int)sizeof a->outdir)
        return gf_error_set(GF_ERR_PARAM, "%s: output directory name too long", outdir);
    if (!outdir) {
        gf_status so = gf_dem_analyze_outdir(path, a->outdir, sizeof a->outdir);
        if (so != GF_OK) return so;
    }
    gf_dem_source source = src ? *src : gf_dem_source_default();
    source.dump_dt = o->dump_dt;
    if (!source.stop) source.stop = o->stop;
    gf_series s = {0};
    gf_dem_load_report rep;
    gf_status st = gf_dem_series_load(path, &source, &s, &rep);
    if (st != GF_OK) return st;
    snprintf(a->container, sizeof a->container, "%s", rep.container);
    a->nframes = s.nframes;
    a->nexits = s.nexits;
    a->exits_derived = s.exits_derived;
    a->exit_resolution = s.exit_resolution;
    a->t_first = s.nframes ? s.frames[0].time : 0.0;
    a->t_last = s.nframes ? s.frames[s.nframes - 1].time : 0.0;
    gf_analysis_opts opts = *o;
    st = gf_dem_window(&s, &opts, &a->window);
    if (st == GF_OK) st = gf_analyze(&s, &opts, name, a->outdir, plots);
    gf_series_free(&s);
    return st;
}
