// SPDX-License-Identifier: MIT
// The guard between granflow and LAMMPS (dem/lammps_guard.h). LAMMPS runs in
// a process group of its own, which a stop of granflow ends (lammps_run.c);
// but a granflow killed with SIGKILL runs no code, and its LAMMPS (with the
// ranks of mpirun, or whatever else it started) went on alone. The kernel
// tells a process of its parent's death (PR_SET_PDEATHSIG), but only the
// direct child, and LAMMPS would take the signal for itself alone: so the
// direct child is this guard, which stays in the group and ends all of it.
// Only async-signal-safe calls after the fork.
#define _GNU_SOURCE
#include "dem/lammps_guard.h"

#include <errno.h>
#include <signal.h>
#include <stddef.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

enum {
    GF_GUARD_GRACE = 100, // tenths of a second between SIGTERM and SIGKILL to the group
};

static volatile sig_atomic_t gf_guard_stop;

static void gf_guard_on_signal(int sig) { gf_guard_stop = sig; }

static void gf_guard_catch(int sig, void (*handler)(int))
{
    struct sigaction sa = {0};
    sa.sa_handler = handler;
    sigemptyset(&sa.sa_mask);
    sigaction(sig, &sa, NULL); // no SA_RESTART: waitpid returns on the signal
}

_Noreturn void gf_dem_guard_run(pid_t parent, char *const *argv)
{
    static const int sigs[] = {SIGTERM, SIGINT, SIGHUP};
    for (int k = 0; k < 3; k++) gf_guard_catch(sigs[k], gf_guard_on_signal);
    // Unblock them, whatever granflow's thread had blocked.
    sigset_t set;
    sigemptyset(&set);
    for (int k = 0; k < 3; k++) sigaddset(&set, sigs[k]);
    sigprocmask(SIG_UNBLOCK, &set, NULL);
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(1); // granflow died before the line above: start nothing

    pid_t lmp = fork();
    if (lmp < 0) _exit(127);
    if (lmp == 0) {
        for (int k = 0; k < 3; k++) gf_guard_catch(sigs[k], SIG_DFL);
        execv(argv[0], argv);
        _exit(127);
    }
    // Polled every 0.1 s rather than a blocking wait, which a signal arriving
    // just before it would not interrupt.
    int status = 0, waited = 0;
    for (;;) {
        pid_t w = waitpid(lmp, &status, WNOHANG);
        if (w == lmp) break;
        if (w < 0 && errno != EINTR) _exit(1);
        if (gf_guard_stop) {
            if (waited == 0) kill(0, SIGTERM); // the whole group, this guard too (caught)
            if (waited == GF_GUARD_GRACE) kill(0, SIGKILL);
            waited++;
        }
        struct timespec nap = {0, 100 * 1000 * 1000};
        nanosleep(&nap, NULL);
    }
    if (gf_guard_stop && waited == 0) kill(0, SIGTERM); // LAMMPS went first: the rest of its group
    if (WIFEXITED(status)) _exit(WEXITSTATUS(status));
    // The same signal, so the parent reads how LAMMPS ended (without a core of this guard).
    int sig = WIFSIGNALED(status) ? WTERMSIG(status) : SIGKILL;
    struct rlimit none = {0, 0};
    setrlimit(RLIMIT_CORE, &none);
    gf_guard_catch(sig, SIG_DFL);
    sigemptyset(&set);
    sigaddset(&set, sig);
    sigprocmask(SIG_UNBLOCK, &set, NULL);
    kill(getpid(), sig);
    _exit(128 + sig);
}
