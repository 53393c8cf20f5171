// SPDX-License-Identifier: MIT
// gf_bench (granflow/bench.h): the silo is packed the way a run packs it
// (gf_packing_for_config), so an imported bidisperse packing with
// packing.types is what the bench times; its report, and bad options.
#include "support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "granflow/bench.h"
#include "granflow/granflow.h"

enum { NX = 9, NY = 4, NZ = 6 };

/// A LAMMPS dump of a 10 x 4 silo: NZ layers of NX x NY sites 1 d apart,
/// types 1 (radius 0.5) and 2 (radius 0.4) alternating (a bidisperse mixture),
/// and a top layer of type 3 (what packing.types = 1,2 leaves out).
/// Counts of each type go to n[1..3].
static const char *write_mixture(size_t n[4])
{
    static char path[1024];
    snprintf(path, sizeof path, "%s/mixture.dump", gf_test_tmpdir());
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fprintf(f, "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n%d\nITEM: BOX BOUNDS ff ff ff\n-5 5\n-2 2\n0 10\n"
               "ITEM: ATOMS id type x y z radius\n",
            NX * NY * (NZ + 1));
    int id = 1;
    memset(n, 0, 4 * sizeof *n);
    for (int k = 0; k <= NZ; k++)
        for (int j = 0; j < NY; j++)
            for (int i = 0; i < NX; i++, id++) {
                int type = k == NZ ? 3 : 1 + (i + j + k) % 2;
                n[type]++;
                fprintf(f, "%d %d %g %g %g %g\n", id, type, -4.0 + i, -1.5 + j, 0.6 + k, type == 2 ? 0.4 : 0.5);
            }
    assert_int_equal(fclose(f), 0);
    return path;
}

/// What the bench's silo held when packed: particles by radius.
typedef struct seen {
    size_t calls, small, large, other;
    int64_t max_id;
} seen;

static void on_packed(void *ctx, const gf_bench_spot *b, const gf_sim *sim, double warmup)
{
    seen *s = ctx;
    (void)warmup;
    s->calls++;
    size_t n = gf_sim_particle_count(sim);
    assert_int_equal(n, b->particles);
    int64_t *id = calloc(n, sizeof *id);
    double *r = calloc(n, sizeof *r);
    assert_true(id && r);
    assert_int_equal(gf_sim_copy_particles(sim, id, NULL, NULL, r, n, NULL), GF_OK);
    for (size_t i = 0; i < n; i++) {
        if (r[i] == 0.4) s->small++;
        else if (r[i] == 0.5) s->large++;
        else s->other++;
        if (id[i] > s->max_id) s->max_id = id[i];
    }
    free(id);
    free(r);
}

static gf_config mixture_config(const char *path, const char *types)
{
    gf_config c = gf_config_default();
    c.container_width = 10;
    c.container_depth = 4;
    c.orifice_diameter = 2;
    snprintf(c.packing_file, sizeof c.packing_file, "%s", path);
    snprintf(c.packing_types, sizeof c.packing_types, "%s", types);
    if (gf_config_validate(&c) != GF_OK) fail_msg("config: %s", gf_last_error());
    return c;
}

static gf_bench_opts small_opts(seen *s)
{
    gf_bench_opts o = gf_bench_opts_default();
    o.warmup = 0.2;
    o.window = 0.05;
    o.large = false;
    o.lga_iters = 1;
    o.packed = on_packed;
    o.ctx = s;
    return o;
}

