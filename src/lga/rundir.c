// SPDX-License-Identifier: MIT
// `granflow lga`: one scenario run into a directory (maps, sheet, CSV, summary).
#include <dirent.h>
#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "config/keys.h"
#include "core/alloc.h"
#include "core/atomic_file.h"
#include "core/clock.h"
#include "core/error.h"
#include "core/fs.h"
#include "core/json.h"
#include "lga/image.h"
#include "lga/scenario.h"

#define GF_LGA_MAP_PX 2.0          // pixels per lattice spacing of the single maps
#define GF_LGA_SHEET_FRAMES 12     // panels of the contact sheet (the paper's Fig. 6 has 12)
#define GF_LGA_KEEP_FRAMES 256     // frames kept in memory for the sheet (thinned beyond)
#define GF_LGA_QUIET 20            // pile: iterations without motion that end an auto run
#define GF_LGA_PILE_SETTLE_MAX 20000 // pile: at most this long after the feed ends (auto)
#define GF_LGA_SILO_MAX 1000000    // silo: at most this many iterations (auto)
#define GF_LGA_WAVE_WINDOW 8       // rows of the running mean in the wave variance
#define GF_LGA_WAVE_EVERY 10       // channel: wave variance every this many iterations

// Whether dir exists and holds anything.
static bool gf_lga_dir_busy(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return false;
    bool busy = false;
    for (struct dirent *e; !busy && (e = readdir(d)) != NULL;)
        if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0) busy = true;
    closedir(d);
    return busy;
}

static const char *gf_lga_scenario_name(gf_lga_scenario s)
{
    return s == GF_LGA_PILE ? "pile" : s == GF_LGA_CHANNEL ? "channel" : "silo";
}

typedef struct gf_lga_out {
    char dir[GF_PATH_MAX];
    gf_lga_frame *frames;
    size_t nframes, keep_every, seen; // every keep_every-th captured frame is kept
    FILE *outflow, *waves;
    char outflow_tmp[GF_PATH_MAX + 64], waves_tmp[GF_PATH_MAX + 64];
    char outflow_path[GF_PATH_MAX + 64], waves_path[GF_PATH_MAX + 64];
    int64_t *out_iter, *out_count; // the iterations with outflow and how many left in each
    size_t nout, iter_cap, count_cap;
} gf_lga_out;

static gf_status gf_lga_snapshot(gf_lga_out *o, const gf_lga *l, const char *title)
{
    gf_lga_frame f;
    gf_status st = gf_lga_frame_capture(l, &f);
    if (st != GF_OK) return st;
    char path[GF_PATH_MAX + 64];
    snprintf(path, sizeof path, "%s/maps/map_%06lld.png", o->dir, (long long)f.iteration);
    st = gf_lga_frame_draw(&f, GF_LGA_MAP_PX, title, path);
    if (st != GF_OK || (o->seen++ % o->keep_every) != 0) {
        gf_lga_frame_free(&f);
        return st;
    }
    if (o->nframes == GF_LGA_KEEP_FRAMES) {
        // thin out: keep every other frame, and from now on every other capture
        size_t k = 0;
        for (size_t i = 0; i < o->nframes; i++) {
            if (i % 2 == 0) o->frames[k++] = o->frames[i];
            else gf_lga_frame_free(&o->frames[i]);
        }
        o->nframes = k;
        o->keep_every *= 2;
    }
    o->frames[o->nframes++] = f;
    return GF_OK;
}

static gf_status gf_lga_write_sheet(gf_lga_out *o, const gf_lga_frame *last, const char *title)
{
    gf_lga_frame pick[GF_LGA_SHEET_FRAMES];
    size_t n = 0, total = o->nframes + (last ? 1 : 0);
    size_t want = total < GF_LGA_SHEET_FRAMES ? total : GF_LGA_SHEET_FRAMES;
    for (size_t k = 0; k < want; k++) {
        size_t i = want == 1 ? 0 : (size_t)floor((double)k * (double)(total - 1) / (double)(want - 1) + 0.5);
        pick[n++] = i < o->nframes ? o->frames[i] : *last;
    }
    char path[GF_PATH_MAX + 64];
    snprintf(path, sizeof path, "%s/sheet.png", o->dir);
    return gf_lga_sheet_draw(pick, n, title, path);
}

