// SPDX-License-Identifier: MIT
// Running LAMMPS on the inputs of gf_dem_write_inputs: lmp (under mpirun -np N
// when asked and available) in the run directory, its output read line by
// line for the phase markers (`granflow-phase NAME A B`, printed by the
// inputs) and the thermo lines (step time particles ke) that drive progress.
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "core/alloc.h"
#include "core/atomic_file.h"
#include "core/clock.h"
#include "core/error.h"
#include "dem/dem_internal.h"
#include "dem/lammps_guard.h"
#include "dem/lammps_output.h"
#include "granflow/defs.h"
#include "granflow/dem.h"

/// Finds `name` on PATH (or takes it as a path when it holds a '/').
static int gf_dem_which(const char *name, char *out, size_t n)
{
    if (strchr(name, '/')) {
        snprintf(out, n, "%s", name);
        return access(out, X_OK) == 0;
    }
    const char *path = getenv("PATH");
    if (!path) path = "/usr/local/bin:/usr/bin:/bin";
    while (*path) {
        const char *end = strchr(path, ':');
        size_t len = end ? (size_t)(end - path) : strlen(path);
        if (len > 0 && snprintf(out, n, "%.*s/%s", (int)len, path, name) < (int)n && access(out, X_OK) == 0)
            return 1;
        path += len + (end ? 1 : 0);
    }
    return 0;
}

static void gf_dem_nap(void)
{
    struct timespec ts = {0, 100 * 1000 * 1000};
    nanosleep(&ts, NULL);
}

/// Feeds LAMMPS' output on `fd` line by line to gf_dem_line until it ends,
/// polling r->o->stop at least every 0.2 s. True when stopped by the flag.
static bool gf_dem_read(int fd, gf_dem_reader *r)
{
    volatile sig_atomic_t *stop = r->o->stop;
    char acc[4096], chunk[4096];
    size_t len = 0;
    for (;;) {
        if (stop && *stop) return true;
        struct pollfd p = {.fd = fd, .events = POLLIN};
        int np = poll(&p, 1, 200);
        if (np < 0 && errno != EINTR) break;
        if (np <= 0) continue; // a signal or the time-out: look at the flag again
        ssize_t n = read(fd, chunk, sizeof chunk);
        if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
        if (n <= 0) break; // end of output: LAMMPS is done
        for (ssize_t i = 0; i < n; i++) {
            if (len < sizeof acc - 1) acc[len++] = chunk[i]; // an over-long line is cut, still ended at its newline
            if (chunk[i] == '\n') {
                acc[len] = '\0';
                gf_dem_line(r, acc);
                len = 0;
            }
        }
    }
    if (len) {
        acc[len] = '\0';
        gf_dem_line(r, acc);
    }
    return stop && *stop;
}

/// Ends LAMMPS' process group: SIGTERM, up to 10 s for the group (mpirun
/// passes it to its ranks) to go, then SIGKILL. The child is reaped: no zombie.
static void gf_dem_stop_child(pid_t pid, int *status)
{
    kill(-pid, SIGTERM);
    kill(pid, SIGTERM); // in case it had not made its group yet
    bool reaped = false;
    for (int k = 0; k < 100; k++) {
        if (!reaped && waitpid(pid, status, WNOHANG) == pid) reaped = true;
        if (reaped && kill(-pid, 0) != 0) return; // the whole group is gone
        gf_dem_nap();
    }
    kill(-pid, SIGKILL);
    if (!reaped) {
        kill(pid, SIGKILL);
        while (waitpid(pid, status, 0) < 0 && errno == EINTR) {
        }
    }
}

