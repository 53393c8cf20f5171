// SPDX-License-Identifier: MIT
// A DEM run (LAMMPS dumps) as a series: read in d and tau (dump.diameter,
// dump.gravity), the container from a config or --set and, for the walls
// none gives, from the particles' extent, the atom types of packing.types,
// the particles below the base counted as exited, and without exits.csv the
// exits read off the frames (SPEC 1.8).
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/alloc.h"
#include "core/error.h"
#include "granflow/defs.h"
#include "granflow/dem.h"
#include "core/textscan.h"
#include "geom/container.h"
#include "packing/layer.h"

static int gf_dem_is_dump(const char *name)
{
    if (name[0] == '.') return 0;
    if (gf_textscan_has_ext(name, ".dump") || gf_textscan_has_ext(name, ".lammpstrj") ||
        gf_textscan_has_ext(name, ".txt"))
        return 1;
    return strncmp(name, "dump.", 5) == 0 && name[5] != '\0';
}

/// The first dump gf_series_load reads from `path` (same rules), into `out`.
static int gf_dem_first_dump(const char *path, char *out, size_t n)
{
    struct stat sb;
    if (stat(path, &sb) != 0) return 0;
    if (!S_ISDIR(sb.st_mode)) return snprintf(out, n, "%s", path) < (int)n;
    char dir[GF_PATH_MAX + 16];
    snprintf(dir, sizeof dir, "%s/snapshots", path);
    if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode)) snprintf(dir, sizeof dir, "%s", path);
    DIR *d = opendir(dir);
    if (!d) return 0;
    char best[256] = "";
    for (struct dirent *e; (e = readdir(d)) != NULL;)
        if (gf_dem_is_dump(e->d_name) && (!best[0] || strcmp(e->d_name, best) < 0))
            snprintf(best, sizeof best, "%s", e->d_name);
    closedir(d);
    return best[0] && snprintf(out, n, "%s/%s", dir, best) < (int)n;
}

/// Whether the first ITEM: ATOMS line of `file` names a `type` column.
static bool gf_dem_has_type(const char *file)
{
    gf_textscan ts;
    if (gf_textscan_open(&ts, file) != GF_OK) return false;
    char *line, *tok[64];
    size_t len;
    gf_status st;
    bool found = false;
    while (gf_textscan_next(&ts, &line, &len, &st) == 1)
        if (strncmp(line, "ITEM: ATOMS", 11) == 0) {
            size_t n = gf_textscan_split(line + 11, tok, 64);
            for (size_t k = 0; k < n && k < 64; k++)
                if (strcmp(tok[k], "type") == 0) found = true;
            break;
        }
    gf_textscan_close(&ts);
    gf_error_clear();
    return found;
}

/// Keeps the particles of `p` for which keep[i] is set, in order.
static void gf_dem_compact(gf_packing *p, const unsigned char *keep)
{
    size_t m = 0;
    for (size_t i = 0; i < p->n; i++) {
        if (!keep[i]) continue;
        p->id[m] = p->id[i];
        p->layer[m] = p->layer[i];
        p->x[m] = p->x[i];
        p->y[m] = p->y[i];
        p->z[m] = p->z[i];
        p->r[m] = p->r[i];
        m++;
    }
    p->n = m;
}

/// Layer tags from the first frame's heights, carried to later frames by id.
static gf_status gf_dem_retag(gf_series *s)
{
    if (s->nframes == 0) return GF_OK;
    gf_packing_defs pd;
    gf_config_packing_defs(&s->cfg, &pd);
    double thick = pd.layer_thickness;
    gf_packing *p0 = &s->frames[0].pk;
    gf_packing_tag_layers(p0, thick);
    gf_idmap m;
    gf_status st = gf_idmap_build(p0, &m);
    if (st != GF_OK) return st;
    for (size_t k = 1; k < s->nframes; k++) {
        gf_packing *p = &s->frames[k].pk;
        for (size_t i = 0; i < p->n; i++) {
            size_t j = gf_idmap_find(&m, p->id[i]);
            p->layer[i] = j == SIZE_MAX ? gf_packing_layer_of(p->z[i], thick) : p0->layer[j];
        }
    }
    gf_idmap_free(&m);
    return GF_OK;
}

