// SPDX-License-Identifier: MIT
// The run directory: the engine's snapshot and checkpoint hooks turned into files.
#include "granflow/run.h"

#include <dirent.h>
#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "core/atomic_file.h"
#include "core/clock.h"
#include "core/alloc.h"
#include "core/error.h"
#include "geom/mesh.h"
#include "granflow/packing.h"
#include "io/vtk.h"

typedef struct gf_rundir {
    const gf_config *cfg;
    const gf_run_opts *opts;
    char dir[GF_PATH_MAX];
    double wall0;
    double t0;
    uint64_t moves0;
    gf_packing scratch;
    int32_t *pass;      ///< recirculation: the pass of each scratch particle
    size_t pass_cap;
    const char *status;
} gf_rundir;

static gf_status gf_mkdir(const char *path)
{
    if (mkdir(path, 0777) == 0 || errno == EEXIST) {
        struct stat sb;
        if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode)) return GF_OK;
        return gf_error_set(GF_ERR_IO, "%s: exists and is not a directory", path);
    }
    return gf_error_set(GF_ERR_IO, "%s: cannot create directory: %s", path, strerror(errno));
}

// mkdir -p
static gf_status gf_mkdirs(const char *path)
{
    char buf[GF_PATH_MAX];
    if (snprintf(buf, sizeof buf, "%s", path) >= (int)sizeof buf)
        return gf_error_set(GF_ERR_PARAM, "path too long: %s", path);
    for (char *s = buf + 1; *s; s++) {
        if (*s != '/') continue;
        *s = '\0';
        gf_status st = gf_mkdir(buf);
        *s = '/';
        if (st != GF_OK) return st;
    }
    return gf_mkdir(buf);
}

// A fresh run over an old directory must not leave the old run's later snapshots.
static gf_status gf_clear_snapshots(const char *snaps)
{
    DIR *d = opendir(snaps);
    if (!d) return GF_OK;
    gf_status st = GF_OK;
    for (struct dirent *e; (e = readdir(d)) != NULL;) {
        size_t n = strlen(e->d_name);
        if (strncmp(e->d_name, "snap_", 5) != 0 || n < 6 ||
            (strcmp(e->d_name + n - 5, ".dump") != 0 && strcmp(e->d_name + n - 4, ".vtu") != 0))
            continue;
        char path[GF_PATH_MAX + 300];
        snprintf(path, sizeof path, "%s/%s", snaps, e->d_name);
        if (remove(path) != 0) st = gf_error_set(GF_ERR_IO, "%s: cannot remove: %s", path, strerror(errno));
    }
    closedir(d);
    return st;
}

static void gf_path(char *out, size_t n, const char *dir, const char *name)
{
    snprintf(out, n, "%s/%s", dir, name);
}

gf_status gf_run_write_snapshot(const char *path, const gf_config *cfg, const gf_packing *p, const int32_t *pass,
                                double time, uint64_t step)
{
    char tmp[GF_PATH_MAX + 8];
    FILE *f;
    gf_status st = gf_atomic_open(path, tmp, sizeof tmp, &f);
    if (st != GF_OK) return st;
    double ztop = 1.0;
    for (size_t i = 0; i < p->n; i++)
        if (p->z[i] + p->r[i] > ztop) ztop = p->z[i] + p->r[i];
    double zlo = cfg->exit_z < 0.0 ? cfg->exit_z : 0.0;
    fprintf(f, "ITEM: TIME\n%.17g\nITEM: TIMESTEP\n%" PRIu64 "\nITEM: NUMBER OF ATOMS\n%zu\n", time, step, p->n);
    fprintf(f, "ITEM: BOX BOUNDS ff ff ff\n%.17g %.17g\n%.17g %.17g\n%.17g %.17g\n", -0.5 * cfg->container_width,
            0.5 * cfg->container_width, -0.5 * cfg->container_depth, 0.5 * cfg->container_depth, zlo, ztop);
    bool poly = false; // a radius column only when the radii differ from the papers' 0.5
    for (size_t i = 0; i < p->n && !poly; i++) poly = p->r[i] != 0.5;
    fprintf(f, "ITEM: ATOMS id type x y z%s%s\n", poly ? " radius" : "", pass ? " pass" : "");
    for (size_t i = 0; i < p->n; i++) {
        fprintf(f, "%" PRId64 " %d %.7f %.7f %.7f", p->id[i], p->layer[i], p->x[i], p->y[i], p->z[i]);
        if (poly) fprintf(f, " %.7g", p->r[i]);
        if (pass) fprintf(f, " %d", (int)pass[i]);
        fputc('\n', f);
    }
    return gf_atomic_commit(f, tmp, path);
}

