// SPDX-License-Identifier: MIT
// The run directory: the engine's snapshot and checkpoint hooks turned into files.
#include "geom/container.h"
#include "granflow/run.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <time.h>
#include <unistd.h>

#include "core/atomic_file.h"
#include "core/clock.h"
#include "core/alloc.h"
#include "core/error.h"
#include "core/fs.h"
#include "core/json.h"
#include "core/limits.h"
#include "geom/mesh.h"
#include "granflow/defs.h"
#include "granflow/packing.h"
#include "io/vtk.h"
#include "run/mesh_copy.h"
#include "spot/sim_internal.h"
#ifdef GF_MPI
#include <mpi.h>

#include "spot/par_mpi.h"
#endif

typedef struct gf_rundir {
    const gf_config *cfg; ///< handed to config/ and the writers (config.ini); read d
    gf_rundir_defs d;
    const gf_run_opts *opts;
    char dir[GF_PATH_MAX];
    double wall0;
    double t0;
    uint64_t moves0;
    gf_packing scratch;
    int32_t *pass;      ///< recirculation: the pass of each scratch particle
    size_t pass_cap;
    const char *status;
    FILE *exits;          // exits.csv, open for appending
    size_t exits_written; // exits already in it
    double flow_t0;       // when this invocation began (stall clock without exits)
    bool stalled;         // the snapshot hook saw no exit for run.stall_time
    int lock_fd;          // holds the lock on dir/.lock
    uint64_t *vtu_index;  // the .vtu snapshots of snapshots.pvd: their indices and times
    double *vtu_time;
    size_t nvtu, vtu_cap;
    void *reserve;        // memory held for the checkpoint (gf_make_room), freed while one is built
    size_t reserve_size;
} gf_rundir;

// A fresh run starts from an empty run directory: everything an earlier run
// (and analyze/render with their default -o) wrote there goes first, the
// checkpoint before anything else, so that a clear cut short leaves no
// resumable mix of two runs. Other files are left alone.
static gf_status gf_clear_run(const char *dir)
{
    static const char *const files[] = {"checkpoint.bin", "checkpoint.bin.tmp", "summary.json", "summary.json.tmp",
                                        "exits.csv",      "exits.csv.tmp",      "config.ini",   "config.ini.tmp",
                                        "container.vtk",  "container.vtk.tmp",  "container.vtp",
                                        "container.vtp.tmp", "snapshots.pvd", "snapshots.pvd.tmp", "stress.csv"};
    static const char *const trees[] = {"analysis", "render"};
    char path[GF_PATH_MAX + 32];
    gf_status st = GF_OK;
    for (size_t i = 0; st == GF_OK && i < sizeof files / sizeof files[0]; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, files[i]);
        st = gf_fs_remove(path);
    }
    for (size_t i = 0; st == GF_OK && i < sizeof trees / sizeof trees[0]; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, trees[i]);
        st = gf_fs_remove_tree(path);
    }
    snprintf(path, sizeof path, "%s/snapshots", dir);
    static const char *const snaps[] = {".dump", ".vtu", ".tmp"};
    return st == GF_OK ? gf_fs_clear(path, "snap_", snaps, sizeof snaps / sizeof snaps[0]) : st;
}

// One run at a time per directory: a POSIX record lock on dir/.lock, held
// until the process ends (the kernel drops it even after kill -9). The file
// holds the owner's pid for the message of the next one.
// The refusal of a directory whose lock (open on fd) another run holds; closes fd.
static gf_status gf_lock_busy(const char *dir, const char *path, int fd)
{
    char pid[32] = "";
    ssize_t n = pread(fd, pid, sizeof pid - 1, 0);
    pid[n > 0 ? n : 0] = '\0';
    pid[strcspn(pid, "\n")] = '\0';
    close(fd);
    return gf_error_set(GF_ERR_PARAM,
                        "%s is in use by another granflow run (%s%s%slock %s): wait for it to end, "
                        "or use another directory",
                        dir, *pid ? "pid " : "", pid, *pid ? ", " : "", path);
}

gf_status gf_run_dir_check_free(const char *dir)
{
    if (!dir) return gf_error_set(GF_ERR_PARAM, "gf_run_dir_check_free: NULL directory");
    char path[GF_PATH_MAX + 32];
    snprintf(path, sizeof path, "%s/.lock", dir);
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) return GF_OK; // no lock file (or no directory): nobody runs there
    struct flock fl = {.l_type = F_WRLCK, .l_whence = SEEK_SET};
    if (fcntl(fd, F_GETLK, &fl) == 0 && fl.l_type != F_UNLCK) return gf_lock_busy(dir, path, fd);
    close(fd);
    return GF_OK;
}