/// The dumps' units: dump.diameter and dump.gravity of src->config and
/// src->sets only. A run directory's own config.ini may hold them too, for
/// its packing.file; its snapshots granflow wrote in d and tau.
static gf_status gf_dem_units(const gf_dem_source *src, gf_config *ucfg)
{
    *ucfg = gf_config_default();
    gf_status st = src->config ? gf_config_load(ucfg, src->config) : GF_OK;
    for (size_t k = 0; st == GF_OK && k < src->nsets; k++) st = gf_config_set(ucfg, src->sets[k], "--set");
    return st;
}

/// "container.width = 50 (particle extent)"-style text of the container and
/// the units, for the report of gf_dem_series_load.
static void gf_dem_describe(const gf_config *cfg, const gf_series_units *u, char *buf, size_t n)
{
    const gf_container c = gf_container_make(cfg);
    gf_container_describe(&c, cfg, buf, n);
    int len = (int)strlen(buf);
    if (len >= 0 && (size_t)len < n && (u->diameter != 1.0 || u->gravity != 1.0))
        snprintf(buf + len, n - (size_t)len, "; the dumps read with d = %g and tau = %.6g in their units "
                 "(dump.diameter = %g, dump.gravity = %g)", u->diameter, sqrt(u->diameter / u->gravity),
                 u->diameter, u->gravity);
}

/// A dump in other units than d read as if in d: particles a few thousandths
/// of a d across (a radius column), or (without one) two or more centres all
/// within one d of each other, which no packing of unit spheres has. Said
/// so, with the keys that fix it.
static gf_status gf_dem_check_scale(const char *path, const gf_series *s, const gf_series_units *u)
{
    const gf_packing *p = s->nframes ? &s->frames[0].pk : NULL;
    if (!p || p->n == 0) return GF_OK;
    double r = 0.0, lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < p->n; i++) {
        const double c[3] = {p->x[i], p->y[i], p->z[i]};
        r += p->r[i];
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], c[k]);
            hi[k] = fmax(hi[k], c[k]);
        }
    }
    r /= (double)p->n;
    const double span = hypot(hypot(hi[0] - lo[0], hi[1] - lo[1]), hi[2] - lo[2]);
    if (2.0 * r >= 0.2 && 2.0 * r <= 10.0 && (p->n < 2 || span >= 1.0)) return GF_OK;
    return gf_error_set(GF_ERR_PARAM,
                        "%s: read with dump.diameter = %g, its first frame's %zu particles have a mean diameter "
                        "of %g d and their centres span %g d: dumps in another length unit than d need "
                        "dump.diameter = the particle diameter in that unit (0.004 for 4 mm spheres in metres) "
                        "and dump.gravity = gravity in their units (9.81 in SI; times are read in tau = "
                        "sqrt(dump.diameter / dump.gravity)), e.g. --set dump.diameter=0.004 --set dump.gravity=9.81",
                        path, u->diameter, p->n, 2.0 * r, span);
}

