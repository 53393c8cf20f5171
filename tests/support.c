// SPDX-License-Identifier: MIT
#include "support.h"

#include <zlib.h>

#include <math.h>

#include "core/alloc.h"
#include "granflow/analysis.h"
#include "granflow/granflow.h"
#include "run_outcome.h"
#include "spot/sim_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char gf_tmp[512];

static void gf_test_cleanup(void)
{
    if (gf_tmp[0] && !getenv("GF_KEEP_TMP")) {
        char cmd[600];
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", gf_tmp);
        if (system(cmd) != 0) fprintf(stderr, "warning: could not remove %s\n", gf_tmp);
    }
}

const char *gf_test_tmpdir(void)
{
    if (!gf_tmp[0]) {
        const char *base = getenv("TMPDIR");
        snprintf(gf_tmp, sizeof gf_tmp, "%s/gftest.XXXXXX", base && *base ? base : "/tmp");
        if (!mkdtemp(gf_tmp)) {
            perror("mkdtemp");
            abort();
        }
        atexit(gf_test_cleanup);
    }
    return gf_tmp;
}

const char *gf_test_write_file(const char *dir, const char *name, const char *text)
{
    static char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (!f) {
        perror(path);
        abort();
    }
    fputs(text, f);
    fclose(f);
    return path;
}

char *gf_test_read_file(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = malloc((size_t)n + 1);
    if (buf && fread(buf, 1, (size_t)n, f) != (size_t)n) {
        free(buf);
        buf = NULL;
    }
    fclose(f);
    if (buf) {
        buf[n] = '\0';
        if (len) *len = (size_t)n;
    }
    return buf;
}

size_t gf_test_gzip(const char *src, const char *dst, size_t keep)
{
    size_t n;
    char *text = gf_test_read_file(src, &n);
    if (!text) return 0;
    gzFile g = gzopen(dst, "wb6");
    bool ok = g && (n == 0 || gzwrite(g, text, (unsigned)n) == (int)n);
    if (g && gzclose(g) != Z_OK) ok = false;
    free(text);
    if (!ok) return 0;
    size_t full;
    char *z = gf_test_read_file(dst, &full);
    if (!z) return 0;
    if (keep > 0 && keep < full) {
        FILE *f = fopen(dst, "wb");
        ok = f && fwrite(z, 1, keep, f) == keep;
        if (f) fclose(f);
    }
    free(z);
    return ok ? full : 0;
}

void gf_assert_near_(double a, double b, double tol, const char *ea, const char *eb, const char *file,
                     int line)
{
    if (!(a - b <= tol && b - a <= tol)) {
        print_error("%s = %.12g and %s = %.12g differ by %.3g > tolerance %.3g\n", ea, a, eb, b,
                       a > b ? a - b : b - a, tol);
        _fail(file, line);
    }
}

static int gf_check_leaks(void **state)
{
    (void)state;
    size_t left = gf_bytes_allocated();
    if (left != 0) {
        print_error("%zu bytes of granflow memory still allocated after the test\n", left);
        return -1;
    }
    return 0;
}

int gf_test_run(int argc, char **argv, const char *suite, const struct CMUnitTest *tests, size_t n)
{
    struct CMUnitTest *sel = calloc(n, sizeof *sel);
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        if (argc > 1 && strcmp(argv[1], tests[i].name) != 0) continue;
        sel[k] = tests[i];
        if (!sel[k].teardown_func) sel[k].teardown_func = gf_check_leaks;
        k++;
    }
    if (k == 0) {
        fprintf(stderr, "%s: no test named '%s'\n", suite, argc > 1 ? argv[1] : "");
        free(sel);
        return 1;
    }
    int rc = _cmocka_run_group_tests(suite, sel, k, NULL, NULL);
    free(sel);
    return rc;
}

bool gf_test_same_file(const char *a, const char *b)
{
    size_t na, nb;
    char *x = gf_test_read_file(a, &na), *y = gf_test_read_file(b, &nb);
    bool same = x && y && na == nb && memcmp(x, y, na) == 0;
    free(x);
    free(y);
    return same;
}

bool gf_test_same_snapshot(const char *d1, const char *d2, int k)
{
    char a[1024], b[1024];
    snprintf(a, sizeof a, "%s/snapshots/snap_%06d.dump", d1, k);
    snprintf(b, sizeof b, "%s/snapshots/snap_%06d.dump", d2, k);
    return gf_test_same_file(a, b);
}

gf_sim *gf_test_generated_sim(const gf_config *c)
{
    gf_packing pk = {0};
    assert_int_equal(gf_packing_generate(c, NULL, &pk), GF_OK);
    gf_sim *sim = NULL;
    assert_int_equal(gf_sim_create(c, &pk, &sim), GF_OK);
    gf_packing_free(&pk);
    return sim;
}