static gf_status gf_lock_dir(const char *dir, int *fd_out)
{
    char path[GF_PATH_MAX + 32];
    snprintf(path, sizeof path, "%s/.lock", dir);
    int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd < 0) return gf_error_set(GF_ERR_IO, "%s: cannot create the run lock: %s", path, strerror(errno));
    struct flock fl = {.l_type = F_WRLCK, .l_whence = SEEK_SET};
    if (fcntl(fd, F_SETLK, &fl) != 0) {
        int err = errno;
        if (err == EACCES || err == EAGAIN) return gf_lock_busy(dir, path, fd);
        close(fd);
        return gf_error_set(GF_ERR_IO, "%s: cannot lock: %s", path, strerror(err));
    }
    char pid[32];
    int len = snprintf(pid, sizeof pid, "%ld\n", (long)getpid());
    if (ftruncate(fd, 0) != 0 || write(fd, pid, (size_t)len) != len) { /* the pid is only for messages */
    }
    *fd_out = fd;
    return GF_OK;
}

static void gf_path(char *out, size_t n, const char *dir, const char *name)
{
    snprintf(out, n, "%s/%s", dir, name);
}

static gf_status gf_save_progress(gf_rundir *rd, const gf_sim *sim);

// snapshots.pvd: the .vtu series with its times in tau, for ParaView (which
// otherwise plays the numbered files against their numbers).
static gf_status gf_write_pvd(const gf_rundir *rd)
{
    enum { NAME = 40 };
    char path[GF_PATH_MAX + 32];
    gf_path(path, sizeof path, rd->dir, "snapshots.pvd");
    char *names = rd->nvtu ? GF_NEW(char, rd->nvtu * NAME) : NULL;
    const char **files = rd->nvtu ? GF_NEW(const char *, rd->nvtu) : NULL;
    gf_status st = GF_OK;
    if (rd->nvtu && (!names || !files)) st = gf_error_set(GF_ERR_NOMEM, "out of memory for %s", path);
    for (size_t k = 0; st == GF_OK && k < rd->nvtu; k++) {
        snprintf(names + k * NAME, NAME, "snapshots/snap_%06" PRIu64 ".vtu", rd->vtu_index[k]);
        files[k] = names + k * NAME;
    }
    if (st == GF_OK) st = gf_vtk_write_collection(path, files, rd->vtu_time, rd->nvtu);
    if (names) GF_DELETE(names, rd->nvtu * NAME);
    if (files) GF_DELETE(files, rd->nvtu);
    return st;
}

// Snapshot `index` at `time` enters the series, replacing those from index
// on (a resumed run writes again the snapshots past its checkpoint).
static gf_status gf_add_vtu(gf_rundir *rd, uint64_t index, double time)
{
    while (rd->nvtu && rd->vtu_index[rd->nvtu - 1] >= index) rd->nvtu--;
    if (rd->nvtu == rd->vtu_cap) {
        size_t nc = rd->vtu_cap ? 2 * rd->vtu_cap : 64;
        uint64_t *i = gf_realloc(rd->vtu_index, rd->vtu_cap * sizeof *i, nc * sizeof *i);
        if (i) rd->vtu_index = i;
        double *t = i ? gf_realloc(rd->vtu_time, rd->vtu_cap * sizeof *t, nc * sizeof *t) : NULL;
        if (t) rd->vtu_time = t;
        if (!i || !t) return gf_error_set(GF_ERR_NOMEM, "out of memory for the list of snapshots");
        rd->vtu_cap = nc;
    }
    rd->vtu_index[rd->nvtu] = index;
    rd->vtu_time[rd->nvtu++] = time;
    return GF_OK;
}

// A resumed run's series starts with the .vtu already there: snap_000000,
// snap_000001, ... up to the first missing one, each with its own time.
static gf_status gf_find_vtus(gf_rundir *rd)
{
    char path[GF_PATH_MAX + 64];
    gf_status st = GF_OK;
    for (uint64_t k = 0; st == GF_OK; k++) {
        snprintf(path, sizeof path, "%s/snapshots/snap_%06" PRIu64 ".vtu", rd->dir, k);
        if (access(path, F_OK) != 0) break;
        double t;
        st = gf_vtk_read_time(path, &t);
        if (st == GF_OK) st = gf_add_vtu(rd, k, t);
    }
    return st;
}