static gf_status gf_lga_write_profile(const gf_lga_out *o, const gf_lga *l, double *angle, double *left, double *right)
{
    int w = gf_lga_width(l);
    double *p = GF_NEW(double, w);
    if (!p) return gf_error_set(GF_ERR_NOMEM, "out of memory (heap profile)");
    gf_lga_profile(l, p);
    *angle = gf_lga_slope_angle(p, w, GF_LGA_SLOPE_LO, GF_LGA_SLOPE_HI, left, right);
    char path[GF_PATH_MAX + 64], tmp[GF_PATH_MAX + 80];
    snprintf(path, sizeof path, "%s/profile.csv", o->dir);
    FILE *f;
    gf_status st = gf_atomic_open(path, tmp, sizeof tmp, &f);
    if (st == GF_OK) {
        fprintf(f, "x,height\n");
        for (int i = 0; i < w; i++) {
            if (!isfinite(p[i])) continue;
            double x, y;
            gf_lga_site_position(i, 0, &x, &y);
            fprintf(f, "%.4f,%.4f\n", x, p[i]);
        }
        st = gf_atomic_commit(f, tmp, path);
    }
    GF_DELETE(p, w);
    return st;
}

static gf_status gf_lga_write_summary(const gf_lga_out *o, const gf_lga *l, const gf_lga_summary *s, const char *status)
{
    char path[GF_PATH_MAX + 64], tmp[GF_PATH_MAX + 80];
    snprintf(path, sizeof path, "%s/summary.json", o->dir);
    FILE *f;
    gf_status st = gf_atomic_open(path, tmp, sizeof tmp, &f);
    if (st != GF_OK) return st;
    gf_lga_stats t = gf_lga_get_stats(l);
    gf_json j = gf_json_start(f, true);
    gf_json_object_begin(&j, NULL);
    gf_json_string(&j, "granflow_version", gf_version());
    gf_json_string(&j, "status", status);
    gf_json_string(&j, "scenario", gf_lga_scenario_name(s->scenario));
    if (s->scenario == GF_LGA_SILO) {
        gf_json_string(&j, "silo_flow", l->d.flow == GF_LGA_FUNNEL ? "funnel" : "mass");
        gf_json_general(&j, "hopper_angle", gf_lga_hopper_angle(&l->d), 6);
        gf_json_general(&j, "outlet_width", l->d.outlet_width, 6);
    }
    gf_json_uint(&j, "seed", l->d.seed);
    gf_json_general(&j, "p", l->d.p, 6);
    gf_json_general(&j, "q", l->d.q, 6);
    gf_json_general(&j, "g", l->d.g, 6);
    gf_json_general(&j, "h", l->d.h, 6);
    gf_json_general(&j, "k", l->d.k, 6);
    gf_json_general(&j, "b", l->d.b, 6);
    gf_json_int(&j, "lattice_width", t.width);
    gf_json_int(&j, "lattice_height", t.height);
    gf_json_int(&j, "fluid_sites", t.fluid_sites);
    gf_json_int(&j, "iterations", s->iterations);
    gf_json_int(&j, "particles_initial", s->particles_initial);
    gf_json_int(&j, "particles_added", s->particles_added);
    gf_json_int(&j, "particles_removed", s->particles_removed);
    gf_json_int(&j, "particles_final", s->particles_final);
    if (s->iterations_to_empty >= 0) gf_json_int(&j, "iterations_to_empty", s->iterations_to_empty);
    else gf_json_null(&j, "iterations_to_empty");
    int64_t span = s->iterations_to_empty >= 0 ? s->iterations_to_empty : s->iterations;
    // When the outflow happened, whether or not the silo emptied (a funnel
    // flow leaves a stagnant heap: iterations_to_empty is null there).
    static const char *const names[] = {"iterations_to_stop", "t50", "t90", "t99"};
    const int64_t times[] = {s->iterations_to_stop, s->t50, s->t90, s->t99};
    for (size_t k = 0; k < 4; k++) {
        if (times[k] >= 0) gf_json_int(&j, names[k], times[k]);
        else gf_json_null(&j, names[k]);
    }
    gf_json_general(&j, "mean_outflow_rate", s->iterations > 0 ? (double)s->particles_removed / (double)span : NAN, 6);
    gf_json_general(&j, "slope_angle", s->slope_angle, 6);
    gf_json_general(&j, "slope_left", s->slope_left, 6);
    gf_json_general(&j, "slope_right", s->slope_right, 6);
    gf_json_general(&j, "wave_variance_initial", s->wave_variance_initial, 6);
    gf_json_general(&j, "wave_variance_final", s->wave_variance_final, 6);
    gf_json_general(&j, "wave_variance_ratio", s->wave_variance_final / s->wave_variance_initial, 6);
    gf_json_general(&j, "wall_seconds", s->wall_seconds, 6);
    gf_json_general(&j, "site_updates_per_second", s->site_updates_per_second, 6);
    gf_json_end(&j);
    return gf_atomic_commit(f, tmp, path);
}

