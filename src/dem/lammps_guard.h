// SPDX-License-Identifier: MIT
// Internal: the process between granflow and LAMMPS that ends LAMMPS and
// everything it started when granflow goes, however it goes (kill -9 too).
#ifndef GF_DEM_LAMMPS_GUARD_H
#define GF_DEM_LAMMPS_GUARD_H

#include <sys/types.h>

/// Called in the child of fork(), after setpgid(0, 0) and the redirections:
/// starts argv (LAMMPS, or mpirun) as its own child, in the same process
/// group, and waits for it. When granflow (pid `parent`) dies, or on SIGTERM,
/// SIGINT or SIGHUP, sends SIGTERM to the whole group, and SIGKILL 10 s later
/// if some of it is still there. Ends as LAMMPS ended: the same exit status,
/// or the same signal, so the parent reads LAMMPS' own status. Never returns.
_Noreturn void gf_dem_guard_run(pid_t parent, char *const *argv);

#endif