/// Runs one input file; returns GF_OK when LAMMPS exits 0.
static gf_status gf_dem_run_one(const char *dir, const char *script, const char *lmp, const char *mpirun, int ranks,
                                gf_dem_reader *r)
{
    char log[64], np[16];
    snprintf(log, sizeof log, "log.%s", script + 3); // in.fill -> log.fill
    snprintf(np, sizeof np, "%d", ranks);
    const char *argv[16];
    int k = 0;
    if (mpirun) {
        argv[k++] = mpirun;
        argv[k++] = "-np";
        argv[k++] = np;
        if (ranks > gf_cpu_count()) argv[k++] = "--oversubscribe";
    }
    argv[k++] = lmp;
    argv[k++] = "-in";
    argv[k++] = script;
    argv[k++] = "-log";
    argv[k++] = log;
    argv[k++] = "-nocite";
    argv[k] = NULL;
    int fd[2];
    if (pipe(fd) != 0) return gf_error_set(GF_ERR_IO, "cannot make a pipe for LAMMPS: %s", strerror(errno));
    fflush(NULL);
    pid_t parent = getpid();
    pid_t pid = fork();
    if (pid < 0) {
        close(fd[0]);
        close(fd[1]);
        return gf_error_set(GF_ERR_IO, "cannot start LAMMPS: %s", strerror(errno));
    }
    if (pid == 0) {
        setpgid(0, 0); // LAMMPS and what it starts (mpirun's ranks) form one group that a stop ends
        dup2(fd[1], STDOUT_FILENO);
        dup2(fd[1], STDERR_FILENO);
        close(fd[0]);
        close(fd[1]);
        int devnull = open("/dev/null", O_RDONLY);
        if (devnull >= 0) dup2(devnull, STDIN_FILENO);
        if (chdir(dir) != 0) _exit(126);
        // Open MPI refuses root unless told; CI containers run as root.
        if (geteuid() == 0) {
            setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
            setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
        }
        if (!getenv("OMP_NUM_THREADS")) setenv("OMP_NUM_THREADS", "1", 1);
        // This child stays as LAMMPS' guard: it ends the group if granflow dies.
        gf_dem_guard_run(parent, (char *const *)argv);
    }
    close(fd[1]);
    setpgid(pid, pid); // as the child does (whichever runs first): its own group, to be stopped as one
    bool stopped = gf_dem_read(fd[0], r);
    close(fd[0]);
    int status = 0;
    if (stopped) {
        gf_dem_stop_child(pid, &status);
        return gf_error_set(GF_ERR_INTERRUPTED, "LAMMPS (%s/%s) stopped on request", dir, script);
    }
    // LAMMPS has closed its output but may not have ended: still a stop
    // polled every 0.1 s (a blocking waitpid ignored Ctrl-C until LAMMPS ended).
    volatile sig_atomic_t *stop = r->o->stop;
    for (;;) {
        pid_t w = waitpid(pid, &status, WNOHANG);
        if (w == pid) break;
        if (w < 0 && errno != EINTR)
            return gf_error_set(GF_ERR_IO, "LAMMPS (%s/%s): cannot wait for it: %s", dir, script, strerror(errno));
        if (stop && *stop) {
            gf_dem_stop_child(pid, &status);
            return gf_error_set(GF_ERR_INTERRUPTED, "LAMMPS (%s/%s) stopped on request", dir, script);
        }
        gf_dem_nap();
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && !r->error[0]) return GF_OK;
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
        return gf_error_set(GF_ERR_IO, "cannot execute %s", argv[0]);
    if (WIFSIGNALED(status)) {
        // Our own stop only when the flag is up (a signal to granflow after
        // LAMMPS closed its output); a crash or a kill by someone else is a
        // failure, not an interruption (issue 26: a segfault read as exit 130).
        if (r->o->stop && *r->o->stop)
            return gf_error_set(GF_ERR_INTERRUPTED, "LAMMPS (%s/%s) stopped by signal %d", dir, script,
                                WTERMSIG(status));
        return gf_error_set(GF_ERR_STATE, "LAMMPS crashed on %s/%s: killed by signal %d (%s); see %s/%s", dir,
                            script, WTERMSIG(status), strsignal(WTERMSIG(status)), dir, log);
    }
    return gf_error_set(GF_ERR_PARAM, "LAMMPS failed on %s/%s (see %s/%s): %s", dir, script, dir, log,
                        r->error[0] ? r->error : "non-zero exit status");
}

