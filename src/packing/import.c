// SPDX-License-Identifier: MIT
// Importing packing.file as a run's initial packing: its lengths converted
// to d (dump.diameter), atom-type filter (packing.types) and particles
// already below the base (SPEC 1.2, 1.8).
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "granflow/defs.h"
#include "granflow/packing.h"
#include "io/packing_frames.h"
#include "packing/import.h"
#include "core/textscan.h"

/// The last frame of a LAMMPS dump, with whether it had a `type` column.
typedef struct gf_import_last {
    gf_packing pk;
    int have_type;
    size_t frames;
} gf_import_last;

static gf_status gf_import_keep_last(void *ctx, const gf_packing_frame *f, gf_packing *pk)
{
    gf_import_last *l = ctx;
    gf_packing_free(&l->pk);
    l->pk = *pk;
    memset(pk, 0, sizeof *pk);
    l->have_type = f->have_type;
    l->frames++;
    return GF_OK;
}


static int gf_cmp_centre(const void *a, const void *b, void *ctx)
{
    const gf_packing *p = ctx;
    size_t i = *(const size_t *)a, j = *(const size_t *)b;
    const double u[3] = {p->x[i], p->y[i], p->z[i]}, v[3] = {p->x[j], p->y[j], p->z[j]};
    for (int k = 0; k < 3; k++)
        if (u[k] != v[k]) return u[k] < v[k] ? -1 : 1;
    return (i > j) - (i < j);
}

// Sorting with a context: qsort_r is not POSIX, so a small merge sort.
static void gf_sort_centres(size_t *a, size_t *tmp, size_t n, const gf_packing *p)
{
    if (n < 2) return;
    size_t h = n / 2;
    gf_sort_centres(a, tmp, h, p);
    gf_sort_centres(a + h, tmp, n - h, p);
    size_t i = 0, j = h, k = 0;
    while (i < h && j < n) tmp[k++] = gf_cmp_centre(&a[i], &a[j], (void *)p) <= 0 ? a[i++] : a[j++];
    while (i < h) tmp[k++] = a[i++];
    while (j < n) tmp[k++] = a[j++];
    memcpy(a, tmp, n * sizeof *a);
}

// What the engine cannot simulate: radii outside its range, and two
// particles on one centre (relax() has no direction to part them along, so
// they would stay together for the whole run).
gf_status gf_packing_import_check(const gf_config *cfg, const gf_packing *p)
{
    gf_packing_defs pd;
    gf_config_packing_defs(cfg, &pd);
    const char *path = pd.file;
    for (size_t i = 0; i < p->n; i++)
        if (!(p->r[i] >= GF_IMPORT_RMIN && p->r[i] <= GF_IMPORT_RMAX)) {
            // A file in other units (metres, say) shows here first: say which key converts it.
            char where[GF_PATH_MAX + 32];
            gf_config_where(cfg, "dump.diameter", where, sizeof where);
            return gf_error_set(GF_ERR_FORMAT,
                                "%s: particle id %lld has radius %g d: the engine takes radii in [%g, %g] d "
                                "(its unit is the mean diameter); a file in another length unit needs "
                                "dump.diameter = the particle diameter in that unit (this one's is %g; "
                                "dump.diameter = %g, %s)",
                                path, (long long)p->id[i], p->r[i], GF_IMPORT_RMIN, GF_IMPORT_RMAX,
                                2.0 * p->r[i] * pd.unit_diameter, pd.unit_diameter, where);
        }
    size_t *a = GF_NEW(size_t, p->n), *tmp = GF_NEW(size_t, p->n);
    gf_status st = GF_OK;
    if (!a || !tmp) st = gf_error_set(GF_ERR_NOMEM, "%s: out of memory checking %zu centres", path, p->n);
    for (size_t i = 0; st == GF_OK && i < p->n; i++) a[i] = i;
    if (st == GF_OK) gf_sort_centres(a, tmp, p->n, p);
    for (size_t k = 1; st == GF_OK && k < p->n; k++) {
        size_t i = a[k - 1], j = a[k];
        if (p->x[i] == p->x[j] && p->y[i] == p->y[j] && p->z[i] == p->z[j])
            st = gf_error_set(GF_ERR_FORMAT,
                              "%s: particles id %lld and id %lld have the same centre (%g, %g, %g): "
                              "no packing can hold them",
                              path, (long long)p->id[i], (long long)p->id[j], p->x[i], p->y[i], p->z[i]);
    }
    GF_DELETE(a, p->n);
    GF_DELETE(tmp, p->n);
    return st;
}

