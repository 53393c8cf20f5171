// SPDX-License-Identifier: MIT
// gf_packing_write: LAMMPS text dump, XYZ or CSV, written to `path.tmp` and
// renamed over `path` so that readers never see half a file.
#include "granflow/particles.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "granflow/defs.h"
#include "io/dump_write.h"

enum { GF_WRITE_PATH_MAX = 4096 };

static int gf_write_has_suffix(const char *path, const char *suffix)
{
    size_t n = strlen(path), k = strlen(suffix);
    return n >= k && strcasecmp(path + n - k, suffix) == 0;
}

static void gf_write_bounds(const gf_packing *p, const gf_config *cfg, double lo[3], double hi[3])
{
    double zmax = 0.0, zmin = 0.0;
    double bmin[2] = {0.0, 0.0}, bmax[2] = {0.0, 0.0};
    for (size_t i = 0; i < p->n; i++) {
        double r = p->r[i];
        double xl = p->x[i] - r, xh = p->x[i] + r, yl = p->y[i] - r, yh = p->y[i] + r;
        if (i == 0 || xl < bmin[0]) bmin[0] = xl;
        if (i == 0 || xh > bmax[0]) bmax[0] = xh;
        if (i == 0 || yl < bmin[1]) bmin[1] = yl;
        if (i == 0 || yh > bmax[1]) bmax[1] = yh;
        if (p->z[i] - r < zmin) zmin = p->z[i] - r;
        if (i == 0 || p->z[i] + r > zmax) zmax = p->z[i] + r;
    }
    if (cfg) {
        gf_container_defs d;
        gf_config_container_defs(cfg, &d);
        lo[0] = -0.5 * d.width;
        hi[0] = 0.5 * d.width;
        lo[1] = -0.5 * d.depth;
        hi[1] = 0.5 * d.depth;
    } else {
        lo[0] = bmin[0];
        hi[0] = bmax[0];
        lo[1] = bmin[1];
        hi[1] = bmax[1];
    }
    lo[2] = zmin; // 0 unless particles hang below the base (leaving through the orifice)
    hi[2] = zmax;
}

static void gf_write_body(FILE *f, const gf_packing *p, gf_packing_format format,
                          const gf_config *cfg)
{
    char x[32], y[32], z[32], r[32];
    if (format == GF_FORMAT_LAMMPS) {
        // Exact numbers (the brief's "%.9g" would lose up to 5e-9 relative):
        // a written packing reads back bit for bit.
        gf_dump_frame fr = {.p = p, .numbers = GF_DUMP_EXACT, .step = 0, .radius = true};
        gf_write_bounds(p, cfg, fr.lo, fr.hi);
        gf_dump_write_frame(f, &fr);
        return;
    }
    if (format == GF_FORMAT_XYZ) {
        // Extended XYZ: the comment line names the columns, so the radii
        // come back (a bidisperse packing stays bidisperse) and OVITO and
        // ASE read them too.
        fprintf(f, "%zu\ngranflow packing Properties=species:S:1:pos:R:3:radius:R:1\n", p->n);
    } else {
        fputs("id,type,x,y,z,radius\n", f);
    }
    for (size_t i = 0; i < p->n; i++) {
        gf_dump_exact(x, sizeof x, p->x[i]);
        gf_dump_exact(y, sizeof y, p->y[i]);
        gf_dump_exact(z, sizeof z, p->z[i]);
        gf_dump_exact(r, sizeof r, p->r[i]);
        if (format == GF_FORMAT_XYZ) {
            fprintf(f, "P %s %s %s %s\n", x, y, z, r);
            continue;
        }
        int type = p->layer[i] > 0 ? (int)p->layer[i] : 1;
        fprintf(f, "%lld,%d,%s,%s,%s,%s\n", (long long)p->id[i], type, x, y, z, r);
    }
}

gf_status gf_packing_write(const gf_packing *p, const char *path, gf_packing_format format,
                           const gf_config *cfg)
{
    if (!p || !path || !*path)
        return gf_error_set(GF_ERR_PARAM, "gf_packing_write: %s",
                            p ? "no file name" : "no packing");
    if (format == GF_FORMAT_AUTO)
        format = gf_write_has_suffix(path, ".xyz")   ? GF_FORMAT_XYZ
                 : gf_write_has_suffix(path, ".csv") ? GF_FORMAT_CSV
                                                     : GF_FORMAT_LAMMPS;
    if (format != GF_FORMAT_LAMMPS && format != GF_FORMAT_XYZ && format != GF_FORMAT_CSV)
        return gf_error_set(GF_ERR_PARAM, "gf_packing_write: unknown format %d for %s", (int)format,
                            path);
    for (size_t i = 0; i < p->n; i++)
        if (!isfinite(p->x[i]) || !isfinite(p->y[i]) || !isfinite(p->z[i]) || !isfinite(p->r[i]))
            return gf_error_set(
                GF_ERR_PARAM, "cannot write %s: particle %lld has a non-finite position or radius",
                path, (long long)p->id[i]);
    char tmp[GF_WRITE_PATH_MAX];
    FILE *f;
    gf_status st = gf_atomic_open(path, tmp, sizeof tmp, &f);
    if (st != GF_OK) return st;
    gf_write_body(f, p, format, cfg);
    return gf_atomic_commit(f, tmp, path);
}
