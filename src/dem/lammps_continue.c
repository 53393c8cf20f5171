// SPDX-License-Identifier: MIT
// What `granflow dem --continue` does to a run directory around LAMMPS
// (lammps_run.c runs it): whether its drain already ended, the tail the
// interrupted drain wrote after its restart file (dropped: a continued drain
// is not bit-identical to the one it replaces, so the record keeps one
// trajectory), and in.continue, written from the directory's own in.drain
// (whatever it holds, a restart line added by hand included) so that the
// drain goes on with exactly the commands it began with:
//   read_restart drain.X.restart, no reset_timestep (the restart holds the
//   step); the same fix IDs (fix wall/gran keeps its contact history in the
//   restart file under its ID; the pair style's history is in it too);
//   `run TOTAL upto`; recirculating, the loop's count from the restart's
//   step and its reinsertions first (the restart is written at the end of a
//   chunk, before them).
// LAMMPS 29 Sep 2021 starts `time` again from 0 at the first run after
// read_restart (Integrate::init sets atimestep without atime, which the
// restart does not hold): in.continue's thermo and reinserted.txt use
// step * dt, and the snapshots' ITEM: TIME is put right afterwards
// (gf_dem_cont_fix_times).
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "core/alloc.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/fs.h"
#include "dem/dem_internal.h"
#include "granflow/defs.h"
#include "granflow/particles.h"

#define GF_CONT_LINE 4096

/// Step of a snapshot's file name (snap_NNNNNNNNN.dump, .dump.gz); -1 for other names.
static long long gf_cont_snap_step(const char *name)
{
    long long step;
    int end = 0;
    if (sscanf(name, "snap_%lld.dump%n", &step, &end) != 1 || end == 0) return -1;
    return (!name[end] || !strcmp(name + end, ".gz")) ? step : -1;
}

bool gf_dem_cont_done(const char *dir, double *until)
{
    char path[GF_PATH_MAX + 32], best[GF_PATH_MAX + 32] = "";
    struct stat sb;
    double newest = -1.0;
    const char *names[2] = {"log.drain", "log.continue"};
    for (int k = 0; k < 2; k++) {
        snprintf(path, sizeof path, "%s/%s", dir, names[k]);
        if (stat(path, &sb) != 0) continue;
        double t = (double)sb.st_mtim.tv_sec + 1e-9 * (double)sb.st_mtim.tv_nsec;
        if (t >= newest) {
            newest = t;
            snprintf(best, sizeof best, "%s", path);
        }
    }
    *until = 0.0;
    FILE *f = best[0] ? fopen(best, "r") : NULL;
    if (!f) return false;
    char line[GF_CONT_LINE], name[32];
    double a, d = NAN;
    bool done = false;
    while (fgets(line, sizeof line, f)) {
        if (sscanf(line, "granflow-phase %31s %lf %lf", name, &a, &d) != 3) continue;
        if (!strcmp(name, "drain") || !strcmp(name, "continue")) {
            *until = d;
            done = false;
        } else if (!strcmp(name, "done")) {
            done = true;
        }
    }
    fclose(f);
    return done;
}

gf_status gf_dem_cont_check_idle(const char *dir)
{
    static const char *const names[] = {"log.drain", "log.continue", "drain.a.restart", "drain.b.restart", "snapshots"};
    char path[GF_PATH_MAX + 32], newest[GF_PATH_MAX + 32] = "";
    struct stat sb;
    time_t last = 0;
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++) {
        snprintf(path, sizeof path, "%s/%s", dir, names[k]); // snapshots/: its time changes as a file is added
        if (stat(path, &sb) == 0 && sb.st_mtime > last) {
            last = sb.st_mtime;
            snprintf(newest, sizeof newest, "%s", path);
        }
    }
    snprintf(path, sizeof path, "%s/%s", dir, GF_DEM_INTERRUPTED);
    if (stat(path, &sb) == 0 && sb.st_mtime >= last) return GF_OK; // granflow stopped that LAMMPS and saw it go
    const time_t now = time(NULL);
    if (!newest[0] || now - last >= GF_DEM_BUSY_SECONDS) return GF_OK;
    return gf_error_set(GF_ERR_EXISTS,
                        "%s was written %lld s ago: the drain's LAMMPS may still be running there, and going on "
                        "would remove and write over what it writes; stop it (or wait until %d s after it stopped)",
                        newest, (long long)(now - last), GF_DEM_BUSY_SECONDS);
}