/// After a phase LAMMPS ended with exit 0: what it must have written is
/// there and new (modified since `since`, less a second for the file system's
/// coarse clock): the fill's settled.restart and packing.dump, at least one
/// snapshot of the drain. A LAMMPS that exits 0 without them (a wrong binary
/// under GF_LMP, an input edited by hand) would otherwise end in "done".
static gf_status gf_dem_check_outputs(const char *dir, bool fill, time_t since)
{
    char path[GF_PATH_MAX + 64];
    struct stat sb;
    if (fill) {
        const char *names[2] = {"settled.restart", "packing.dump"};
        for (int k = 0; k < 2; k++) {
            snprintf(path, sizeof path, "%s/%s", dir, names[k]);
            if (stat(path, &sb) != 0 || sb.st_mtime < since - 1 || sb.st_size == 0)
                return gf_error_set(GF_ERR_STATE,
                                    "LAMMPS ended the fill (%s/in.fill) with exit status 0 but wrote no %s "
                                    "(see %s/log.fill)",
                                    dir, path, dir);
        }
        return GF_OK;
    }
    snprintf(path, sizeof path, "%s/snapshots", dir);
    DIR *d = opendir(path);
    bool found = false;
    for (struct dirent *e; d && !found && (e = readdir(d)) != NULL;) {
        if (strncmp(e->d_name, "snap_", 5) != 0) continue;
        char file[GF_PATH_MAX + 320];
        snprintf(file, sizeof file, "%s/%s", path, e->d_name);
        found = stat(file, &sb) == 0 && sb.st_mtime >= since - 1 && sb.st_size > 0;
    }
    if (d) closedir(d);
    if (!found)
        return gf_error_set(GF_ERR_STATE,
                            "LAMMPS ended the drain (%s/in.drain) with exit status 0 but wrote no snapshot in %s "
                            "(see %s/log.drain)",
                            dir, path, dir);
    return GF_OK;
}

/// After LAMMPS was stopped: removes what the stopped phase may have left
/// half-written (the fill's settled.restart and packing.dump; the drain's
/// newest snapshot, if this drain wrote it: modified after `since`, less a
/// second for the file system's coarse clock) and writes DIR/interrupted.txt
/// saying so. The error message of the stop is kept.
static void gf_dem_mark_interrupted(const char *dir, bool fill, const gf_dem_reader *r, time_t since)
{
    char msg[1024], path[GF_PATH_MAX + 320], removed[GF_PATH_MAX + 64] = "";
    snprintf(msg, sizeof msg, "%s", gf_last_error());
    if (fill) {
        const char *names[2] = {"settled.restart", "packing.dump"};
        for (int k = 0; k < 2; k++) {
            snprintf(path, sizeof path, "%s/%s", dir, names[k]);
            if (unlink(path) == 0) snprintf(removed, sizeof removed, "settled.restart and packing.dump");
        }
    } else {
        char snaps[GF_PATH_MAX + 32], newest[256] = "";
        snprintf(snaps, sizeof snaps, "%s/snapshots", dir);
        DIR *d = opendir(snaps);
        for (struct dirent *e; d && (e = readdir(d)) != NULL;) // snap_NNNNNNNNN.dump: the largest name is the newest
            if (!strncmp(e->d_name, "snap_", 5) && strcmp(e->d_name, newest) > 0 && strlen(e->d_name) < sizeof newest)
                snprintf(newest, sizeof newest, "%s", e->d_name);
        if (d) closedir(d);
        snprintf(path, sizeof path, "%s/%s", snaps, newest);
        struct stat sb;
        bool ours = newest[0] && stat(path, &sb) == 0 && sb.st_mtime >= since - 1;
        if (ours && unlink(path) == 0) snprintf(removed, sizeof removed, "snapshots/%s", newest);
        else if (newest[0])
            snprintf(removed, sizeof removed, "nothing (the newest snapshot, %s, is older than this drain)", newest);
    }
    snprintf(path, sizeof path, "%s/%s", dir, GF_DEM_INTERRUPTED);
    char tmp[GF_PATH_MAX + 96];
    FILE *f;
    bool restarts = false;
    for (int k = 0; k < 2 && !fill; k++) {
        snprintf(path, sizeof path, "%s/drain.%c.restart", dir, "ab"[k]);
        restarts = restarts || access(path, F_OK) == 0;
    }
    snprintf(path, sizeof path, "%s/%s", dir, GF_DEM_INTERRUPTED);
    if (gf_atomic_open(path, tmp, sizeof tmp, &f) == GF_OK) {
        fprintf(f,
                "interrupted: LAMMPS was stopped during the %s (t = %.6g tau of the phase, %.0f s after the start)\n"
                "removed: %s\n"
                "again: granflow dem ... --run --force (from the fill)%s%s%s%s\n",
                r->p.phase != GF_DEM_PHASE_NONE ? gf_dem_phase_name(r->p.phase) : fill ? "fill" : "drain", r->p.time, gf_clock_now() - r->wall0,
                removed[0] ? removed : (fill ? "nothing (no settled packing was written)" : "nothing (no snapshot yet)"),
                fill ? "" : " or --drain-only (from settled.restart)",
                fill || !restarts ? "" : "\ncontinue: granflow dem -o ",
                fill || !restarts ? "" : dir,
                fill || !restarts ? "" : " --continue (from the newer of drain.a.restart and drain.b.restart)");
        gf_atomic_commit(f, tmp, path);
    }
    gf_error_set(GF_ERR_INTERRUPTED, "%s; %s/%s says what is left", msg, dir, GF_DEM_INTERRUPTED);
}

