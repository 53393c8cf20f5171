// SPDX-License-Identifier: MIT
// The one LAMMPS text-dump frame writer (see dump_write.h).
#include "io/dump_write.h"

#include <inttypes.h>
#include <stdlib.h>

void gf_dump_exact(char *buf, size_t size, double v)
{
    snprintf(buf, size, "%.15g", v);
    if (strtod(buf, NULL) != v) snprintf(buf, size, "%.17g", v);
}

static void gf_dump_box(FILE *f, const gf_dump_frame *fr)
{
    fputs("ITEM: BOX BOUNDS ff ff ff\n", f);
    for (int k = 0; k < 3; k++) {
        if (fr->numbers == GF_DUMP_SNAPSHOT) {
            fprintf(f, "%.17g %.17g\n", fr->lo[k], fr->hi[k]);
            continue;
        }
        char lo[32], hi[32];
        gf_dump_exact(lo, sizeof lo, fr->lo[k]);
        gf_dump_exact(hi, sizeof hi, fr->hi[k]);
        fprintf(f, "%s %s\n", lo, hi);
    }
}

static void gf_dump_atom(FILE *f, const gf_dump_frame *fr, size_t i)
{
    const gf_packing *p = fr->p;
    if (fr->numbers == GF_DUMP_SNAPSHOT) {
        fprintf(f, "%" PRId64 " %d %.7f %.7f %.7f", p->id[i], p->layer[i], p->x[i], p->y[i], p->z[i]);
        if (fr->radius) fprintf(f, " %.7g", p->r[i]);
    } else {
        char x[32], y[32], z[32];
        gf_dump_exact(x, sizeof x, p->x[i]);
        gf_dump_exact(y, sizeof y, p->y[i]);
        gf_dump_exact(z, sizeof z, p->z[i]);
        fprintf(f, "%" PRId64 " %d %s %s %s", p->id[i], p->layer[i] > 0 ? (int)p->layer[i] : 1, x, y, z);
        if (fr->radius) {
            gf_dump_exact(x, sizeof x, p->r[i]);
            fprintf(f, " %s", x);
        }
    }
    if (fr->pass) fprintf(f, " %d", (int)fr->pass[i]);
    fputc('\n', f);
}

void gf_dump_write_frame(FILE *f, const gf_dump_frame *fr)
{
    if (fr->has_time) fprintf(f, "ITEM: TIME\n%.17g\n", fr->time);
    fprintf(f, "ITEM: TIMESTEP\n%" PRIu64 "\nITEM: NUMBER OF ATOMS\n%zu\n", fr->step, fr->p->n);
    gf_dump_box(f, fr);
    fprintf(f, "ITEM: ATOMS id type x y z%s%s\n", fr->radius ? " radius" : "", fr->pass ? " pass" : "");
    for (size_t i = 0; i < fr->p->n; i++) gf_dump_atom(f, fr, i);
}