/// Rewrites a snapshot's ITEM: TIME line as step * dt when it is not that.
static gf_status gf_cont_fix_one(const char *path, double dt, bool *fixed)
{
    *fixed = false;
    FILE *f = fopen(path, "r");
    if (!f) return gf_error_set(GF_ERR_IO, "%s: %s", path, strerror(errno));
    char l1[128], l2[128], l3[128], l4[128];
    double t = 0.0;
    long long step = 0;
    bool ok = fgets(l1, sizeof l1, f) && fgets(l2, sizeof l2, f) && fgets(l3, sizeof l3, f) &&
              fgets(l4, sizeof l4, f) && !strncmp(l1, "ITEM: TIME", 10) && sscanf(l2, "%lf", &t) == 1 &&
              !strncmp(l3, "ITEM: TIMESTEP", 14) && sscanf(l4, "%lld", &step) == 1;
    const double want = ok ? (double)step * dt : 0.0;
    if (!ok || fabs(t - want) <= 1e-9 * fmax(1.0, want)) { // not ours to judge, or right already
        fclose(f);
        return GF_OK;
    }
    char tmp[GF_PATH_MAX + 48];
    FILE *o;
    gf_status st = gf_atomic_open(path, tmp, sizeof tmp, &o);
    if (st != GF_OK) {
        fclose(f);
        return st;
    }
    fprintf(o, "ITEM: TIME\n%.16g\n%s%s", want, l3, l4); // as LAMMPS writes it ({:.16})
    char buf[65536];
    for (size_t n; (n = fread(buf, 1, sizeof buf, f)) > 0;) fwrite(buf, 1, n, o);
    bool err = ferror(f);
    fclose(f);
    if (err) {
        gf_atomic_abort(o, tmp);
        return gf_error_set(GF_ERR_IO, "%s: read error", path);
    }
    *fixed = true;
    return gf_atomic_commit(o, tmp, path);
}

gf_status gf_dem_cont_fix_step(const char *dir, int64_t step, double dt)
{
    char path[GF_PATH_MAX + 64];
    snprintf(path, sizeof path, "%s/snapshots/snap_%09lld.dump", dir, (long long)step); // dump_modify pad 9
    if (access(path, F_OK) != 0) return GF_OK;
    bool did;
    return gf_cont_fix_one(path, dt, &did);
}

gf_status gf_dem_cont_fix_times(const char *dir, double dt, size_t *fixed)
{
    char snaps[GF_PATH_MAX + 32], path[GF_PATH_MAX + 320];
    snprintf(snaps, sizeof snaps, "%s/snapshots", dir);
    if (fixed) *fixed = 0;
    DIR *d = opendir(snaps);
    if (!d) return GF_OK;
    gf_status st = GF_OK;
    for (struct dirent *e; st == GF_OK && (e = readdir(d)) != NULL;) {
        const char *n = e->d_name;
        size_t len = strlen(n);
        if (gf_cont_snap_step(n) < 0 || len < 5 || strcmp(n + len - 5, ".dump")) continue; // gzipped: not LAMMPS'
        snprintf(path, sizeof path, "%s/%s", snaps, n);
        bool did = false;
        st = gf_cont_fix_one(path, dt, &did);
        if (did && fixed) (*fixed)++;
    }
    closedir(d);
    return st;
}

/// Removes the snapshots after step `step`; counts them and the newest time.
static gf_status gf_cont_prune_snaps(const char *dir, int64_t step, double dt, gf_dem_cont *c)
{
    char snaps[GF_PATH_MAX + 32], path[GF_PATH_MAX + 320];
    snprintf(snaps, sizeof snaps, "%s/snapshots", dir);
    DIR *d = opendir(snaps);
    if (!d) return gf_error_set(GF_ERR_IO, "%s: %s", snaps, strerror(errno));
    gf_status st = GF_OK;
    for (struct dirent *e; (e = readdir(d)) != NULL;) {
        long long s = gf_cont_snap_step(e->d_name);
        if (s < 0) continue;
        if (s <= step) {
            c->kept_snaps++;
            continue;
        }
        snprintf(path, sizeof path, "%s/%s", snaps, e->d_name);
        if (unlink(path) != 0) {
            st = gf_error_set(GF_ERR_IO, "%s: cannot remove it: %s", path, strerror(errno));
            break;
        }
        c->dropped_snaps++;
        c->dropped_until = fmax(c->dropped_until, (double)s * dt);
    }
    closedir(d);
    return st;
}

