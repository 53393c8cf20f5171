// SPDX-License-Identifier: MIT
// Importing packing.file as a run's initial packing: atom-type filter
// (packing.types) and particles already below the base (SPEC 1.2, 1.8).
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "granflow/packing.h"
#include "io/packing_frames.h"
#include "io/textscan.h"

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

static int gf_import_is_lammps(const char *path)
{
    return !gf_textscan_has_ext(path, ".xyz") && !gf_textscan_has_ext(path, ".csv");
}

gf_status gf_packing_import(const gf_config *cfg, gf_packing *out, gf_packing_import_report *rep)
{
    gf_packing_import_report r = {0};
    if (rep) *rep = r;
    const char *path = cfg->packing_file;
    int32_t types[GF_PACKING_MAXTYPES];
    size_t ntypes;
    gf_status st = gf_packing_types_parse(cfg->packing_types, types, GF_PACKING_MAXTYPES, &ntypes);
    if (st != GF_OK) {
        char why[256];
        snprintf(why, sizeof why, "%s", gf_last_error());
        return gf_error_set(st, "packing.types = %s: %s", cfg->packing_types, why);
    }
    gf_packing pk = {0};
    if (ntypes == 0) {
        st = gf_packing_read(path, GF_FORMAT_AUTO, &pk);
    } else if (!gf_import_is_lammps(path)) {
        st = gf_error_set(GF_ERR_PARAM, "packing.types = %s needs a LAMMPS dump with a type column, not %s",
                          cfg->packing_types, path);
    } else {
        gf_import_last last = {0};
        st = gf_packing_read_frames(path, gf_import_keep_last, &last);
        if (st == GF_OK && last.frames == 0) st = gf_error_set(GF_ERR_FORMAT, "%s: no frame in the file", path);
        else if (st == GF_OK && !last.have_type)
            st = gf_error_set(GF_ERR_PARAM, "packing.types = %s: %s has no `type` column in its ITEM: ATOMS line",
                              cfg->packing_types, path);
        pk = last.pk; // the frames reader keeps the type column in `layer`
    }
    if (st != GF_OK) {
        gf_packing_free(&pk);
        return st;
    }
    r.read = pk.n;
    size_t keep = 0;
    for (size_t i = 0; i < pk.n; i++) {
        bool ok = ntypes == 0;
        for (size_t k = 0; k < ntypes && !ok; k++) ok = pk.layer[i] == types[k];
        if (!ok) {
            r.other_types++;
            continue;
        }
        if (pk.z[i] < gf_config_exit_plane(cfg)) {
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
    if (keep == 0) {
        gf_packing_free(&pk);
        return gf_error_set(GF_ERR_PARAM,
                            "%s: no particle left of %zu (%zu of other atom types than packing.types = '%s', "
                            "%zu below the exit plane, container.exit_z less container.outlet_length)",
                            path, r.read, r.other_types, cfg->packing_types, r.below_base);
    }
    gf_packing_tag_layers(&pk, cfg->packing_layer_thickness);
    gf_packing_free(out);
    *out = pk;
    return GF_OK;
}