/// The LAMMPS binary (and mpirun, when o->ranks asks for more than one rank
/// and it is found; else *ranks is 1).
static gf_status gf_dem_find(const gf_dem_run_opts *o, char *lmp, char *mpirun, size_t n, int *ranks)
{
    const char *want = o->lmp ? o->lmp : getenv("GF_LMP") ? getenv("GF_LMP") : "lmp";
    if (!gf_dem_which(want, lmp, n))
        return gf_error_set(GF_ERR_IO,
                            "LAMMPS not found (%s): install it with `apt-get install lammps` (Debian's package "
                            "has the GRANULAR styles), or set GF_LMP to the binary",
                            want);
    *ranks = o->ranks < 1 ? gf_cpu_count() : o->ranks;
    if (*ranks > 1 && !gf_dem_which("mpirun", mpirun, n)) *ranks = 1;
    if (*ranks == 1) mpirun[0] = '\0';
    return GF_OK;
}

gf_status gf_dem_run(const char *dir, const gf_dem_run_opts *o)
{
    gf_dem_run_opts def = gf_dem_run_opts_default();
    if (!o) o = &def;
    char lmp[4096], mpirun[4096];
    int ranks;
    gf_status fs = gf_dem_find(o, lmp, mpirun, sizeof lmp, &ranks);
    if (fs != GF_OK) return fs;
    const bool use_mpi = mpirun[0] != '\0';
    const char *scripts[2] = {"in.fill", "in.drain"};
    gf_dem_reader r = {.o = o, .wall0 = gf_clock_now(), .t_phase = NAN};
    for (int k = o->drain_only ? 1 : 0; k < 2; k++) {
        char path[GF_PATH_MAX + 32];
        snprintf(path, sizeof path, "%s/%s", dir, scripts[k]);
        if (access(path, R_OK) != 0)
            return gf_error_set(GF_ERR_IO, "%s: %s (no LAMMPS inputs there: write them first)", path, strerror(errno));
        const time_t since = time(NULL);
        if (k == 1) { // a recirculating drain's records, an earlier drain's restart files and continuation (the
                      // drain writes them again; a stale one would mislead, or be continued)
            const char *names[6] = {"exits.csv", GF_DEM_REINSERTED, "drain.a.restart", "drain.b.restart",
                                    "in.continue", "log.continue"};
            for (int j = 0; j < 6; j++) {
                snprintf(path, sizeof path, "%s/%s", dir, names[j]);
                if (unlink(path) != 0 && errno != ENOENT)
                    return gf_error_set(GF_ERR_IO, "%s: cannot remove the previous drain's: %s", path, strerror(errno));
            }
        }
        gf_status st = gf_dem_run_one(dir, scripts[k], lmp, use_mpi ? mpirun : NULL, ranks, &r);
        if (st == GF_ERR_INTERRUPTED) gf_dem_mark_interrupted(dir, k == 0, &r, since);
        if (st == GF_OK) st = gf_dem_check_outputs(dir, k == 0, since);
        // run.recirculate: exits.csv from what LAMMPS put back, also when it
        // was stopped (the snapshots kept are read with them).
        if (k == 1 && (st == GF_OK || st == GF_ERR_INTERRUPTED)) {
            char msg[1024];
            snprintf(msg, sizeof msg, "%s", gf_last_error());
            gf_status se = gf_dem_write_exits(dir);
            if (se != GF_OK && st == GF_OK) return se;
            if (st != GF_OK) gf_error_set(st, "%s", msg); // keep the stop's message
        }
        if (st != GF_OK) return st;
    }
    char mark[GF_PATH_MAX + 32];
    snprintf(mark, sizeof mark, "%s/%s", dir, GF_DEM_INTERRUPTED);
    unlink(mark); // a complete run: an earlier interruption no longer holds
    return GF_OK;
}

