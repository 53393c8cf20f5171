// SPDX-License-Identifier: MIT
// Internal: the monotonic wall clock, in seconds (timing and progress only;
// results never depend on it).
#ifndef GF_CORE_CLOCK_H
#define GF_CORE_CLOCK_H

#include <time.h>

static inline double gf_clock_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/// CPU time of the calling thread, in seconds: work measured this way does
/// not count the time the thread was preempted (a shared machine).
static inline double gf_clock_thread_cpu(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

#endif
