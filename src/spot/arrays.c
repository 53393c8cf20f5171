// SPDX-License-Identifier: MIT
// The simulation as flat arrays and named numbers, for bindings (Python's
// ctypes) that must not depend on struct layouts.
#include "granflow/sim.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "geom/container.h"
#include "granflow/defs.h"
#include "granflow/packing.h"
#ifdef GF_MPI
#include "spot/par_mpi.h"
#endif

gf_status gf_sim_create_from_config(const gf_config *cfg, const gf_packing_opts *opts, gf_sim **out)
{
    if (!cfg || !out) return gf_error_set(GF_ERR_PARAM, "gf_sim_create_from_config: NULL argument");
    *out = NULL;
    gf_config c = *cfg;
    gf_status st = gf_config_validate(&c);
    if (st != GF_OK) return st;
#ifdef GF_MPI
    // MPI ranks of the domain engine read packing.file keeping their regions.
    if (gf_mpi_windowed(&c)) return gf_mpi_sim_create_part(&c, out);
#endif
    gf_packing pk = {0};
    gf_packing_import_report rep;
    st = gf_packing_for_config(&c, opts, &pk, &rep);
    gf_packing_defs pd;
    gf_config_packing_defs(&c, &pd);
    if (st == GF_OK && (rep.other_types || rep.below_base))
        gf_warn("%s: %zu of %zu particles kept (%zu below the base counted as exited, %zu of other atom types dropped)",
                pd.file, pk.n, rep.read, rep.below_base, rep.other_types);
    if (st == GF_OK) st = gf_sim_create(&c, &pk, out);
    gf_packing_free(&pk);
    return st;
}

static int gf_cmp_i64(const void *a, const void *b)
{
    int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
    return (x > y) - (x < y);
}

// The first id that occurs twice (0: none); ids are already known to be >= 1.
static gf_status gf_first_repeated_id(const int64_t *id, size_t n, int64_t *dup)
{
    *dup = 0;
    int64_t *sorted = GF_NEW(int64_t, n);
    if (!sorted) return gf_error_set(GF_ERR_NOMEM, "out of memory");
    memcpy(sorted, id, sizeof *sorted * n);
    qsort(sorted, n, sizeof *sorted, gf_cmp_i64);
    for (size_t i = 1; i < n && !*dup; i++)
        if (sorted[i] == sorted[i - 1]) *dup = sorted[i];
    GF_DELETE(sorted, n);
    return GF_OK;
}

gf_status gf_sim_create_from_arrays(const gf_config *cfg, size_t n, const double *xyz, const double *radius,
                                    const int64_t *id, gf_sim **out)
{
    if (!cfg || !out || (n && !xyz)) return gf_error_set(GF_ERR_PARAM, "gf_sim_create_from_arrays: NULL argument");
    *out = NULL;
    if (n == 0) return gf_error_set(GF_ERR_PARAM, "no particles: give at least one position");
    gf_config c = *cfg;
    gf_status st = gf_config_validate(&c);
    if (st != GF_OK) return st;
    for (size_t i = 0; i < n; i++) {
        const double *p = xyz + 3 * i;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
            return gf_error_set(GF_ERR_PARAM, "positions[%zu] = (%g, %g, %g) is not finite", i, p[0], p[1], p[2]);
        if (radius && !(isfinite(radius[i]) && radius[i] > 0))
            return gf_error_set(GF_ERR_PARAM, "radii[%zu] = %g: a radius must be positive and finite (d)", i,
                                radius[i]);
        if (id && id[i] < 1)
            return gf_error_set(GF_ERR_PARAM, "ids[%zu] = %lld: ids must be >= 1", i, (long long)id[i]);
    }
    if (id) {
        int64_t dup;
        if ((st = gf_first_repeated_id(id, n, &dup)) != GF_OK) return st;
        if (dup) {
            size_t a = 0, b = 0;
            while (id[a] != dup) a++;
            for (b = a + 1; id[b] != dup; b++) {}
            return gf_error_set(GF_ERR_PARAM, "ids[%zu] = ids[%zu] = %lld: ids must be unique", a, b, (long long)dup);
        }
    }
    gf_packing pk = {0};
    st = gf_packing_reserve(&pk, n);
    for (size_t i = 0; st == GF_OK && i < n; i++)
        st = gf_packing_push(&pk, id ? id[i] : (int64_t)i + 1, 0, xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2],
                             radius ? radius[i] : 0.5);
    if (st == GF_OK) {
        gf_packing_defs pd;
        gf_config_packing_defs(&c, &pd);
        gf_packing_tag_layers(&pk, pd.layer_thickness);
        // gf_packing_check names the particle by id; the caller knows indices.
        gf_container box = gf_container_make(&c);
        for (size_t i = 0; i < n; i++)
            if (!gf_container_contains(&box, pk.x[i], pk.y[i], pk.z[i], 0.0, 0.0)) {
                st = gf_error_set(GF_ERR_PARAM,
                                  "positions[%zu] = (%g, %g, %g) is outside the container (|x| <= %g, |y| <= %g, "
                                  "above the base except over the outlet)",
                                  i, pk.x[i], pk.y[i], pk.z[i], box.xhi, box.yhi);
                break;
            }
    }
    if (st == GF_OK) st = gf_sim_create(&c, &pk, out);
    gf_packing_free(&pk);
    return st;
}