static int gf_import_is_lammps(const char *path)
{
    return !gf_textscan_has_ext(path, ".xyz") && !gf_textscan_has_ext(path, ".csv");
}

gf_status gf_packing_import(const gf_config *cfg, gf_packing *out, gf_packing_import_report *rep)
{
    gf_packing_defs pd;
    gf_config_packing_defs(cfg, &pd);
    gf_packing_import_report r = {0};
    if (rep) *rep = r;
    const char *path = pd.file;
    int32_t types[GF_PACKING_MAXTYPES];
    size_t ntypes;
    // Errors about packing.types start with where it was set.
    char at[GF_PATH_MAX + 40];
    gf_config_where_lead(cfg, "packing.types", at, sizeof at);
    gf_status st = gf_packing_types_parse(pd.types, types, GF_PACKING_MAXTYPES, &ntypes);
    if (st != GF_OK) {
        char why[256];
        snprintf(why, sizeof why, "%s", gf_last_error());
        return gf_error_set(st, "%spacking.types = %s: %s", at, pd.types, why);
    }
    gf_packing pk = {0};
    if (ntypes == 0) {
        st = gf_packing_read_in(path, GF_FORMAT_AUTO, pd.unit_diameter, &pk);
    } else if (!gf_import_is_lammps(path)) {
        st = gf_error_set(GF_ERR_PARAM, "%spacking.types = %s needs a LAMMPS dump with a type column, not %s",
                          at, pd.types, path);
    } else {
        gf_import_last last = {0};
        st = gf_packing_read_frames_in(path, pd.unit_diameter, gf_import_keep_last, &last);
        if (st == GF_OK && last.frames == 0) st = gf_error_set(GF_ERR_FORMAT, "%s: no frame in the file", path);
        else if (st == GF_OK && !last.have_type)
            st = gf_error_set(GF_ERR_PARAM, "%spacking.types = %s: %s has no `type` column in its ITEM: ATOMS line",
                              at, pd.types, path);
        pk = last.pk; // the frames reader keeps the type column in `layer`
    }
    if (st != GF_OK) {
        gf_packing_free(&pk);
        return st;
    }
    r.read = pk.n;
    const double exit_plane = gf_config_exit_plane(cfg);
    size_t keep = 0;
    for (size_t i = 0; i < pk.n; i++) {
        bool ok = ntypes == 0;
        for (size_t k = 0; k < ntypes && !ok; k++) ok = pk.layer[i] == types[k];
        if (!ok) {
            r.other_types++;
            continue;
        }
        if (pk.z[i] < exit_plane) {
            r.below_base++;
            continue;
        }
        pk.id[keep] = pk.id[i];
        pk.x[keep] = pk.x[i];
        pk.y[keep] = pk.y[i];
        pk.z[keep] = pk.z[i];
        pk.r[keep] = pk.r[i];
        keep++;
    }
    pk.n = keep;
    if (rep) *rep = r;
    if (keep > 0 && (st = gf_packing_import_check(cfg, &pk)) != GF_OK) {
        gf_packing_free(&pk);
        return st;
    }
    if (keep == 0) {
        gf_packing_free(&pk);
        return gf_error_set(GF_ERR_PARAM,
                            "%s: no particle left of %zu (%zu of other atom types than packing.types = '%s', "
                            "%zu below the exit plane, container.exit_z less container.outlet_length)",
                            path, r.read, r.other_types, pd.types, r.below_base);
    }
    gf_packing_tag_layers(&pk, pd.layer_thickness);
    gf_packing_free(out);
    *out = pk;
    return GF_OK;
}