/// A continuation's progress: passed on, and each snapshot LAMMPS has
/// finished gets its ITEM: TIME put right then (gf_dem_cont_fix_step), not
/// only at the end: a granflow killed meanwhile leaves few wrong ones.
typedef struct gf_dem_cont_watch {
    const gf_dem_run_opts *o;
    const char *dir;
    double dt;
    int64_t every, next; ///< steps between snapshots; the next one to put right
} gf_dem_cont_watch;

static void gf_dem_cont_on_progress(void *ctx, const gf_dem_progress *p)
{
    gf_dem_cont_watch *w = ctx;
    if (w->o->progress) w->o->progress(w->o->ctx, p);
    if (p->phase != GF_DEM_PHASE_DRAIN || !(p->time >= 0)) return; // thermo times: the drain's (step * dt)
    const int64_t now = (int64_t)floor(p->time / w->dt + 0.5);
    for (; w->next <= now; w->next += w->every) (void)gf_dem_cont_fix_step(w->dir, w->next, w->dt); // the end's pass reports
}

/// The error of a directory without restart files.
static gf_status gf_dem_cont_none(const char *dir)
{
    return gf_error_set(GF_ERR_PARAM,
                        "%s: no restart file to continue from (drain.a.restart, drain.b.restart): the drain "
                        "wrote none yet (it writes one every dem.restart_interval), or its in.drain has no "
                        "restart line; drain again from settled.restart (--drain-only)",
                        dir);
}

/// Which of DIR/drain.a.restart and drain.b.restart LAMMPS reads, and at
/// which step: each present one is read by a one-rank LAMMPS (in.probe) that
/// prints its step and timestep; the readable one of the higher step wins.
/// A present one LAMMPS cannot read (a restart cut short when LAMMPS was
/// killed while writing it) is named in c->unreadable with LAMMPS' error.
static gf_status gf_dem_cont_probe(const char *dir, const char *lmp, const gf_dem_run_opts *o, gf_dem_cont *c,
                                   int64_t *step, double *dt)
{
    char path[GF_PATH_MAX + 32], tmp[GF_PATH_MAX + 48], why[2][600] = {"", ""};
    int found = 0, best = -1;
    int64_t steps[2] = {-1, -1};
    double dts[2] = {0, 0};
    for (int k = 0; k < 2; k++) {
        snprintf(path, sizeof path, "%s/drain.%c.restart", dir, "ab"[k]);
        if (access(path, F_OK) != 0) continue;
        found++;
        FILE *f;
        snprintf(path, sizeof path, "%s/in.probe", dir);
        gf_status st = gf_atomic_open(path, tmp, sizeof tmp, &f);
        if (st != GF_OK) return st;
        fprintf(f, "# granflow dem --continue: the step of drain.%c.restart\nread_restart drain.%c.restart\n"
                   "print \"granflow-restart $(step) $(dt:%%.17g)\"\n", "ab"[k], "ab"[k]);
        if ((st = gf_atomic_commit(f, tmp, path)) != GF_OK) return st;
        gf_dem_run_opts po = {.ranks = 1, .stop = o->stop};
        gf_dem_reader r = {.o = &po, .wall0 = gf_clock_now(), .t_phase = NAN, .restart_step = -1};
        st = gf_dem_run_one(dir, "in.probe", lmp, NULL, 1, &r);
        unlink(path);
        snprintf(path, sizeof path, "%s/log.probe", dir);
        unlink(path);
        if (st == GF_ERR_INTERRUPTED) return st;
        if (st == GF_OK && r.restart_step >= 0) {
            steps[k] = r.restart_step;
            dts[k] = r.restart_dt;
            if (best < 0 || steps[k] > steps[best]) best = k;
        } else {
            snprintf(why[k], sizeof why[k], "%s/drain.%c.restart: LAMMPS cannot read it (%s)", dir, "ab"[k],
                     r.error[0] ? r.error : "no step printed");
        }
    }
    if (!found) return gf_dem_cont_none(dir);
    if (best < 0)
        return gf_error_set(GF_ERR_FORMAT, "%s%s%s", why[0], why[0][0] && why[1][0] ? "; " : "", why[1]);
    snprintf(c->unreadable, sizeof c->unreadable, "%s", why[1 - best]);
    *step = steps[best];
    *dt = dts[best];
    snprintf(c->restart, sizeof c->restart, "drain.%c.restart", "ab"[best]);
    return GF_OK;
}