/// Keeps the reinsertions of reinserted.txt before time t0 (those at or after
/// it the continued drain makes again) and its comment lines.
static gf_status gf_cont_prune_reins(const char *dir, double t0, gf_dem_cont *c)
{
    char path[GF_PATH_MAX + 64], tmp[GF_PATH_MAX + 80], line[GF_CONT_LINE];
    snprintf(path, sizeof path, "%s/%s", dir, GF_DEM_REINSERTED);
    FILE *f = fopen(path, "r");
    if (!f) return gf_error_set(GF_ERR_IO, "%s: %s (a recirculating drain writes it from its start)", path, strerror(errno));
    FILE *o;
    gf_status st = gf_atomic_open(path, tmp, sizeof tmp, &o);
    if (st != GF_OK) {
        fclose(f);
        return st;
    }
    while (fgets(line, sizeof line, f)) {
        long long id;
        double t;
        bool whole = strchr(line, '\n') != NULL; // a last line cut short (LAMMPS stopped while writing it) goes
        if (line[0] == '#' && whole) {
            fputs(line, o);
            continue;
        }
        if (whole && sscanf(line, "%lld %lf", &id, &t) == 2 && t < t0) {
            fputs(line, o);
            c->kept_reins++;
        } else if (line[0] != '\n') {
            c->dropped_reins++;
        }
    }
    fclose(f);
    return gf_atomic_commit(o, tmp, path);
}

/// The highest flowing centre of the settled packing (packing.dump): where
/// the recirculating drain's reinsertion slab began (bound(flow,zmax) then).
static gf_status gf_cont_settled_top(const char *dir, double *top)
{
    char path[GF_PATH_MAX + 32];
    snprintf(path, sizeof path, "%s/packing.dump", dir);
    gf_packing pk = {0};
    gf_status st = gf_packing_read(path, GF_FORMAT_LAMMPS, &pk);
    if (st != GF_OK) return st;
    *top = -INFINITY;
    for (size_t i = 0; i < pk.n; i++) *top = fmax(*top, pk.z[i]);
    gf_packing_free(&pk);
    if (!isfinite(*top)) return gf_error_set(GF_ERR_FORMAT, "%s: no particle", path);
    return GF_OK;
}

/// in.drain as lines: the file in one block (*data, *cap: gf_free), split in
/// place at its newlines, and an array of their starts (*lines, *lcap).
typedef struct gf_cont_text {
    unsigned char *data;
    size_t len, cap;
    char **l;
    size_t n, lcap;
} gf_cont_text;

static void gf_cont_free(gf_cont_text *t)
{
    if (t->data) gf_free(t->data, t->cap);
    if (t->l) GF_DELETE(t->l, t->lcap);
    *t = (gf_cont_text){0};
}

static gf_status gf_cont_read(const char *path, gf_cont_text *t)
{
    *t = (gf_cont_text){0};
    gf_status st = gf_fs_read_all(path, 1 << 24, &t->data, &t->len, &t->cap); // an in.drain is a few kB
    if (st != GF_OK) return st;
    size_t lines = 1;
    for (size_t k = 0; k < t->len; k++) lines += t->data[k] == '\n';
    if (!(t->l = GF_NEW(char *, lines))) {
        gf_cont_free(t);
        return gf_error_set(GF_ERR_NOMEM, "%s: out of memory", path);
    }
    t->lcap = lines;
    char *p = (char *)t->data, *end = p + t->len;
    while (p < end) {
        char *nl = memchr(p, '\n', (size_t)(end - p));
        if (nl) *nl = '\0';
        p[strcspn(p, "\r")] = '\0';
        t->l[t->n++] = p;
        p = nl ? nl + 1 : end;
    }
    return GF_OK;
}

/// The index of the first line starting with `head` from `from` (n: none).
static size_t gf_cont_find(char **l, size_t n, size_t from, const char *head)
{
    for (size_t k = from; k < n; k++)
        if (!strncmp(l[k], head, strlen(head))) return k;
    return n;
}

