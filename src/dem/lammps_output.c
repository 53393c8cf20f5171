// SPDX-License-Identifier: MIT
// LAMMPS' output while it runs the inputs of gf_dem_write_inputs, one line at
// a time: the phase markers (`granflow-phase NAME A B`, printed by the inputs),
// the thermo lines (step time particles ke) and the ERROR lines.
#include "dem/lammps_output.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "core/clock.h"

const char *gf_dem_phase_name(gf_dem_phase phase)
{
    static const char *const names[] = {"none", "fill", "settle", "drain", "done"};
    return (unsigned)phase < sizeof names / sizeof names[0] ? names[phase] : "?";
}

// A count LAMMPS printed as a number, as an int64_t: NaN and negatives are 0,
// and beyond 2^62 it is clamped (converting an out-of-range double is undefined).
static int64_t gf_dem_count(double v)
{
    if (!(v > 0)) return 0;
    return v < 0x1p62 ? (int64_t)v : INT64_C(1) << 62;
}

void gf_dem_line(gf_dem_reader *r, char *line)
{
    size_t len = strlen(line);
    while (len && (line[len - 1] == '\n' || line[len - 1] == '\r')) line[--len] = '\0';
    if (!strncmp(line, "ERROR", 5)) {
        snprintf(r->error, sizeof r->error, "%s", line);
        return;
    }
    char name[32];
    double a, b;
    long long step;
    if (sscanf(line, "granflow-restart %lld %lf", &step, &a) == 2) { // the probe of a restart file (--continue)
        r->restart_step = step;
        r->restart_dt = a;
        return;
    }
    if (sscanf(line, "granflow-phase %31s %lf %lf", name, &a, &b) == 3) {
        // "settled" marks the end of the settle phase (its line says how many settled).
        static const struct {
            const char *name;
            gf_dem_phase phase;
        } marks[] = {{"fill", GF_DEM_PHASE_FILL},
                     {"settle", GF_DEM_PHASE_SETTLE},
                     {"settled", GF_DEM_PHASE_SETTLE},
                     {"drain", GF_DEM_PHASE_DRAIN},
                     {"continue", GF_DEM_PHASE_DRAIN},
                     {"done", GF_DEM_PHASE_DONE}};
        for (size_t k = 0; k < sizeof marks / sizeof marks[0]; k++)
            if (!strcmp(name, marks[k].name)) r->p.phase = marks[k].phase;
        const bool cont = !strcmp(name, "continue");
        if (!strcmp(name, "fill") || !strcmp(name, "drain") || cont) r->p.target = gf_dem_count(a);
        if (strcmp(name, "settled") && strcmp(name, "done")) r->p.until = b;
        // A continued drain (in.continue) prints the drain's own time (step * dt) from its restart on.
        r->t_phase = cont ? 0.0 : NAN;
        if (!strcmp(name, "done")) r->p.time = r->p.until;
    } else {
        double t, n, ke;
        char extra;
        if (sscanf(line, " %lld %lf %lf %lf %c", &step, &t, &n, &ke, &extra) != 4 || r->p.phase == GF_DEM_PHASE_NONE) return;
        if (isnan(r->t_phase)) r->t_phase = t; // first thermo line of the phase
        r->p.time = t - r->t_phase;
        r->p.particles = gf_dem_count(n);
        r->p.ke = ke;
    }
    r->p.wall_seconds = gf_clock_now() - r->wall0;
    if (r->o->progress && r->p.phase != GF_DEM_PHASE_NONE) r->o->progress(r->o->ctx, &r->p);
}