gf_status gf_dem_continue(const char *dir, const gf_config *cfg, const gf_dem_run_opts *o, gf_dem_cont *out)
{
    gf_dem_run_opts def = gf_dem_run_opts_default();
    if (!o) o = &def;
    gf_dem_cont c = {0};
    if (out) *out = c;
    gf_dem_defs dd;
    gf_config_dem_defs(cfg, &dd);
    char lmp[4096], mpirun[4096], path[GF_PATH_MAX + 32];
    int ranks;
    gf_status st = gf_dem_find(o, lmp, mpirun, sizeof lmp, &ranks);
    if (st != GF_OK) return st;
    snprintf(path, sizeof path, "%s/in.drain", dir);
    if (access(path, R_OK) != 0)
        return gf_error_set(GF_ERR_IO, "%s: %s (no drain to continue there)", path, strerror(errno));
    double until = 0.0;
    const bool done = gf_dem_cont_done(dir, &until);
    bool any = false;
    for (int k = 0; k < 2; k++) {
        snprintf(path, sizeof path, "%s/drain.%c.restart", dir, "ab"[k]);
        any = any || access(path, F_OK) == 0;
    }
    if (!any) return gf_dem_cont_none(dir);
    if (!done && !o->force && (st = gf_dem_cont_check_idle(dir)) != GF_OK) return st;
    // The marker has 6 digits (%.6g): a drain to 12.3456789 tau printed 12.3457.
    if (done && dd.duration <= until * (1.0 + 1e-5))
        return gf_error_set(GF_ERR_PARAM,
                            "%s: the drain ran to its end (t = %g tau, run.duration = %g): nothing to continue "
                            "(a longer drain: --set run.duration=T)",
                            dir, until, dd.duration);
    int64_t step = -1;
    double dt = 0.0;
    if ((st = gf_dem_cont_probe(dir, lmp, o, &c, &step, &dt)) != GF_OK) return st;
    if (fabs(dt - dd.timestep) > 1e-12 * dd.timestep)
        return gf_error_set(GF_ERR_PARAM,
                            "%s/%s has a timestep of %.10g tau, %s/config.ini dem.timestep = %.10g: the configuration "
                            "is not the one this drain ran with",
                            dir, c.restart, dt, dir, dd.timestep);
    gf_dem_cont probe = c; // prepare fills c afresh
    if ((st = gf_dem_cont_prepare(dir, cfg, probe.restart, step, &c)) != GF_OK) {
        if (out) *out = (gf_dem_cont){0};
        return st;
    }
    snprintf(c.unreadable, sizeof c.unreadable, "%s", probe.unreadable);
    if (out) *out = c;
    snprintf(path, sizeof path, "%s/config.ini", dir); // a longer run.duration is the drain's from now on
    if ((st = gf_config_save(cfg, path)) != GF_OK) return st;

    const time_t since = time(NULL);
    const int64_t every = (int64_t)fmax(1.0, floor(dd.snapshot_interval / dd.timestep + 0.5));
    gf_dem_cont_watch w = {.o = o, .dir = dir, .dt = dd.timestep, .every = every,
                           .next = (step + every - 1) / every * every};
    gf_dem_run_opts wo = *o;
    wo.progress = gf_dem_cont_on_progress;
    wo.ctx = &w;
    gf_dem_reader r = {.o = &wo, .wall0 = gf_clock_now(), .t_phase = NAN, .restart_step = -1};
    st = gf_dem_run_one(dir, "in.continue", lmp, mpirun[0] ? mpirun : NULL, ranks, &r);
    char msg[1024];
    snprintf(msg, sizeof msg, "%s", gf_last_error());
    if (st == GF_ERR_INTERRUPTED) {
        gf_dem_mark_interrupted(dir, false, &r, since);
        snprintf(msg, sizeof msg, "%s", gf_last_error());
    }
    gf_status sf = gf_dem_cont_fix_times(dir, dd.timestep, NULL); // whatever LAMMPS did, the times it wrote
    if (sf == GF_OK && (st == GF_OK || st == GF_ERR_INTERRUPTED)) sf = gf_dem_write_exits(dir);
    if (st != GF_OK) return gf_error_set(st, "%s", msg);
    if (sf != GF_OK) return sf;
    snprintf(path, sizeof path, "%s/%s", dir, GF_DEM_INTERRUPTED);
    unlink(path);
    return GF_OK;
}

gf_dem_run_opts gf_dem_run_opts_default(void) { return (gf_dem_run_opts){.ranks = 1}; }