gf_status gf_dem_cont_prepare(const char *dir, const gf_config *cfg, const char *restart, int64_t step64,
                              gf_dem_cont *c)
{
    const long long step = (long long)step64;
    gf_dem_defs dd;
    gf_config_dem_defs(cfg, &dd);
    gf_engine_defs ed;
    gf_config_engine_defs(cfg, &ed);
    const double dt = dd.timestep;
    const long long total = (long long)fmax(1.0, floor(dd.duration / dt + 0.5));
    char path[GF_PATH_MAX + 32], cpath[GF_PATH_MAX + 32], tmp[GF_PATH_MAX + 48];
    snprintf(path, sizeof path, "%s/in.drain", dir);
    snprintf(cpath, sizeof cpath, "%s/config.ini", dir);
    gf_cont_text text;
    gf_status st = gf_cont_read(path, &text);
    if (st != GF_OK) return st;
    char **l = text.l;
    const size_t n = text.n;
    // What the continuation needs of in.drain, and what must agree with the configuration.
    const size_t i_read = gf_cont_find(l, n, 0, "read_restart settled.restart"),
                 i_reset = gf_cont_find(l, n, 0, "reset_timestep 0"),
                 i_thermo = gf_cont_find(l, n, 0, "thermo_style custom step time "),
                 i_ts = gf_cont_find(l, n, 0, "timestep "), i_dump = gf_cont_find(l, n, 0, "dump snap flow custom "),
                 i_mark = gf_cont_find(l, n, 0, "print \"granflow-phase drain "),
                 i_restart = gf_cont_find(l, n, 0, "restart "), i_loop = gf_cont_find(l, n, 0, "variable rc_k loop ");
    const bool recirc = i_loop < n;
    const char *missing = i_read == n ? "read_restart settled.restart" : i_reset == n ? "reset_timestep 0"
                        : i_thermo == n ? "thermo_style custom step time ..." : i_ts == n ? "timestep DT"
                        : i_dump == n ? "dump snap flow custom N ..." : i_mark == n ? "print \"granflow-phase drain ...\""
                        : NULL;
    double ts = NAN;
    long long snap_every = 0;
    if (!missing && (sscanf(l[i_ts], "timestep %lf", &ts) != 1 || sscanf(l[i_dump], "dump snap flow custom %lld", &snap_every) != 1))
        missing = "timestep DT and dump snap flow custom N";
    if (missing) {
        st = gf_error_set(GF_ERR_FORMAT, "%s: no line '%s': not the drain granflow dem writes, cannot continue it", path,
                          missing);
        goto done;
    }
    const long long want_snap = (long long)fmax(1.0, floor(dd.snapshot_interval / dt + 0.5));
    if (fabs(ts - dt) > 1e-12 * dt || snap_every != want_snap || recirc != ed.recirculate) {
        st = gf_error_set(GF_ERR_PARAM,
                          "%s:%zu and %s disagree (%s): the configuration is not the one this drain ran with; "
                          "continue it with its own %s",
                          path, fabs(ts - dt) > 1e-12 * dt ? i_ts + 1 : snap_every != want_snap ? i_dump + 1 : (recirc ? i_loop : i_mark) + 1,
                          cpath,
                          fabs(ts - dt) > 1e-12 * dt ? "dem.timestep" : snap_every != want_snap ? "output.snapshot_interval"
                                                                                                : "run.recirculate",
                          cpath);
        goto done;
    }
    if (step >= total) {
        st = gf_error_set(GF_ERR_PARAM,
                          "%s/%s is at t = %g tau, the end of the drain (run.duration = %g tau): nothing to continue",
                          dir, restart, (double)step * dt, dd.duration);
        goto done;
    }
    // Recirculating: the chunk between reinsertions, and where the slab began.
    long long chunk = 0;
    size_t i_run = n, i_rest = n, i_lo = n;
    double top = NAN;
    if (recirc) {
        i_run = gf_cont_find(l, n, i_loop, "run ");
        const size_t i_back = gf_cont_find(l, n, i_loop, "jump SELF rc_loop");
        i_lo = gf_cont_find(l, n, 0, "variable rc_lo equal $(bound(flow,zmax)");
        if (i_run == n || sscanf(l[i_run], "run %lld", &chunk) != 1 || chunk < 1 || i_back == n || i_lo == n) {
            st = gf_error_set(GF_ERR_FORMAT, "%s: its reinsertion loop is not the one granflow dem writes: cannot "
                                             "continue it", path);
            goto done;
        }
        if (i_back + 1 < n && !strncmp(l[i_back + 1], "run ", 4)) i_rest = i_back + 1;
        if ((st = gf_cont_settled_top(dir, &top)) != GF_OK) goto done;
    }

    // The tail after the restart goes: snapshots, and reinsertions at or after it.
    *c = (gf_dem_cont){.step = step, .total = total, .dt = dt};
    snprintf(c->restart, sizeof c->restart, "%s", restart);
    if ((st = gf_dem_cont_fix_times(dir, dt, NULL)) != GF_OK) goto done; // a continuation killed before it could
    if ((st = gf_cont_prune_snaps(dir, step, dt, c)) != GF_OK) goto done;
    if (recirc && (st = gf_cont_prune_reins(dir, ((double)step - 0.5) * dt, c)) != GF_OK) goto done;

    FILE *f;
    snprintf(path, sizeof path, "%s/in.continue", dir);
    if ((st = gf_atomic_open(path, tmp, sizeof tmp, &f)) != GF_OK) goto done;
    fprintf(f,
            "# granflow dem --continue: in.drain (the lines marked 'continued' changed), from %s at\n"
            "# step %lld (t = %.10g tau) to step %lld (t = %.10g tau). See docs/dem.md.\n",
            restart, step, (double)step * dt, total, (double)total * dt);
    const long long first = (step + chunk - 1) / (chunk ? chunk : 1) * chunk; // recirculating: the first chunk's end
    const long long full = chunk ? total / chunk * chunk : 0;
    for (size_t k = 0; k < n; k++) {
        if (k == i_read) {
            fprintf(f, "read_restart %s # continued: the drain's state at step %lld\n", restart, step);
        } else if (k == i_reset) {
            fprintf(f, "# continued: no reset_timestep (the restart holds the step)\n");
        } else if (k == i_thermo) {
            fprintf(f,
                    "# continued: LAMMPS starts 'time' again from 0 after read_restart; the drain's time is step * dt\n"
                    "variable gf_t equal step*dt\nthermo_style custom step v_gf_t %s\n",
                    l[k] + strlen("thermo_style custom step time "));
        } else if (k == i_mark) {
            if (i_restart == n && dd.restart_interval > 0) { // an in.drain without restart files: this one writes them
                gf_dem_plan plan = {.restart_steps = (int64_t)fmax(1.0, floor(dd.restart_interval / dt + 0.5))};
                if (chunk) plan.restart_steps = (plan.restart_steps + chunk - 1) / chunk * chunk;
                gf_dem_restart_line(f, &plan, dt);
            }
            fprintf(f, "print \"granflow-phase continue ${nflow} %.6g\"\n", dd.duration);
        } else if (recirc && strstr(l[k], "reinserted.txt") && !strncmp(l[k], "print \"# ", 9)) {
            fprintf(f, "# continued: reinserted.txt keeps its lines before t = %.10g tau\n", (double)step * dt);
        } else if (k == i_lo) {
            const char *rest = l[k] + strlen("variable rc_lo equal $(bound(flow,zmax)");
            fprintf(f, "# continued: the slab from the settled packing's top again (packing.dump); it rises\n"
                       "# as before while the 1 d below it is packed\n"
                       "variable rc_lo equal $(%.10g%s\n", top, rest);
        } else if (k == i_loop) {
            // Before any reinsertion moves a particle (create_atoms, set, delete_atoms): LAMMPS discards
            // restart state no fix has claimed by then, and the pair style's contact histories are claimed
            // at the first run's setup.
            fprintf(f, "run 0 post no # continued: takes the contact histories back from the restart\n");
            if (first > full) { // the restart is in the last, partial chunk: no reinsertion is left
                fprintf(f, "run %lld upto pre yes post no # continued\njump SELF rc_end\n", total);
            } else {
                fprintf(f, "variable rc_k loop %lld # continued: the chunks left, and the reinsertions at the first's end\n",
                        (full - first) / chunk + 1);
                if (first > step) fprintf(f, "run %lld upto pre yes post no\nvariable rc_pre string no\n", first);
                fprintf(f, "jump SELF rc_block\n");
            }
        } else if (k == i_rest) {
            continue; // written after the loop below
        } else if (recirc && k > i_loop && !strncmp(l[k], "jump SELF rc_loop", 17)) {
            fprintf(f, "%s\n", l[k]);
            if (total > full) fprintf(f, "run %lld pre ${rc_pre} post no\n", total - full);
            fprintf(f, "label rc_end\n");
        } else if (!recirc && k > i_mark && !strncmp(l[k], "run ", 4)) {
            fprintf(f, "run %lld upto # continued\n", total);
        } else if (recirc && strstr(l[k], "$(time:")) {
            // The reinsertion's time, as step * dt (LAMMPS' time restarted from 0).
            const char *p = l[k], *q;
            while ((q = strstr(p, "$(time:")) != NULL) {
                fwrite(p, 1, (size_t)(q - p), f);
                fputs("$(v_gf_t:", f);
                p = q + 7;
            }
            fprintf(f, "%s\n", p);
        } else {
            fprintf(f, "%s\n", l[k]);
        }
    }
    st = gf_atomic_commit(f, tmp, path);
done:
    gf_cont_free(&text);
    return st;
}
