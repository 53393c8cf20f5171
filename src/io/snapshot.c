// SPDX-License-Identifier: MIT
// gf_run_write_snapshot: one snapshot frame of a run directory as a LAMMPS
// text dump (formats layer; granflow/particles.h). A pure writer: the run
// driver (src/run/) decides when and where.
#include "granflow/particles.h"

#include <inttypes.h>
#include <stdbool.h>
#include <stdio.h>

#include "core/atomic_file.h"
#include "core/error.h"

gf_status gf_run_write_snapshot(const char *path, const gf_config *cfg, const gf_packing *p, const int32_t *pass,
                                double time, uint64_t step)
{
    char tmp[GF_PATH_MAX + 8];
    FILE *f;
    gf_status st = gf_atomic_open(path, tmp, sizeof tmp, &f);
    if (st != GF_OK) return st;
    double ztop = 1.0;
    for (size_t i = 0; i < p->n; i++)
        if (p->z[i] + p->r[i] > ztop) ztop = p->z[i] + p->r[i];
    double zlo = gf_config_exit_plane(cfg) < 0.0 ? gf_config_exit_plane(cfg) : 0.0;
    fprintf(f, "ITEM: TIME\n%.17g\nITEM: TIMESTEP\n%" PRIu64 "\nITEM: NUMBER OF ATOMS\n%zu\n", time, step, p->n);
    fprintf(f, "ITEM: BOX BOUNDS ff ff ff\n%.17g %.17g\n%.17g %.17g\n%.17g %.17g\n", -0.5 * cfg->container_width,
            0.5 * cfg->container_width, -0.5 * cfg->container_depth, 0.5 * cfg->container_depth, zlo, ztop);
    bool poly = false; // a radius column only when the radii differ from the papers' 0.5
    for (size_t i = 0; i < p->n && !poly; i++) poly = p->r[i] != 0.5;
    fprintf(f, "ITEM: ATOMS id type x y z%s%s\n", poly ? " radius" : "", pass ? " pass" : "");
    for (size_t i = 0; i < p->n; i++) {
        fprintf(f, "%" PRId64 " %d %.7f %.7f %.7f", p->id[i], p->layer[i], p->x[i], p->y[i], p->z[i]);
        if (poly) fprintf(f, " %.7g", p->r[i]);
        if (pass) fprintf(f, " %d", (int)pass[i]);
        fputc('\n', f);
    }
    return gf_atomic_commit(f, tmp, path);
}