static gf_status gf_on_snapshot(void *ctx, const gf_sim *sim, uint64_t index, double time)
{
    gf_rundir *rd = ctx;
    gf_status st = gf_sim_particles(sim, &rd->scratch);
    if (st != GF_OK) return st;
    const int32_t *pass = NULL;
    if (rd->cfg->run_recirculate) {
        size_t n = rd->scratch.n;
        if (n > rd->pass_cap) {
            GF_DELETE(rd->pass, rd->pass_cap);
            rd->pass_cap = 0;
            if (!(rd->pass = GF_NEW(int32_t, n))) return gf_error_set(GF_ERR_NOMEM, "out of memory");
            rd->pass_cap = n;
        }
        if ((st = gf_sim_passes(sim, rd->pass, n)) != GF_OK) return st;
        pass = rd->pass;
    }
    char path[GF_PATH_MAX + 64];
    const gf_output_format fmt = rd->cfg->output_format;
    if (fmt != GF_OUTPUT_VTK) {
        snprintf(path, sizeof path, "%s/snapshots/snap_%06" PRIu64 ".dump", rd->dir, index);
        st = gf_run_write_snapshot(path, rd->cfg, &rd->scratch, pass, time, gf_sim_get_stats(sim).events);
    }
    if (st == GF_OK && fmt != GF_OUTPUT_DUMP) {
        snprintf(path, sizeof path, "%s/snapshots/snap_%06" PRIu64 ".vtu", rd->dir, index);
        st = gf_vtk_write_particles(path, &rd->scratch, pass, time);
    }
    return st;
}

static gf_status gf_write_exits(gf_rundir *rd, const gf_sim *sim)
{
    char path[GF_PATH_MAX + 32], tmp[GF_PATH_MAX + 40];
    gf_path(path, sizeof path, rd->dir, "exits.csv");
    FILE *f;
    gf_status st = gf_atomic_open(path, tmp, sizeof tmp, &f);
    if (st != GF_OK) return st;
    size_t n;
    const gf_exit *e = gf_sim_exits(sim, &n);
    fputs("id,time,x,y,pass,entry_time,entry_r\n", f);
    for (size_t i = 0; i < n; i++)
        fprintf(f, "%" PRId64 ",%.9g,%.7f,%.7f,%" PRId64 ",%.9g,%.7f\n", e[i].id, e[i].time, e[i].x, e[i].y, e[i].pass,
                e[i].entry_time, e[i].entry_r);
    return gf_atomic_commit(f, tmp, path);
}

static gf_status gf_write_summary(gf_rundir *rd, const gf_sim *sim)
{
    char path[GF_PATH_MAX + 32], tmp[GF_PATH_MAX + 40];
    gf_path(path, sizeof path, rd->dir, "summary.json");
    FILE *f;
    gf_status st = gf_atomic_open(path, tmp, sizeof tmp, &f);
    if (st != GF_OK) return st;
    gf_sim_stats s = gf_sim_get_stats(sim);
    double wall = gf_clock_now() - rd->wall0;
    double sps = wall > 0 ? (double)(s.spot_moves - rd->moves0) / wall : 0.0;
    fprintf(f, "{\n  \"granflow_version\": \"%s\",\n  \"status\": \"%s\",\n", gf_version(), rd->status);
    fprintf(f, "  \"seed\": %" PRIu64 ",\n", rd->cfg->run_seed);
    fprintf(f, "  \"particles_initial\": %zu,\n  \"particles_remaining\": %zu,\n  \"particles_exited\": %zu,\n",
            s.particles_initial, s.particles_remaining, s.particles_exited);
    fprintf(f, "  \"particles_reinserted\": %zu,\n", s.particles_reinserted);
    fprintf(f, "  \"spots_inserted\": %" PRIu64 ",\n  \"spots_deleted\": %" PRIu64 ",\n  \"spots_active\": %zu,\n",
            s.spots_inserted, s.spots_deleted, s.spots_active);
    fprintf(f, "  \"spot_moves\": %" PRIu64 ",\n  \"relax_calls\": %" PRIu64 ",\n  \"events\": %" PRIu64 ",\n",
            s.spot_moves, s.relax_calls, s.events);
    fprintf(f, "  \"global_relaxations\": %" PRIu64 ",\n  \"t_relax\": %.3f,\n", s.global_relaxations, s.relax_seconds);
    fprintf(f, "  \"neighbour_list_builds\": %" PRIu64 ",\n", s.nlist_builds);
    fprintf(f, "  \"simulated_time\": %.9g,\n  \"wall_seconds\": %.3f,\n  \"steps_per_second\": %.1f\n}\n", s.time,
            wall, sps);
    return gf_atomic_commit(f, tmp, path);
}