static void gf_lga_out_close(gf_lga_out *o)
{
    if (o->outflow) gf_atomic_abort(o->outflow, o->outflow_tmp);
    if (o->waves) gf_atomic_abort(o->waves, o->waves_tmp);
    o->outflow = o->waves = NULL;
    for (size_t i = 0; i < o->nframes; i++) gf_lga_frame_free(&o->frames[i]);
    if (o->frames) GF_DELETE(o->frames, GF_LGA_KEEP_FRAMES);
    if (o->out_iter) GF_DELETE(o->out_iter, o->iter_cap);
    if (o->out_count) GF_DELETE(o->out_count, o->count_cap);
    o->out_iter = o->out_count = NULL;
    o->frames = NULL;
}

// Doubles the capacity of `*a` (`*cap` values) when `n` values fill it.
static bool gf_lga_grow(int64_t **a, size_t *cap, size_t n)
{
    if (n < *cap) return true;
    size_t grown = *cap ? 2 * *cap : 1024;
    int64_t *q = gf_realloc(*a, *cap * sizeof *q, grown * sizeof *q);
    if (!q) return false;
    *a = q;
    *cap = grown;
    return true;
}

// Notes that `count` particles left in `iteration` (for t50, t90, t99).
static gf_status gf_lga_note_outflow(gf_lga_out *o, int64_t iteration, int64_t count)
{
    if (!gf_lga_grow(&o->out_iter, &o->iter_cap, o->nout) || !gf_lga_grow(&o->out_count, &o->count_cap, o->nout))
        return gf_error_set(GF_ERR_NOMEM, "out of memory (LGA outflow record)");
    o->out_iter[o->nout] = iteration;
    o->out_count[o->nout++] = count;
    return GF_OK;
}

// Whether the run is over (auto ends; an explicit lga.iterations is handled by the caller).
static bool gf_lga_auto_done(const gf_lga *l, int64_t *quiet, int64_t *last_out, int64_t *fed_at)
{
    gf_lga_stats s = gf_lga_get_stats(l);
    switch (l->scenario) {
    case GF_LGA_CHANNEL: return s.iteration >= GF_LGA_CHANNEL_ITERATIONS;
    case GF_LGA_SILO:
        if (s.last_outflow > 0) *last_out = s.iteration;
        return s.particles == 0 || s.iteration - *last_out >= GF_LGA_STALL_ITERATIONS || s.iteration >= GF_LGA_SILO_MAX;
    case GF_LGA_PILE:
        // a heap that buries the feed cannot take more: give up after ten times the feeding time
        if (s.to_add > 0)
            return (double)s.iteration >= 10.0 * (double)(s.added + s.to_add) / l->d.feed_rate + 1000.0;
        if (*fed_at < 0) *fed_at = s.iteration;
        if (s.iteration % 10 == 0) *quiet = gf_lga_moving(l) == 0 ? *quiet + 10 : 0;
        return *quiet >= GF_LGA_QUIET || s.iteration - *fed_at >= GF_LGA_PILE_SETTLE_MAX;
    }
    return true;
}

// The automaton reads the [lga] keys and run.seed; any other key changed
// from its default (run.duration, spot.*) would be silently ignored, so it
// is refused, named.
static gf_status gf_lga_check_keys(const gf_config *cfg)
{
    gf_config c = *cfg, d = gf_config_default();
    gf_status st = gf_config_validate(&c);
    if (st == GF_OK) st = gf_config_validate(&d);
    if (st != GF_OK) return st;
    for (size_t i = 0; i < gf_keys_count; i++) {
        const gf_key *k = &gf_keys[i];
        if (!strcmp(k->section, "lga") || (!strcmp(k->section, "run") && !strcmp(k->name, "seed"))) continue;
        char a[GF_PATH_MAX], b[GF_PATH_MAX];
        gf_keys_format(k, &c, a, sizeof a);
        gf_keys_format(k, &d, b, sizeof b);
        if (strcmp(a, b) != 0)
            return gf_error_set(GF_ERR_PARAM,
                                "%s.%s = %s: the lattice-gas automaton does not use this key (it reads the "
                                "[lga] keys and run.seed)",
                                k->section, k->name, a);
    }
    return GF_OK;
}

