// SPDX-License-Identifier: MIT
// Internal: what the machine gives this process, beyond gf_cpu_count (granflow/core.h).
#ifndef GF_CORE_CPU_H
#define GF_CORE_CPU_H

#include <stddef.h>

/// Bytes of memory this process can ever have: the least of the machine's
/// physical memory and the limits on its address space and data (ulimit -v,
/// ulimit -d). *what (may be NULL) gets which one it is, for a message:
/// "the machine's memory", "ulimit -v", "ulimit -d".
double gf_cpu_memory(const char **what);

#endif