static gf_status gf_save_all(gf_rundir *rd, const gf_sim *sim)
{
    char path[GF_PATH_MAX + 32];
    gf_path(path, sizeof path, rd->dir, "checkpoint.bin");
    gf_status st = gf_sim_save(sim, path);
    if (st == GF_OK) st = gf_write_exits(rd, sim);
    if (st == GF_OK) st = gf_write_summary(rd, sim);
    return st;
}

static gf_status gf_on_checkpoint(void *ctx, const gf_sim *sim) { return gf_save_all(ctx, sim); }

static void gf_on_progress(void *ctx, const gf_sim *sim)
{
    gf_rundir *rd = ctx;
    gf_sim_stats s = gf_sim_get_stats(sim);
    double wall = gf_clock_now() - rd->wall0;
    gf_run_progress p = {"running", s.time, rd->cfg->run_duration, rd->t0, s.particles_initial, s.particles_remaining,
                         wall > 0 ? (double)(s.spot_moves - rd->moves0) / wall : 0.0, wall, NULL};
    rd->opts->progress(rd->opts->ctx, &p);
}

// container.vtk: the walls up to a diameter above the packing, for ParaView.
static gf_status gf_write_container(gf_rundir *rd, const gf_sim *sim)
{
    gf_status st = gf_sim_particles(sim, &rd->scratch);
    if (st != GF_OK) return st;
    double top = 1.0;
    for (size_t i = 0; i < rd->scratch.n; i++) top = fmax(top, rd->scratch.z[i] + rd->scratch.r[i] + 1.0);
    gf_container box = gf_container_make(rd->cfg);
    gf_mesh m;
    if ((st = gf_container_mesh(&box, top, 96, &m)) != GF_OK) return st;
    char path[GF_PATH_MAX + 32];
    gf_path(path, sizeof path, rd->dir, "container.vtk");
    st = gf_vtk_write_mesh(path, &m, "granflow container");
    gf_mesh_free(&m);
    return st;
}

static gf_status gf_make_packing(const gf_config *cfg, const gf_run_opts *opts, gf_packing *pk)
{
    if (!cfg->packing_file[0]) return gf_packing_generate(cfg, pk);
    // A DEM packing may hold other atom types (a frozen floor) and particles
    // already falling through the orifice: dropped, and said so.
    gf_packing_import_report rep;
    gf_status st = gf_packing_import(cfg, pk, &rep);
    if (st == GF_OK && opts->progress) {
        char note[GF_PATH_MAX + 256];
        snprintf(note, sizeof note,
                 "%zu of %zu particles from %s (%zu below the base counted as exited, %zu of other atom types dropped)",
                 pk->n, rep.read, cfg->packing_file, rep.below_base, rep.other_types);
        gf_run_progress p = {.phase = "imported", .until = cfg->run_duration, .initial = pk->n, .note = note};
        opts->progress(opts->ctx, &p);
    }
    return st;
}

