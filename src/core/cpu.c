// SPDX-License-Identifier: MIT
// The machine's cores, for thread and rank counts.
#include <unistd.h>

#include "granflow/core.h"

int gf_cpu_count(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : (int)n;
}