static void packing_types_give_the_bidisperse_packing(void **state)
{
    (void)state;
    size_t n[4];
    const char *path = write_mixture(n);
    gf_config c = mixture_config(path, "1,2");
    seen s = {0};
    gf_bench_opts o = small_opts(&s);
    gf_bench_report r;
    gf_status st = gf_bench(&c, &o, &r);
    if (st != GF_OK) fail_msg("gf_bench: %s", gf_last_error());
    assert_int_equal(s.calls, 1);
    // Both species, and nothing of type 3 (the top layer, the highest ids).
    assert_int_equal(r.silo.particles, n[1] + n[2]);
    assert_int_equal(s.large, n[1]);
    assert_int_equal(s.small, n[2]);
    assert_int_equal(s.other, 0);
    assert_true(s.max_id <= NX * NY * NZ);
    assert_string_equal(r.engine, "domains");
    assert_false(r.large);
    assert_true(r.silo.threads >= 1);
    assert_int_equal(r.lga.iterations, 1);
    // One process: one rank, its peak resident set, nothing exchanged (issue 23).
    assert_int_equal(r.silo.ranks, 1);
    assert_true(r.silo.rank_peak_rss_bytes[0] > 1e6);
    assert_true(r.silo.rank_exchange_bytes_per_phase[0] == 0.0);
    assert_true(r.silo.rank_region_particles[0] > 0 && r.silo.rank_region_particles[0] <= (double)r.silo.particles);
    assert_true(r.silo.rank_slab_particles[0] == r.silo.rank_region_particles[0]);
    assert_true(r.silo.rank_held_particles[0] == (double)r.silo.particles); // one process holds every particle
    // The work per layer of sectors along z adds up to the whole work, and
    // nothing lies above the top layer.
    const gf_par_profile *f = &r.silo.prof;
    double layers = 0.0;
    for (int k = 0; k < GF_PAR_LAYERS; k++) {
        if (k >= f->blocks_along[2]) assert_true(f->layer_seconds[k] == 0.0);
        layers += f->layer_seconds[k];
    }
    assert_true(f->work_seconds > 0.0);
    assert_true(fabs(layers - f->work_seconds) <= 1e-9 * f->work_seconds);
    // Without packing.types every type is imported.
    c = mixture_config(path, "");
    s = (seen){0};
    st = gf_bench(&c, &o, &r);
    if (st != GF_OK) fail_msg("gf_bench: %s", gf_last_error());
    assert_int_equal(r.silo.particles, n[1] + n[2] + n[3]);
    assert_int_equal(s.large, n[1] + n[3]);
}

static void report_as_json(void **state)
{
    (void)state;
    gf_bench_report r = {.engine = "event", .warmup = 40, .window = 1, .step_us = 2.5, .efficiency = 1,
                         .peak_rss_bytes = 4000};
    r.silo = (gf_bench_spot){.particles = 2, .threads = 1, .spot_us = 1.25, .sps_all = 4e5, .sps_one = 4e5, .ranks = 2,
                             .rank_peak_rss_bytes = {3000, 5000}, .rank_exchange_bytes_per_phase = {0, 1234.4},
                             .rank_region_particles = {2, 1}, .rank_slab_particles = {1, 1},
                             .rank_held_particles = {2, 1}};
    r.lga = (gf_bench_lga){.site_updates_per_second = 1.5e7, .sites = 50000, .iterations = 1000};
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    assert_non_null(f);
    gf_bench_write(f, &r, true);
    assert_int_equal(fclose(f), 0);
    const char *want = "{\"engine\": \"event\", \"particles\": 2, \"threads\": 1, \"warmup_tau\": 40, \"window_tau\": 1, "
                       "\"spot_us\": 1.2500, \"relax_us\": 0.0000, \"step_us\": 2.5000, \"steps_per_second\": 400000.0, "
                       "\"steps_per_second_1thread\": 400000.0, \"parallel_efficiency\": 1.000, \"spots_active\": 0, "
                       "\"flow_rate\": 0.00, \"moves_per_tau\": 0, \"memory_bytes_per_particle\": 0.0, "
                       "\"peak_rss_bytes_per_particle\": 2000.0, \"peak_rss_bytes\": 4000, \"ranks\": 2, "
                       "\"rank_peak_rss_bytes\": [3000, 5000], \"rank_exchange_bytes_per_phase\": [0, 1234], "
                       "\"rank_region_particles\": [2, 1], \"rank_slab_particles\": [1, 1], "
                       "\"rank_held_particles\": [2, 1], "
                       "\"projected_drain_seconds\": 0, \"pack_seconds\": 0.00, "
                       "\"warmup_seconds\": 0.00, \"lga_site_updates_per_second\": 15000000, \"lga_sites\": 50000, "
                       "\"lga_iterations\": 1000}\n";
    if (strcmp(buf, want)) fail_msg("wrote\n%s\nexpected\n%s", buf, want);
    free(buf);
}

static void bad_options(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    gf_bench_opts o = gf_bench_opts_default();
    gf_bench_report r;
    o.window = 0;
    assert_int_equal(gf_bench(&c, &o, &r), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "window"));
    o = gf_bench_opts_default();
    o.warmup = NAN;
    assert_int_equal(gf_bench(&c, &o, &r), GF_ERR_PARAM);
    o = gf_bench_opts_default();
    o.lga_iters = 0;
    assert_int_equal(gf_bench(&c, &o, &r), GF_ERR_PARAM);
    assert_int_equal(gf_bench(NULL, &o, &r), GF_ERR_PARAM);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(packing_types_give_the_bidisperse_packing),
    cmocka_unit_test(report_as_json),
    cmocka_unit_test(bad_options),
};

GF_TEST_MAIN("bench", tests)