gf_config gf_test_silo_config(double width, int64_t particles, uint64_t seed)
{
    gf_config c = gf_config_default();
    c.container_width = width;
    c.packing_particles = particles;
    c.run_seed = seed;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    return c;
}

const gf_table *gf_test_table(const gf_measure_out *o, const char *name)
{
    for (size_t k = 0; k < o->ntables; k++)
        if (strcmp(o->tables[k].name, name) == 0) return &o->tables[k];
    fail_msg("no table %s", name);
    return NULL;
}

double gf_test_value(const gf_measure_out *o, const char *key)
{
    for (size_t k = 0; k < o->nvalues; k++)
        if (strcmp(o->values[k].key, key) == 0) return o->values[k].value;
    fail_msg("no value %s", key);
    return NAN;
}

gf_series gf_test_series(size_t nframes, double W, double D)
{
    gf_series s;
    memset(&s, 0, sizeof s);
    s.cfg = gf_config_default();
    s.cfg.container_width = W;
    s.cfg.container_depth = D;
    s.nframes = nframes;
    s.frames = GF_NEW(gf_frame, nframes);
    assert_non_null(s.frames);
    for (size_t k = 0; k < nframes; k++) s.frames[k].time = (double)k;
    return s;
}

gf_test_outcome gf_test_outcome_of(const gf_sim *sim)
{
    gf_test_outcome o = {.st = gf_sim_get_stats(sim), .shared_phases = gf_par_shared_phases(sim),
                         .prof = gf_sim_par_profile(sim)};
    assert_int_equal(gf_sim_particles(sim, &o.pk), GF_OK);
    const gf_exit *e = gf_sim_exits(sim, &o.nex);
    o.ex = malloc(sizeof *o.ex * (o.nex ? o.nex : 1));
    assert_non_null(o.ex);
    if (o.nex) memcpy(o.ex, e, sizeof *o.ex * o.nex);
    return o;
}

gf_test_outcome gf_test_run_outcome(gf_config c)
{
    gf_sim *sim = gf_test_generated_sim(&c);
    assert_int_equal(gf_sim_run(sim, c.run_duration, NULL), GF_OK);
    gf_test_outcome o = gf_test_outcome_of(sim);
    gf_sim_destroy(sim);
    return o;
}

void gf_test_same_outcome(const gf_test_outcome *a, const gf_test_outcome *b)
{
    assert_int_equal(a->pk.n, b->pk.n);
    assert_memory_equal(a->pk.id, b->pk.id, sizeof(int64_t) * a->pk.n);
    assert_memory_equal(a->pk.x, b->pk.x, sizeof(double) * a->pk.n);
    assert_memory_equal(a->pk.y, b->pk.y, sizeof(double) * a->pk.n);
    assert_memory_equal(a->pk.z, b->pk.z, sizeof(double) * a->pk.n);
    assert_int_equal(a->nex, b->nex);
    assert_memory_equal(a->ex, b->ex, sizeof(gf_exit) * a->nex);
    assert_int_equal(a->st.spot_moves, b->st.spot_moves);
    assert_int_equal(a->st.relax_calls, b->st.relax_calls);
    assert_int_equal(a->st.spots_deleted, b->st.spots_deleted);
    // The counters' floating-point sums are made block by block, in block order.
    assert_memory_equal(&a->st.spot_dz, &b->st.spot_dz, sizeof(double));
    assert_memory_equal(&a->st.relax_dz, &b->st.relax_dz, sizeof(double));
}

void gf_test_outcome_free(gf_test_outcome *o)
{
    gf_packing_free(&o->pk);
    free(o->ex);
}

void gf_test_resume_matches(const char *tag, gf_config whole, gf_config first, gf_config second, double stop_at)
{
    char dw[512], dp[512];
    assert_true(snprintf(dw, sizeof dw, "%s/%s_whole", gf_test_tmpdir(), tag) < (int)sizeof dw);
    assert_true(snprintf(dp, sizeof dp, "%s/%s_part", gf_test_tmpdir(), tag) < (int)sizeof dp);
    gf_run_opts o = {.dir = dw, .force = 1};
    assert_int_equal(gf_run_dir(&whole, &o, NULL), GF_OK);
    first.run_duration = stop_at;
    o.dir = dp;
    assert_int_equal(gf_run_dir(&first, &o, NULL), GF_OK);
    gf_run_opts r = {.dir = dp, .resume = 1, .force = 1};
    assert_int_equal(gf_run_dir(&second, &r, NULL), GF_OK);
    assert_true(gf_test_same_snapshot(dw, dp, 1));
    assert_true(gf_test_same_snapshot(dw, dp, 2));
}