size_t gf_sim_particle_count(const gf_sim *sim) { return gf_sim_get_stats(sim).particles_remaining; }

gf_status gf_sim_copy_particles(const gf_sim *sim, int64_t *id, int32_t *layer, double *xyz, double *radius,
                                size_t cap, size_t *n)
{
    gf_packing pk = {0};
    gf_status st = gf_sim_particles(sim, &pk);
    if (st == GF_OK && pk.n > cap)
        st = gf_error_set(GF_ERR_PARAM, "gf_sim_copy_particles: %zu particles, room for %zu", pk.n, cap);
    if (st == GF_OK) {
        for (size_t i = 0; i < pk.n; i++) {
            if (id) id[i] = pk.id[i];
            if (layer) layer[i] = pk.layer[i];
            if (radius) radius[i] = pk.r[i];
            if (xyz) {
                xyz[3 * i] = pk.x[i];
                xyz[3 * i + 1] = pk.y[i];
                xyz[3 * i + 2] = pk.z[i];
            }
        }
        if (n) *n = pk.n;
    }
    gf_packing_free(&pk);
    return st;
}

size_t gf_sim_exit_count(const gf_sim *sim)
{
    size_t n;
    gf_sim_exits(sim, &n);
    return n;
}

gf_status gf_sim_copy_exits(const gf_sim *sim, int64_t *id, double *txy, size_t cap, size_t *n)
{
    size_t m;
    const gf_exit *e = gf_sim_exits(sim, &m);
    if (m > cap) return gf_error_set(GF_ERR_PARAM, "gf_sim_copy_exits: %zu exits, room for %zu", m, cap);
    for (size_t i = 0; i < m; i++) {
        if (id) id[i] = e[i].id;
        if (txy) {
            txy[3 * i] = e[i].time;
            txy[3 * i + 1] = e[i].x;
            txy[3 * i + 2] = e[i].y;
        }
    }
    if (n) *n = m;
    return GF_OK;
}

// Every member of gf_sim_stats, by name (the order of the struct).
#define GF_STATS(X)                                                                                     \
    X(time) X(particles_initial) X(particles_remaining) X(particles_exited) X(spots_active)             \
    X(spots_inserted) X(spots_deleted) X(spot_moves) X(relax_calls) X(global_relaxations) X(events)     \
    X(nlist_builds) X(spot_seconds) X(relax_seconds) X(spot_dz) X(relax_dz)

static const char *const gf_stat_names[] = {
#define GF_STAT_NAME(m) #m,
    GF_STATS(GF_STAT_NAME)
#undef GF_STAT_NAME
};

double gf_sim_stat(const gf_sim *sim, const char *name)
{
    if (!sim || !name) return NAN;
    gf_sim_stats s = gf_sim_get_stats(sim);
#define GF_STAT_GET(m) if (!strcmp(name, #m)) return (double)s.m;
    GF_STATS(GF_STAT_GET)
#undef GF_STAT_GET
    return NAN;
}

size_t gf_sim_stat_count(void) { return sizeof gf_stat_names / sizeof gf_stat_names[0]; }

const char *gf_sim_stat_name(size_t i) { return i < gf_sim_stat_count() ? gf_stat_names[i] : NULL; }