gf_status gf_run_dir(const gf_config *cfg_in, const gf_run_opts *opts, gf_sim_stats *stats)
{
    gf_config cfg = *cfg_in;
    gf_status st = gf_config_validate(&cfg);
    if (st != GF_OK) return st;
    gf_rundir rd = {.cfg = &cfg, .opts = opts, .status = "running"};
    if (snprintf(rd.dir, sizeof rd.dir, "%s", opts->dir) >= (int)sizeof rd.dir)
        return gf_error_set(GF_ERR_PARAM, "run directory path too long");
    char ckpt[GF_PATH_MAX + 32], snaps[GF_PATH_MAX + 32], cfgpath[GF_PATH_MAX + 32];
    gf_path(ckpt, sizeof ckpt, rd.dir, "checkpoint.bin");
    gf_path(snaps, sizeof snaps, rd.dir, "snapshots");
    gf_path(cfgpath, sizeof cfgpath, rd.dir, "config.ini");
    if (!opts->resume && !opts->force && access(ckpt, F_OK) == 0)
        return gf_error_set(GF_ERR_PARAM,
                            "%s already holds a run (%s exists): resume it with --resume %s, "
                            "overwrite it with --force, or choose another -o",
                            rd.dir, ckpt, rd.dir);
    // Everything that can fail on bad input happens before the directory is touched.
    gf_sim *sim = NULL;
    if (opts->resume) {
        st = gf_sim_load(&cfg, ckpt, &sim);
        if (st == GF_OK && cfg.run_duration < gf_sim_get_stats(sim).time)
            st = gf_error_set(GF_ERR_PARAM, "run.duration = %g is before the time this run already reached (%g tau)",
                              cfg.run_duration, gf_sim_get_stats(sim).time);
    } else {
        if (opts->progress) {
            gf_run_progress p = {cfg.packing_file[0] ? "reading" : "packing", 0.0, cfg.run_duration, 0.0, 0, 0, 0.0, 0.0, NULL};
            opts->progress(opts->ctx, &p);
        }
        gf_packing pk = {0};
        st = gf_make_packing(&cfg, opts, &pk);
        if (st == GF_OK) st = gf_sim_create(&cfg, &pk, &sim);
        gf_packing_free(&pk);
    }
    if (st == GF_OK && ((st = gf_mkdirs(rd.dir)) == GF_OK && (st = gf_mkdir(snaps)) == GF_OK) && !opts->resume)
        st = gf_clear_snapshots(snaps);
    if (st == GF_OK) st = gf_config_save(&cfg, cfgpath);
    if (st == GF_OK && !opts->resume && cfg.output_format != GF_OUTPUT_DUMP) st = gf_write_container(&rd, sim);
    if (st != GF_OK) {
        gf_sim_destroy(sim);
        return st;
    }
    rd.moves0 = gf_sim_get_stats(sim).spot_moves;
    rd.t0 = gf_sim_get_stats(sim).time;
    rd.wall0 = gf_clock_now();
    gf_run_hooks hooks = {
        .ctx = &rd,
        .snapshot = gf_on_snapshot,
        .checkpoint = gf_on_checkpoint,
        .progress = opts->progress ? gf_on_progress : NULL,
        .progress_every = 1u << 15,
        .stop = opts->stop,
    };
    st = gf_sim_run(sim, cfg.run_duration, &hooks);
    if (st == GF_OK || st == GF_ERR_INTERRUPTED) {
        gf_status run_st = st;
        rd.status = st == GF_OK ? "complete" : "interrupted";
        st = gf_save_all(&rd, sim);
        if (st == GF_OK) {
            st = run_st;
            if (st == GF_ERR_INTERRUPTED)
                gf_error_set(st, "stopped at t = %.4g tau; checkpoint written to %s", gf_sim_get_stats(sim).time,
                             ckpt);
        }
        if (opts->progress && run_st == GF_OK) {
            gf_sim_stats s = gf_sim_get_stats(sim);
            double wall = gf_clock_now() - rd.wall0;
            gf_run_progress p = {"done", s.time, cfg.run_duration, rd.t0, s.particles_initial, s.particles_remaining,
                                 wall > 0 ? (double)(s.spot_moves - rd.moves0) / wall : 0.0, wall, NULL};
            opts->progress(opts->ctx, &p);
        }
    }
    if (stats) *stats = gf_sim_get_stats(sim);
    gf_packing_free(&rd.scratch);
    GF_DELETE(rd.pass, rd.pass_cap);
    gf_sim_destroy(sim);
    return st;
}