gf_status gf_lga_run_dir(const gf_config *cfg, const gf_lga_run_opts *opts, gf_lga_summary *summary)
{
    if (!cfg || !opts || !opts->dir || !opts->dir[0]) return gf_error_set(GF_ERR_PARAM, "gf_lga_run_dir: no config or directory");
    gf_status st0 = gf_lga_check_keys(cfg);
    if (st0 != GF_OK) return st0;
    gf_lga_out o = {.keep_every = 1};
    if (snprintf(o.dir, sizeof o.dir, "%s", opts->dir) >= (int)sizeof o.dir)
        return gf_error_set(GF_ERR_PARAM, "output directory path too long");
    if (!opts->force && gf_lga_dir_busy(o.dir))
        return gf_error_set(GF_ERR_EXISTS, "%s is not empty: clear it or use another directory", o.dir);
    // Everything that can fail on bad input happens before the directory is touched.
    gf_lga *l = NULL;
    gf_status st = gf_lga_create(cfg, &l);
    if (st != GF_OK) return st;
    if ((st = gf_lga_pictures_check(l->w, l->h, GF_LGA_MAP_PX, GF_LGA_SHEET_FRAMES)) != GF_OK) {
        gf_lga_destroy(l);
        return st;
    }
    char maps[GF_PATH_MAX + 16], path[GF_PATH_MAX + 32];
    snprintf(maps, sizeof maps, "%s/maps", o.dir);
    static const char *const png[] = {".png"};
    if ((st = gf_fs_mkdirs(maps)) == GF_OK) st = gf_fs_clear(maps, "map_", png, 1); // no old maps left behind
    snprintf(path, sizeof path, "%s/config.ini", o.dir);
    if (st == GF_OK) st = gf_config_save(&l->cfg, path);
    o.frames = GF_NEW(gf_lga_frame, GF_LGA_KEEP_FRAMES);
    if (st == GF_OK && !o.frames) st = gf_error_set(GF_ERR_NOMEM, "out of memory (LGA frames)");
    snprintf(o.outflow_path, sizeof o.outflow_path, "%s/outflow.csv", o.dir);
    if (st == GF_OK) st = gf_atomic_open(o.outflow_path, o.outflow_tmp, sizeof o.outflow_tmp, &o.outflow);
    if (st == GF_OK && l->scenario == GF_LGA_CHANNEL) {
        snprintf(o.waves_path, sizeof o.waves_path, "%s/waves.csv", o.dir);
        st = gf_atomic_open(o.waves_path, o.waves_tmp, sizeof o.waves_tmp, &o.waves);
    }

    gf_lga_summary s = {.scenario = l->scenario, .iterations_to_empty = -1, .iterations_to_stop = -1, .t50 = -1,
                        .t90 = -1, .t99 = -1, .slope_angle = NAN, .slope_left = NAN,
                        .slope_right = NAN, .wave_variance_initial = NAN, .wave_variance_final = NAN};
    char title[96];
    snprintf(title, sizeof title, "LGA %s", gf_lga_scenario_name(l->scenario));
    const int64_t until = l->d.iterations; // 0: the scenario's own end
    const int64_t every = l->d.snapshot_interval;
    double wave_sum = 0;
    int64_t wave_n = 0, quiet = 0, last_out = 0, fed_at = -1;
    bool interrupted = false;
    if (st == GF_OK) {
        fprintf(o.outflow, "iteration,outflow,particles,added\n0,0,%lld,0\n", (long long)l->particles);
        if (o.waves) {
            s.wave_variance_initial = gf_lga_wave_variance(l, GF_LGA_WAVE_WINDOW);
            fprintf(o.waves, "iteration,variance\n0,%.8g\n", s.wave_variance_initial);
        }
        st = gf_lga_snapshot(&o, l, title);
    }
    s.particles_initial = l->particles;
    double wall0 = gf_clock_now();
    while (st == GF_OK) {
        if (until > 0 ? l->iteration >= until : gf_lga_auto_done(l, &quiet, &last_out, &fed_at)) break;
        if (l->scenario == GF_LGA_SILO && l->particles == 0) break;
        if (opts->stop && *opts->stop) {
            interrupted = true;
            break;
        }
        gf_lga_step(l);
        fprintf(o.outflow, "%lld,%lld,%lld,%lld\n", (long long)l->iteration, (long long)l->last_outflow,
                (long long)l->particles, (long long)l->added);
        if (l->last_outflow > 0) st = gf_lga_note_outflow(&o, l->iteration, l->last_outflow);
        if (l->scenario == GF_LGA_SILO && l->particles == 0 && s.iterations_to_empty < 0)
            s.iterations_to_empty = l->iteration;
        if (o.waves && l->iteration % GF_LGA_WAVE_EVERY == 0) {
            double v = gf_lga_wave_variance(l, GF_LGA_WAVE_WINDOW);
            fprintf(o.waves, "%lld,%.8g\n", (long long)l->iteration, v);
            int64_t horizon = until > 0 ? until : GF_LGA_CHANNEL_ITERATIONS;
            if (4 * l->iteration >= 3 * horizon) { // the last quarter of the run
                wave_sum += v;
                wave_n++;
            }
        }
        if (st == GF_OK && l->iteration % every == 0) st = gf_lga_snapshot(&o, l, title);
        if (opts->progress && l->iteration % 100 == 0) {
            gf_lga_stats ps = gf_lga_get_stats(l);
            opts->progress(opts->ctx, &ps, until);
        }
    }
    s.wall_seconds = gf_clock_now() - wall0;
    s.iterations = l->iteration;
    s.particles_added = l->added;
    s.particles_removed = l->removed;
    s.particles_final = l->particles;
    s.iterations_to_stop = gf_lga_outflow_time(o.out_iter, o.out_count, o.nout, 1.0);
    s.t50 = gf_lga_outflow_time(o.out_iter, o.out_count, o.nout, 0.50);
    s.t90 = gf_lga_outflow_time(o.out_iter, o.out_count, o.nout, 0.90);
    s.t99 = gf_lga_outflow_time(o.out_iter, o.out_count, o.nout, 0.99);
    s.site_updates_per_second = s.wall_seconds > 0 ? (double)l->fluid_sites * (double)l->iteration / s.wall_seconds : 0;
    if (o.waves) s.wave_variance_final = wave_n ? wave_sum / (double)wave_n : gf_lga_wave_variance(l, GF_LGA_WAVE_WINDOW);

    gf_lga_frame last = {0};
    bool have_last = false;
    if (st == GF_OK && l->iteration % every != 0) {
        // the final state: its own map, and the sheet's last panel
        if ((st = gf_lga_frame_capture(l, &last)) == GF_OK) {
            have_last = true;
            snprintf(path, sizeof path, "%s/maps/map_%06lld.png", o.dir, (long long)last.iteration);
            st = gf_lga_frame_draw(&last, GF_LGA_MAP_PX, title, path);
        }
    }
    if (st == GF_OK) st = gf_lga_write_sheet(&o, have_last ? &last : NULL, title);
    if (have_last) gf_lga_frame_free(&last);
    if (st == GF_OK && l->scenario == GF_LGA_PILE) st = gf_lga_write_profile(&o, l, &s.slope_angle, &s.slope_left, &s.slope_right);
    if (st == GF_OK) {
        st = gf_atomic_commit(o.outflow, o.outflow_tmp, o.outflow_path);
        o.outflow = NULL;
    }
    if (st == GF_OK && o.waves) {
        st = gf_atomic_commit(o.waves, o.waves_tmp, o.waves_path);
        o.waves = NULL;
    }
    if (st == GF_OK) st = gf_lga_write_summary(&o, l, &s, interrupted ? "interrupted" : "complete");
    gf_lga_out_close(&o);
    gf_lga_destroy(l);
    if (summary) *summary = s;
    if (st == GF_OK && interrupted) return gf_error_set(GF_ERR_INTERRUPTED, "interrupted at iteration %lld; the results so far are in %s", (long long)s.iterations, opts->dir);
    return st;
}

gf_lga_run_opts gf_lga_run_opts_default(void) { return (gf_lga_run_opts){.dir = NULL}; }