gf_status gf_dem_series_load(const char *path, const gf_dem_source *src, gf_series *out, gf_dem_load_report *rep)
{
    gf_dem_source none = {0};
    if (!src) src = &none;
    gf_dem_load_report r = {0};
    if (rep) *rep = r;
    memset(out, 0, sizeof *out);
    gf_config cfg;
    gf_status st = gf_dem_units(src, &cfg);
    if (st != GF_OK) return st;
    gf_packing_defs units;
    gf_config_packing_defs(&cfg, &units);
    const gf_series_units u = {units.unit_diameter, units.unit_gravity};
    const bool converted = u.diameter != 1.0 || u.gravity != 1.0;
    const gf_series_opts so = {.units = &u, .stop = src->stop};
    st = gf_series_load(path, src->dump_dt, &so, out);
    if (st != GF_OK) return st;
    char mark[GF_PATH_MAX + 32];
    struct stat sb;
    if (snprintf(mark, sizeof mark, "%s/%s", path, GF_DEM_INTERRUPTED) < (int)sizeof mark && stat(mark, &sb) == 0)
        gf_warn("%s: its LAMMPS run was stopped before the end (%s says where): the snapshots stop early", path, mark);
    if (converted && out->has_config) {
        char at[GF_PATH_MAX + 40];
        st = gf_error_set(GF_ERR_PARAM,
                          "%sdump.diameter = %g, dump.gravity = %g: %s is a run of granflow (it has config.ini), "
                          "whose snapshots are in d and tau already; the two keys describe the dumps of other "
                          "programs (a LIGGGHTS or LAMMPS run in SI units)",
                          gf_config_where_lead(&cfg, converted && u.diameter != 1.0 ? "dump.diameter" : "dump.gravity",
                                               at, sizeof at),
                          u.diameter, u.gravity, path);
        goto fail;
    }
    // The container: from --config, else the run's config.ini, else the
    // defaults; --set over it; walls no file gave fitted to the particles
    // once the other atom types and the exited are gone (below).
    if (!src->config) {
        cfg = out->has_config ? out->cfg : gf_config_default();
        for (size_t k = 0; st == GF_OK && k < src->nsets; k++) st = gf_config_set(&cfg, src->sets[k], "--set");
        if (st != GF_OK) goto fail;
    }

    char first[GF_PATH_MAX + 300];
    r.have_type = gf_dem_first_dump(path, first, sizeof first) && gf_dem_has_type(first);
    int32_t types[GF_PACKING_MAXTYPES];
    size_t ntypes = 0;
    gf_packing_defs pd;
    gf_config_packing_defs(&cfg, &pd);
    if ((st = gf_packing_types_parse(pd.types, types, GF_PACKING_MAXTYPES, &ntypes)) != GF_OK) goto fail;
    if (ntypes && !r.have_type) {
        st = gf_error_set(GF_ERR_PARAM, "packing.types = %s: the dumps of %s have no `type` column", pd.types,
                          path);
        goto fail;
    }
    const double exit_plane = gf_config_exit_plane(&cfg);
    for (size_t k = 0; k < out->nframes; k++) {
        gf_packing *p = &out->frames[k].pk;
        size_t n0 = p->n;
        unsigned char *keep = n0 ? GF_NEW(unsigned char, n0) : NULL;
        if (p->n && !keep) {
            st = gf_error_set(GF_ERR_NOMEM, "out of memory filtering %zu particles", p->n);
            goto fail;
        }
        for (size_t i = 0; i < p->n; i++) {
            bool ok = ntypes == 0;
            for (size_t t = 0; t < ntypes && !ok; t++) ok = p->layer[i] == types[t];
            if (!ok) r.other_types++;
            else if (p->z[i] < exit_plane) r.below_base++, ok = false;
            keep[i] = ok;
        }
        gf_dem_compact(p, keep);
        if (keep) GF_DELETE(keep, n0);
    }
    if (!out->has_config || src->config) {
        // A frozen floor or wall beads of other types are not the packing:
        // the walls are fitted to what is left (the loader's fit included them).
        gf_config fresh = cfg;
        if (!src->config) { // the loader's "particle extent" is no setting of the user's
            fresh = gf_config_default();
            for (size_t k = 0; st == GF_OK && k < src->nsets; k++) st = gf_config_set(&fresh, src->sets[k], "--set");
        }
        if (st == GF_OK) st = gf_dem_check_scale(path, out, &u);
        if (st == GF_OK) st = gf_series_fit_walls(out, &fresh);
        if (st != GF_OK) goto fail;
        cfg = fresh;
    }
    if ((st = gf_config_validate(&cfg)) != GF_OK) goto fail;
    // The series is in d and tau now: a config made from it (calibrate's
    // params.ini, with the first frame as its packing) must not convert again.
    gf_config_set_dump_units(&cfg, 1.0, 1.0);
    out->cfg = cfg;
    r.diameter = u.diameter;
    r.gravity = u.gravity;
    gf_dem_describe(&cfg, &u, r.container, sizeof r.container);
    // A `type` column was read into the layer tags: tag them by height again.
    if (r.have_type && (st = gf_dem_retag(out)) != GF_OK) goto fail;
    out->n_initial = out->nframes ? out->frames[0].pk.n : 0;
    // No exits.csv (LAMMPS writes none): the exits are read off the frames,
    // after the particles below the exit plane were dropped from them. Not
    // those of a recirculating run: a particle put back between two frames
    // never leaves one, so the outflow would come out short without a word.
    gf_rundir_defs rdd;
    gf_config_rundir_defs(&cfg, &rdd);
    if (!out->has_exits && rdd.recirculate) {
        st = gf_error_set(GF_ERR_FORMAT,
                          "%s: run.recirculate = on but no exits.csv: the exits of a recirculating run cannot be "
                          "read off its snapshots (granflow dem writes exits.csv from reinserted.txt when LAMMPS "
                          "ends or is stopped; after a kill, drain again with granflow dem ... --drain-only)",
                          path);
        goto fail;
    }
    if (!out->has_exits && (st = gf_series_derive_exits(out)) != GF_OK) goto fail;
    if (rep) *rep = r;
    return GF_OK;
fail:
    gf_series_free(out);
    return st;
}

gf_dem_source gf_dem_source_default(void) { return (gf_dem_source){.dump_dt = 0}; }