// The snapshot files of one frame (rd->scratch holds its particles).
static gf_status gf_write_snapshot_files(gf_rundir *rd, const gf_sim *sim, uint64_t index, double time)
{
    gf_status st = GF_OK;
    const int32_t *pass = NULL;
    if (rd->d.recirculate) {
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
    const gf_output_format fmt = rd->d.format;
    if (fmt & GF_OUTPUT_DUMP) {
        snprintf(path, sizeof path, "%s/snapshots/snap_%06" PRIu64 ".dump", rd->dir, index);
        st = gf_run_write_snapshot(path, rd->cfg, &rd->scratch, pass, time, gf_sim_get_stats(sim).events);
    }
    if (st == GF_OK && (fmt & GF_OUTPUT_VTK)) {
        snprintf(path, sizeof path, "%s/snapshots/snap_%06" PRIu64 ".vtu", rd->dir, index);
        st = gf_vtk_write_particles_as(path, &rd->scratch, pass, time, rd->d.vtk_encoding);
        if (st == GF_OK) st = gf_add_vtu(rd, index, time);
        // Rewriting the .pvd at every snapshot costs the square of their number (core/limits.h).
        if (st == GF_OK && rd->nvtu <= GF_PVD_EVERY_SNAPSHOT) st = gf_write_pvd(rd);
    }
    return st == GF_OK ? gf_save_progress(rd, sim) : st;
}

static gf_status gf_on_snapshot(void *ctx, const gf_sim *sim, uint64_t index, double time)
{
    gf_rundir *rd = ctx;
    // (The other MPI ranks write nothing: they need not hold the particles,
    // and ranks that read their regions do not, issue 23.)
    gf_status st = rd->opts->replica ? GF_OK : gf_sim_particles(sim, &rd->scratch);
    if (st == GF_OK && !rd->opts->replica) st = gf_write_snapshot_files(rd, sim, index, time);
    if (st != GF_OK) return st;
    // A silo that no longer drains would write snapshots of the same heap
    // until run.duration: stop it (run.stall_time, checked at each snapshot).
    size_t nexit;
    const gf_exit *e = gf_sim_exits(sim, &nexit);
    double last = nexit ? fmax(e[nexit - 1].time, rd->flow_t0) : rd->flow_t0;
    if (rd->d.stall_time > 0 && gf_sim_get_stats(sim).particles_remaining > 0 && time - last >= rd->d.stall_time) {
        rd->stalled = true;
        return gf_error_set(GF_ERR_STATE, "stalled"); // ends gf_sim_run; gf_run_dir tells why
    }
    return GF_OK;
}

// One line of exits.csv.
static void gf_print_exit(FILE *f, const gf_exit *e)
{
    fprintf(f, "%" PRId64 ",%.9g,%.7f,%.7f,%" PRId64 ",%.9g,%.7f\n", e->id, e->time, e->x, e->y, e->pass, e->entry_time,
            e->entry_r);
}

// exits.csv as a whole, atomically, from the engine's list (a resume drops
// the lines appended after its checkpoint this way).
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
    for (size_t i = 0; i < n; i++) gf_print_exit(f, &e[i]);
    return gf_atomic_commit(f, tmp, path);
}

// Appends the exits not yet in exits.csv and flushes them to the kernel, so
// that they survive the process (SIGKILL, an OOM kill).
static gf_status gf_append_exits(gf_rundir *rd, const gf_sim *sim)
{
    if (!rd->exits) return GF_OK;
    size_t n;
    const gf_exit *e = gf_sim_exits(sim, &n);
    for (size_t i = rd->exits_written; i < n; i++) gf_print_exit(rd->exits, &e[i]);
    if (fflush(rd->exits) != 0 || ferror(rd->exits))
        return gf_error_set(GF_ERR_IO, "%s/exits.csv: cannot write: %s", rd->dir, strerror(errno ? errno : EIO));
    rd->exits_written = n;
    return GF_OK;
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
    gf_json j = gf_json_start(f, true);
    gf_json_object_begin(&j, NULL);
    gf_json_string(&j, "granflow_version", gf_version());
    gf_json_string(&j, "status", rd->status);
    if (!strcmp(rd->status, "failed")) gf_json_string(&j, "error", gf_last_error());
    gf_json_uint(&j, "seed", rd->d.seed);
    gf_json_uint(&j, "particles_initial", s.particles_initial);
    gf_json_uint(&j, "particles_remaining", s.particles_remaining);
    gf_json_uint(&j, "particles_exited", s.particles_exited);
    gf_json_uint(&j, "particles_reinserted", s.particles_reinserted);
    gf_json_uint(&j, "spots_inserted", s.spots_inserted);
    gf_json_uint(&j, "spots_deleted", s.spots_deleted);
    gf_json_uint(&j, "spots_active", s.spots_active);
    gf_json_uint(&j, "spot_moves", s.spot_moves);
    gf_json_uint(&j, "relax_calls", s.relax_calls);
    gf_json_uint(&j, "events", s.events);
    gf_json_uint(&j, "global_relaxations", s.global_relaxations);
    gf_json_fixed(&j, "t_relax", s.relax_seconds, 3);
    gf_json_uint(&j, "neighbour_list_builds", s.nlist_builds);
    gf_json_general(&j, "simulated_time", s.time, 9);
    gf_json_fixed(&j, "wall_seconds", wall, 3);
    gf_json_fixed(&j, "steps_per_second", sps, 1);
    gf_json_end(&j);
    return gf_atomic_commit(f, tmp, path);
}

