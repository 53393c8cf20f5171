// SPDX-License-Identifier: MIT
// gf_run_write_snapshot: one snapshot frame of a run directory as a LAMMPS
// text dump (formats layer; granflow/particles.h). A pure writer: the run
// driver (src/run/) decides when and where.
#include "granflow/particles.h"

#include <stdbool.h>
#include <stdio.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "granflow/defs.h"
#include "io/dump_write.h"

gf_status gf_run_write_snapshot(const char *path, const gf_config *cfg, const gf_packing *p, const int32_t *pass,
                                double time, uint64_t step)
{
    gf_container_defs d;
    gf_config_container_defs(cfg, &d);
    char tmp[GF_PATH_MAX + 8];
    FILE *f;
    gf_status st = gf_atomic_open(path, tmp, sizeof tmp, &f);
    if (st != GF_OK) return st;
    double ztop = 1.0;
    for (size_t i = 0; i < p->n; i++)
        if (p->z[i] + p->r[i] > ztop) ztop = p->z[i] + p->r[i];
    double zlo = d.exit_plane < 0.0 ? d.exit_plane : 0.0;
    bool poly = false; // a radius column only when the radii differ from the papers' 0.5
    for (size_t i = 0; i < p->n && !poly; i++) poly = p->r[i] != 0.5;
    gf_dump_frame fr = {.p = p,
                        .numbers = GF_DUMP_SNAPSHOT,
                        .has_time = true,
                        .time = time,
                        .step = step,
                        .lo = {-0.5 * d.width, -0.5 * d.depth, zlo},
                        .hi = {0.5 * d.width, 0.5 * d.depth, ztop},
                        .radius = poly,
                        .pass = pass};
    gf_dump_write_frame(f, &fr);
    return gf_atomic_commit(f, tmp, path);
}
