// SPDX-License-Identifier: MIT
// Internal: reading LAMMPS' output line by line for gf_dem_run (lammps_run.c);
// tests/fuzz/fuzz_lammps_output.c fuzzes it.
#ifndef GF_DEM_LAMMPS_OUTPUT_H
#define GF_DEM_LAMMPS_OUTPUT_H

#include "granflow/dem.h"

/// What the output said so far.
typedef struct gf_dem_reader {
    gf_dem_progress p;
    double t_phase;        ///< LAMMPS time when the phase began (NaN: not yet seen)
    char error[512];       ///< LAMMPS' last ERROR line
    long long restart_step; ///< `granflow-restart STEP DT` (a restart file's probe): its step (-1: not seen)
    double restart_dt;      ///< and its timestep, tau
    const gf_dem_run_opts *o;
    double wall0;
} gf_dem_reader;

/// Reads one line of LAMMPS' output (its newline, if any, is cut in place):
/// an ERROR line is kept in r->error; `granflow-restart STEP DT` in
/// r->restart_step and r->restart_dt; a phase marker (`continue`: the drain
/// went on from a restart, its thermo times the drain's own) or, once a phase is
/// known, a thermo line updates r->p and is reported to r->o->progress.
void gf_dem_line(gf_dem_reader *r, char *line);

#endif