// Exits and summary: on disk at every snapshot and checkpoint.
static gf_status gf_save_progress(gf_rundir *rd, const gf_sim *sim)
{
    gf_status st = gf_append_exits(rd, sim);
    if (st == GF_OK) st = gf_write_summary(rd, sim);
    return st;
}

static gf_status gf_save_all(gf_rundir *rd, const gf_sim *sim)
{
    if (rd->opts->replica) return GF_OK;
    char path[GF_PATH_MAX + 32];
    gf_path(path, sizeof path, rd->dir, "checkpoint.bin");
    // The memory held for the checkpoint since the start is what it is
    // built in now; held again afterwards, for the next one.
    if (rd->reserve) gf_free(rd->reserve, rd->reserve_size);
    gf_status st = gf_sim_save(sim, path);
    rd->reserve = rd->reserve_size ? gf_alloc(rd->reserve_size) : NULL;
    if (st == GF_OK && (rd->d.format & GF_OUTPUT_VTK)) st = gf_write_pvd(rd);
    return st == GF_OK ? gf_save_progress(rd, sim) : st;
}

static void gf_mb(char *buf, size_t n, double bytes) { snprintf(buf, n, "%.3g MB", bytes / 1e6); }

// What the checkpoint will need at the end of the run, made sure of before
// the run starts (issue 26: a 200,000-particle run under a 100 MB limit ran to
// its end, then failed to write its checkpoint): memory to build it in, held
// from now on; below the file size limit; twice on disk (the new one is
// written beside the old, then renamed). The snapshots' share of the disk is
// only estimated, so a shortfall there is a warning.
static gf_status gf_make_room(gf_rundir *rd, const gf_sim *sim)
{
    const double bound = (double)gf_sim_checkpoint_bound(sim);
    char need[32], have[32];
    gf_mb(need, sizeof need, bound);
    struct rlimit rl;
    if (getrlimit(RLIMIT_FSIZE, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY && bound > (double)rl.rlim_cur) {
        gf_mb(have, sizeof have, (double)rl.rlim_cur);
        return gf_error_set(GF_ERR_IO,
                            "cannot write checkpoint: File too large: it will take up to %s by the end of the run, "
                            "over the file size limit of %s (ulimit -f)",
                            need, have);
    }
    struct statvfs fs;
    if (statvfs(rd->dir, &fs) == 0) {
        const double free_bytes = (double)fs.f_bavail * (double)fs.f_frsize;
        gf_mb(have, sizeof have, free_bytes);
        if (free_bytes < 2.0 * bound)
            return gf_error_set(GF_ERR_IO,
                                "cannot write checkpoint: No space left on device: it will take up to %s by the end "
                                "of the run (twice while one replaces the other), and %s has %s free",
                                need, rd->dir, have);
        const gf_rundir_defs *c = &rd->d;
        const double left = c->duration - gf_sim_get_stats(sim).time;
        const double snaps =
            (c->format & GF_OUTPUT_DUMP) ? floor(fmax(0.0, left) / c->snapshot_interval) + 1.0 : 0.0;
        const double dumps = snaps * 64.0 * (double)gf_sim_get_stats(sim).particles_remaining; // ~64 bytes an atom line
        if (free_bytes < 2.0 * bound + dumps) {
            char total[32];
            gf_mb(total, sizeof total, 2.0 * bound + dumps);
            gf_warn("%s has %s free, and this run may write about %s (up to %.0f snapshots and its checkpoint): "
                    "it may fill the disk before the end",
                    rd->dir, have, total, snaps);
        }
    }
    if (rd->opts->replica) return GF_OK; // (rank 0 writes the checkpoint)
    rd->reserve_size = (size_t)bound;
    rd->reserve = gf_alloc(rd->reserve_size);
    if (!rd->reserve)
        return gf_error_set(GF_ERR_NOMEM,
                            "out of memory for the checkpoint: it will take up to %s by the end of the run, and that "
                            "much cannot be allocated now (a memory limit?)",
                            need);
    return GF_OK;
}

static gf_status gf_on_checkpoint(void *ctx, const gf_sim *sim) { return gf_save_all(ctx, sim); }

static void gf_on_progress(void *ctx, const gf_sim *sim)
{
    gf_rundir *rd = ctx;
    gf_sim_stats s = gf_sim_get_stats(sim);
    double wall = gf_clock_now() - rd->wall0;
    gf_run_progress p = {GF_RUN_PHASE_RUNNING, s.time, rd->d.duration, rd->t0, s.particles_initial,
                         s.particles_remaining, wall > 0 ? (double)(s.spot_moves - rd->moves0) / wall : 0.0, wall, NULL};
    rd->opts->progress(rd->opts->ctx, &p);
}

// container.vtp (ParaView, meshio) and container.vtk (OVITO, legacy
// readers): the walls up to a diameter above the packing.
// The walls' height: a diameter above the highest particle this process holds.
static gf_status gf_container_top(gf_rundir *rd, const gf_sim *sim, double *top)
{
    gf_status st = gf_sim_particles(sim, &rd->scratch);
    *top = 1.0;
    for (size_t i = 0; st == GF_OK && i < rd->scratch.n; i++) *top = fmax(*top, rd->scratch.z[i] + rd->scratch.r[i] + 1.0);
    return st;
}

static gf_status gf_write_container(gf_rundir *rd, double top)
{
    gf_status st;
    gf_container box = gf_container_make(rd->cfg);
    gf_mesh m;
    if ((st = gf_container_mesh(&box, top, 96, &m)) != GF_OK) return st;
    char path[GF_PATH_MAX + 32];
    gf_path(path, sizeof path, rd->dir, "container.vtp");
    st = gf_vtk_write_surface(path, &m, rd->d.vtk_encoding);
    gf_path(path, sizeof path, rd->dir, "container.vtk");
    if (st == GF_OK) st = gf_vtk_write_mesh(path, &m, "granflow container");
    gf_mesh_free(&m);
    return st;
}

static gf_status gf_make_packing(const gf_config *cfg, const gf_run_opts *opts, gf_packing *pk)
{
    gf_packing_import_report rep;
    gf_rundir_defs d;
    gf_config_rundir_defs(cfg, &d);
    gf_status st = gf_packing_for_config(cfg, &(gf_packing_opts){.stop = opts->stop}, pk, &rep);
    if (st == GF_ERR_INTERRUPTED)
        gf_error_set(st, "interrupted while building the packing; nothing was written to %s", opts->dir);
    // A DEM packing may hold other atom types (a frozen floor) and particles
    // already falling through the orifice: dropped, and said so.
    if (st == GF_OK && d.packing[0] && opts->progress) {
        char note[GF_PATH_MAX + 256];
        char units[96] = "";
        if (d.unit_diameter != 1.0)
            snprintf(units, sizeof units, ", lengths / %g (dump.diameter)", d.unit_diameter);
        snprintf(note, sizeof note,
                 "%zu of %zu particles from %s (%zu below the base counted as exited, %zu of other atom types "
                 "dropped%s)",
                 pk->n, rep.read, d.packing, rep.below_base, rep.other_types, units);
        gf_run_progress p = {.phase = GF_RUN_PHASE_IMPORTED, .until = d.duration, .initial = pk->n, .note = note};
        opts->progress(opts->ctx, &p);
    }
    return st;
}

// The run directory made ready for `sim`: created, locked, cleared of an
// earlier run (fresh runs) or of exits past the checkpoint (resume), the
// configuration written, exits.csv open for appending, summary.json "running".
static gf_status gf_prepare_dir(gf_rundir *rd, const gf_sim *sim)
{
    if (rd->opts->replica) return GF_OK; // the process that writes dir prepares it
    char snaps[GF_PATH_MAX + 32], cfgpath[GF_PATH_MAX + 32], exits[GF_PATH_MAX + 32];
    gf_path(snaps, sizeof snaps, rd->dir, "snapshots");
    gf_path(cfgpath, sizeof cfgpath, rd->dir, "config.ini");
    gf_path(exits, sizeof exits, rd->dir, "exits.csv");
    gf_status st = gf_fs_mkdirs(rd->dir);
    if (st == GF_OK) st = gf_lock_dir(rd->dir, &rd->lock_fd);
    if (st == GF_OK && !rd->opts->resume) st = gf_clear_run(rd->dir);
    if (st == GF_OK) st = gf_fs_mkdirs(snaps);
    if (st == GF_OK) st = gf_run_save_config(rd->cfg, rd->dir, cfgpath); // and a mesh container's STL
    if (st == GF_OK) st = gf_write_exits(rd, sim);
    if (st == GF_OK && !rd->opts->resume) st = gf_sim_write_stress(sim, rd->dir); // sfr: the field it follows
    if (st != GF_OK) return st;
    rd->exits = fopen(exits, "a");
    if (!rd->exits) return gf_error_set(GF_ERR_IO, "%s: cannot open for appending: %s", exits, strerror(errno));
    gf_sim_exits(sim, &rd->exits_written);
    return gf_write_summary(rd, sim);
}

gf_status gf_run_dir(const gf_config *cfg_in, const gf_run_opts *opts, gf_sim_stats *stats)
{
    if (stats) memset(stats, 0, sizeof *stats);
    gf_config cfg = *cfg_in;
    gf_status st = gf_config_validate(&cfg);
    if (st == GF_OK) st = gf_sim_check_config(&cfg); // before a packing is built
    if (st != GF_OK) return st;
    gf_rundir rd = {.cfg = &cfg, .opts = opts, .status = "running", .lock_fd = -1};
    gf_config_rundir_defs(&cfg, &rd.d);
    if (snprintf(rd.dir, sizeof rd.dir, "%s", opts->dir) >= (int)sizeof rd.dir)
        return gf_error_set(GF_ERR_PARAM, "run directory path too long (%zu bytes, at most %d)", strlen(opts->dir),
                            GF_PATH_MAX - 1);
    // A directory another run holds is refused first: before a checkpoint
    // is read or a packing built (issue 26: a resume of a locked directory
    // said "no run to resume"; a fresh run built its packing, then failed).
    // Only the process that writes dir asks: a replica would see the lock
    // rank 0 may already hold for this very run (a failed CI run: "Q is in
    // use by another granflow run" on a 4-rank resume).
    if (!opts->replica && (st = gf_run_dir_check_free(rd.dir)) != GF_OK) return st;
    char ckpt[GF_PATH_MAX + 32];
    gf_path(ckpt, sizeof ckpt, rd.dir, "checkpoint.bin");
    if (!opts->resume && !opts->force && !opts->replica && access(ckpt, F_OK) == 0)
        return gf_error_set(GF_ERR_EXISTS,
                            "%s already holds a run (%s exists): resume it, clear it, or use another directory",
                            rd.dir, ckpt);
    // Everything that can fail on bad input happens before the directory is touched.
    gf_sim *sim = NULL;
    if (opts->resume) {
        st = gf_sim_load(&cfg, ckpt, &sim);
        if (st == GF_OK && rd.d.duration < gf_sim_get_stats(sim).time)
            st = gf_error_set(GF_ERR_PARAM, "run.duration = %g is before the time this run already reached (%g tau)",
                              rd.d.duration, gf_sim_get_stats(sim).time);
    } else {
        if (opts->progress) {
            gf_run_progress p = {.phase = rd.d.packing[0] ? GF_RUN_PHASE_READING : GF_RUN_PHASE_PACKING,
                                 .until = rd.d.duration};
            opts->progress(opts->ctx, &p);
        }
        gf_packing pk = {0};
#ifdef GF_MPI
        // On MPI ranks rank 0 packs and sends the packing; a stop on any rank
        // stops all of them there together (each packing its own, a rank
        // stopped meanwhile left the others waiting for it for ever).
        // The domain engine with a packing.file: every rank reads it keeping
        // its own region (issue 23: a rank holds only its region).
        const bool windowed = gf_mpi_windowed(&cfg);
        if (windowed) {
            st = gf_mpi_sim_create_part(&cfg, &sim);
        } else {
            st = gf_mpi_rank() == 0 ? gf_make_packing(&cfg, opts, &pk) : GF_OK;
            st = gf_mpi_share_packing(st, &pk, opts->stop);
            if (st == GF_ERR_INTERRUPTED)
                gf_error_set(st, "interrupted while building the packing; nothing was written to %s", opts->dir);
        }
        if (st == GF_OK && !windowed) st = gf_sim_create(&cfg, &pk, &sim);
#else
        st = gf_make_packing(&cfg, opts, &pk);
        if (st == GF_OK) st = gf_sim_create(&cfg, &pk, &sim);
#endif
        gf_packing_free(&pk);
    }
    // config.ini must hold the configuration: refused before the directory is
    // made (issue 26: a packing.file with a line break left an empty one).
    if (st == GF_OK) st = gf_config_check_writable(&cfg);
    if (st == GF_OK) st = gf_prepare_dir(&rd, sim);
    if (st == GF_OK && !opts->resume && (rd.d.format & GF_OUTPUT_VTK)) {
        double top;
        st = gf_container_top(&rd, sim, &top);
#ifdef GF_MPI
        // Ranks that read their regions of packing.file hold their own
        // particles only: the highest of every rank's (each takes part).
        if (gf_mpi_size() > 1) MPI_Allreduce(MPI_IN_PLACE, &top, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
#endif
        if (st == GF_OK && !opts->replica) st = gf_write_container(&rd, top);
    }
    if (st == GF_OK && opts->resume && !opts->replica && (rd.d.format & GF_OUTPUT_VTK)) st = gf_find_vtus(&rd);
    if (st != GF_OK) {
        if (rd.exits) fclose(rd.exits);
        if (rd.lock_fd >= 0) close(rd.lock_fd);
        gf_packing_free(&rd.scratch);
        if (rd.vtu_index) GF_DELETE(rd.vtu_index, rd.vtu_cap);
        if (rd.vtu_time) GF_DELETE(rd.vtu_time, rd.vtu_cap);
        gf_sim_destroy(sim);
        return st;
    }
    rd.moves0 = gf_sim_get_stats(sim).spot_moves;
    rd.t0 = rd.flow_t0 = gf_sim_get_stats(sim).time;
    rd.wall0 = gf_clock_now();
    gf_sim_hooks hooks = {
        .ctx = &rd,
        .snapshot = gf_on_snapshot,
        .checkpoint = gf_on_checkpoint,
        .progress = opts->progress ? gf_on_progress : NULL,
        .progress_every = 1u << 15,
        .stop = opts->stop,
    };
    st = gf_make_room(&rd, sim);
    if (st == GF_OK) st = gf_sim_run(sim, rd.d.duration, &hooks);
    size_t nexit;
    gf_sim_exits(sim, &nexit);
    double reached = gf_sim_get_stats(sim).time;
    if (rd.stalled && nexit == 0) {
        // Not one particle has left: a silo that cannot drain is an error.
        // An exit plane far below the outlet (or the pipe's end) is reached
        // only slowly: below it a particle moves only as spots pass, there
        // is no free fall, so say so.
        char deep[256] = "";
        const gf_container ctr = gf_container_make(&cfg);
        if (rd.d.exit_level < -1.0)
            snprintf(deep, sizeof deep,
                     "; the exit plane is %g d below the %s, and a particle on its way there moves only as "
                     "spots pass (there is no free fall): raise container.exit_z, or run.stall_time to wait "
                     "longer",
                     -rd.d.exit_level,
                     gf_container_outlet_name(&ctr));
        st = gf_error_set(GF_ERR_STATE,
                          "no particle has left the silo in %g tau (run.stall_time): it cannot drain "
                          "(check the orifice, container.exit_z and the packing); stopped at t = %.4g tau%s",
                          rd.d.stall_time, reached, deep);
    } else if (rd.stalled) {
        st = GF_OK;
    }
    if (st == GF_OK || st == GF_ERR_INTERRUPTED) {
        gf_status run_st = st;
        rd.status = st == GF_ERR_INTERRUPTED ? "interrupted" : rd.stalled ? "stalled" : "complete";
        st = gf_save_all(&rd, sim);
        if (st == GF_OK) {
            st = run_st;
            if (st == GF_ERR_INTERRUPTED)
                gf_error_set(st, "stopped at t = %.4g tau; checkpoint written to %s", reached, ckpt);
        }
        if (st == GF_OK && rd.stalled && opts->progress) {
            char note[256];
            snprintf(note, sizeof note,
                     "the flow stopped: no particle has left since t = %.4g tau (run.stall_time = %g); "
                     "stopped at t = %.4g tau with %zu particles left",
                     gf_sim_exits(sim, &nexit)[nexit - 1].time, rd.d.stall_time, reached,
                     gf_sim_get_stats(sim).particles_remaining);
            gf_run_progress p = {.phase = GF_RUN_PHASE_STALLED, .time = reached, .until = rd.d.duration, .note = note};
            opts->progress(opts->ctx, &p);
        }
        if (opts->progress && run_st == GF_OK) {
            gf_sim_stats s = gf_sim_get_stats(sim);
            double wall = gf_clock_now() - rd.wall0;
            gf_run_progress p = {GF_RUN_PHASE_DONE, s.time, rd.d.duration, rd.t0, s.particles_initial,
                                 s.particles_remaining, wall > 0 ? (double)(s.spot_moves - rd.moves0) / wall : 0.0, wall, NULL};
            opts->progress(opts->ctx, &p);
        }
    }
    if (st != GF_OK && st != GF_ERR_INTERRUPTED) {
        // A failed run says so in its summary (not "running"), with the reason.
        rd.status = "failed";
        char why[2048];
        snprintf(why, sizeof why, "%s", gf_last_error());
        gf_append_exits(&rd, sim);
        gf_error_set(st, "%s", why); // the summary carries it
        if (!opts->replica) gf_write_summary(&rd, sim);
        gf_error_set(st, "%s", why);
    }
    if (stats) *stats = gf_sim_get_stats(sim);
    if (rd.exits) fclose(rd.exits);
    if (rd.lock_fd >= 0) close(rd.lock_fd);
    gf_packing_free(&rd.scratch);
    GF_DELETE(rd.pass, rd.pass_cap);
    if (rd.vtu_index) GF_DELETE(rd.vtu_index, rd.vtu_cap);
    if (rd.vtu_time) GF_DELETE(rd.vtu_time, rd.vtu_cap);
    if (rd.reserve) gf_free(rd.reserve, rd.reserve_size);
    gf_sim_destroy(sim);
    return st;
}

gf_run_opts gf_run_opts_default(void) { return (gf_run_opts){.dir = NULL}; }

const char *gf_run_phase_name(gf_run_phase phase)
{
    static const char *const names[] = {"packing", "reading", "imported", "running", "stalled", "done"};
    return (unsigned)phase < sizeof names / sizeof names[0] ? names[phase] : "?";
}

gf_status gf_sim_write_run_dir(const gf_sim *sim, const char *dir, int force)
{
    if (!sim || !dir || !*dir) return gf_error_set(GF_ERR_PARAM, "gf_sim_write_run_dir: NULL argument");
    const gf_config *cfg = gf_sim_config(sim);
    gf_run_opts opts = gf_run_opts_default();
    opts.dir = dir;
    opts.force = force;
    gf_rundir rd = {.cfg = cfg, .opts = &opts, .status = "saved", .lock_fd = -1, .wall0 = gf_clock_now()};
    gf_config_rundir_defs(cfg, &rd.d);
    if (snprintf(rd.dir, sizeof rd.dir, "%s", dir) >= (int)sizeof rd.dir)
        return gf_error_set(GF_ERR_PARAM, "run directory path too long (%zu bytes, at most %d)", strlen(dir),
                            GF_PATH_MAX - 1);
    char path[GF_PATH_MAX + 64];
    gf_path(path, sizeof path, rd.dir, "checkpoint.bin");
    if (!force && access(path, F_OK) == 0)
        return gf_error_set(GF_ERR_EXISTS, "%s already holds a run (%s exists): clear it, force, or use another directory",
                            rd.dir, path);
    gf_status st = gf_prepare_dir(&rd, sim);
    double top;
    if (st == GF_OK && (rd.d.format & GF_OUTPUT_VTK) && (st = gf_container_top(&rd, sim, &top)) == GF_OK)
        st = gf_write_container(&rd, top);
    // The snapshot of now, numbered on the snapshot grid as gf_run_dir numbers
    // them, so that a resumed run's next snapshots follow it.
    const double t = gf_sim_get_stats(sim).time, dsnap = rd.d.snapshot_interval;
    const uint64_t index = dsnap > 0 ? (uint64_t)floor(t / dsnap + 1e-9) : 0;
    if (st == GF_OK && (rd.d.format & GF_OUTPUT_DUMP)) {
        snprintf(path, sizeof path, "%s/snapshots/snap_%06" PRIu64 ".dump", rd.dir, index);
        st = gf_sim_write_snapshot(sim, path);
    }
    if (st == GF_OK && (rd.d.format & GF_OUTPUT_VTK)) {
        snprintf(path, sizeof path, "%s/snapshots/snap_%06" PRIu64 ".vtu", rd.dir, index);
        st = gf_sim_write_vtk(sim, path);
    }
    if (st == GF_OK) st = gf_save_all(&rd, sim);
    if (rd.exits) fclose(rd.exits);
    if (rd.lock_fd >= 0) close(rd.lock_fd);
    gf_packing_free(&rd.scratch);
    return st;
}
