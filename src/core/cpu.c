// SPDX-License-Identifier: MIT
// The machine's cores, for thread and rank counts; its memory, to refuse up
// front what could never fit.
#ifdef __linux__
#define _GNU_SOURCE // sched_getaffinity
#include <sched.h>
#endif
#include "core/cpu.h"

#include <sys/resource.h>
#include <unistd.h>

#include "granflow/core.h"

int gf_cpu_count(void)
{
#ifdef __linux__
    // The cores this process may run on (taskset, a container's cpuset), as
    // OpenMP's omp_get_num_procs counts them: more threads would share them.
    cpu_set_t set;
    if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0) return CPU_COUNT(&set);
#endif
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : (int)n;
}

double gf_cpu_memory(const char **what)
{
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    double best = pages > 0 && page > 0 ? (double)pages * (double)page : 1e300;
    const char *why = "the machine's memory";
    static const struct {
        int resource;
        const char *name;
    } limits[] = {{RLIMIT_AS, "ulimit -v"}, {RLIMIT_DATA, "ulimit -d"}};
    for (int k = 0; k < 2; k++) {
        struct rlimit rl;
        if (getrlimit(limits[k].resource, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY && (double)rl.rlim_cur < best) {
            best = (double)rl.rlim_cur;
            why = limits[k].name;
        }
    }
    if (what) *what = why;
    return best;
}
