// SPDX-License-Identifier: MIT
// Checkpoint compatibility (issue 26): a checkpoint whose stored
// configuration lacks keys this version has (as every checkpoint of today
// will the day a key is added) resumes when those keys are at their defaults
// and is refused, naming the key, when they are not; it never crashes.
// Checkpoints of this version are made older by removing setting lines from
// the end, the middle and the start of their stored text, a whole section,
// every single key in turn and every tail. (tests/cli/checkpoint_compat.sh
// resumes a checkpoint kept in tests/data through the CLI.)
#include "support.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "granflow/granflow.h"

enum { HEAD = 8 + 4 + 4 + 8 + 4 };

/// A checkpoint file in memory, its stored configuration text as lines.
typedef struct ckpt {
    char *data;
    size_t len;
    char *text;     ///< the stored text (NUL-terminated copy)
    size_t tlen;
    char *line[512]; ///< its lines (pointers into text, NUL-terminated in place)
    size_t nline;
} ckpt;

// The checkpoint of a small silo (width 10, 300 particles, seed 3: three keys
// off their defaults), stepped a little, read into *k.
static void ckpt_make(ckpt *k, gf_config *c)
{
    *c = gf_test_silo_config(10, 300, 3);
    gf_sim *sim = gf_test_generated_sim(c);
    for (int i = 0; i < 50; i++) assert_int_equal(gf_sim_step(sim), GF_OK);
    char path[600];
    snprintf(path, sizeof path, "%s/compat.bin", gf_test_tmpdir());
    assert_int_equal(gf_sim_save(sim, path), GF_OK);
    gf_sim_destroy(sim);
    k->data = gf_test_read_file(path, &k->len);
    assert_non_null(k->data);
    uint64_t plen;
    memcpy(&plen, k->data + HEAD, 8);
    assert_true(plen < k->len - HEAD);
    k->tlen = (size_t)plen;
    k->text = malloc(k->tlen + 1);
    memcpy(k->text, k->data + HEAD + 8, k->tlen);
    k->text[k->tlen] = '\0';
    k->nline = 0;
    for (char *p = k->text; *p && k->nline < 512;) {
        k->line[k->nline++] = p;
        char *nl = strchr(p, '\n');
        if (!nl) break;
        *nl = '\0';
        p = nl + 1;
    }
    assert_true(k->nline > 100 && k->nline < 512);
}

static void ckpt_free(ckpt *k)
{
    free(k->data);
    free(k->text);
}

static bool is_setting(const char *l) { return l[0] && l[0] != ';' && l[0] != '#' && l[0] != '['; }

// Writes the checkpoint with the stored text made of the lines whose keep[]
// is true (plus `extra`, appended), the payload size and CRC-32 redone, to a
// file; returns its path (static storage).
static const char *ckpt_write(const ckpt *k, const bool *keep, const char *extra)
{
    size_t cap = k->tlen + strlen(extra) + 2, n = 0;
    char *t = malloc(cap);
    for (size_t i = 0; i < k->nline; i++)
        if (keep[i]) n += (size_t)sprintf(t + n, "%s\n", k->line[i]);
    n += (size_t)sprintf(t + n, "%s", extra);
    const size_t rest = k->len - HEAD - 8 - k->tlen; // the state after the text
    const size_t size = 8 + n + rest;
    char *out = malloc(HEAD + size);
    memcpy(out, k->data, 16);
    uint64_t size64 = size, n64 = n;
    memcpy(out + 16, &size64, 8);
    memcpy(out + HEAD, &n64, 8);
    memcpy(out + HEAD + 8, t, n);
    memcpy(out + HEAD + 8 + n, k->data + HEAD + 8 + k->tlen, rest);
    uint32_t crc = (uint32_t)crc32(crc32(0L, Z_NULL, 0), (const Bytef *)out + HEAD, (uInt)size);
    memcpy(out + 24, &crc, 4);
    static char path[600];
    snprintf(path, sizeof path, "%s/compat-older.bin", gf_test_tmpdir());
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(out, 1, HEAD + size, f), HEAD + size);
    assert_int_equal(fclose(f), 0);
    free(t);
    free(out);
    return path;
}

// Loads `path` with c: GF_OK (the sim stepped once and freed) or the status.
static gf_status ckpt_load(const gf_config *c, const char *path)
{
    gf_sim *sim = NULL;
    gf_status st = gf_sim_load(c, path, &sim);
    if (st == GF_OK) {
        assert_int_equal(gf_sim_step(sim), GF_OK);
        gf_sim_destroy(sim);
    }
    return st;
}

// keep[] for the text with `count` settings removed from the i-th setting on
// (their comment lines with them, so the text reads as an older version's).
static void drop_settings(const ckpt *k, bool *keep, size_t first, size_t count)
{
    size_t s = 0;
    for (size_t i = 0; i < k->nline; i++) {
        keep[i] = true;
        if (!is_setting(k->line[i])) continue;
        if (s >= first && s < first + count) {
            keep[i] = false;
            for (size_t j = i; j > 0 && k->line[j - 1][0] == ';'; j--) keep[j - 1] = false;
        }
        s++;
    }
}

static size_t count_settings(const ckpt *k)
{
    size_t s = 0;
    for (size_t i = 0; i < k->nline; i++) s += is_setting(k->line[i]);
    return s;
}

// The case the checkpoint fuzzer found (rc 139 on resume): the stored text
// ends before this version's last keys (dem.settle_ke, dem.mpi_ranks).
static void keys_dropped_from_the_end_resume(void **state)
{
    (void)state;
    gf_config c;
    ckpt k;
    ckpt_make(&k, &c);
    bool keep[512];
    size_t n = count_settings(&k);
    for (size_t d = 1; d <= 3; d++) {
        drop_settings(&k, keep, n - d, d);
        assert_int_equal(ckpt_load(&c, ckpt_write(&k, keep, "")), GF_OK);
    }
    ckpt_free(&k);
}

// Keys missing from the middle (here spot.bias_exponent and spot.weighting)
// and a whole section missing from the end, its header too.
static void keys_dropped_from_the_middle_resume(void **state)
{
    (void)state;
    gf_config c;
    ckpt k;
    ckpt_make(&k, &c);
    bool keep[512];
    size_t first = 0;
    for (size_t i = 0, s = 0; i < k.nline; i++) {
        if (!is_setting(k.line[i])) continue;
        if (!strncmp(k.line[i], "bias_exponent =", 15)) first = s;
        s++;
    }
    assert_true(first > 0);
    drop_settings(&k, keep, first, 2);
    assert_int_equal(ckpt_load(&c, ckpt_write(&k, keep, "")), GF_OK);
    // no [dem] section at all
    bool in_dem = false;
    for (size_t i = 0; i < k.nline; i++) {
        if (k.line[i][0] == '[') in_dem = !strcmp(k.line[i], "[dem]");
        keep[i] = !in_dem;
    }
    assert_int_equal(ckpt_load(&c, ckpt_write(&k, keep, "")), GF_OK);
    ckpt_free(&k);
}

// Keys missing from the start: container.width is 10 here, not its default,
// so the older version that made the checkpoint ran another silo: refused,
// naming the key and both values. With the default width it resumes.
static void keys_dropped_from_the_start_are_named(void **state)
{
    (void)state;
    gf_config c;
    ckpt k;
    ckpt_make(&k, &c);
    bool keep[512];
    drop_settings(&k, keep, 0, 1);
    assert_int_equal(ckpt_load(&c, ckpt_write(&k, keep, "")), GF_ERR_PARAM);
    const char *e = gf_last_error();
    assert_non_null(strstr(e, "container.width differs"));
    assert_non_null(strstr(e, "the default, 50)"));
    assert_non_null(strstr(e, "here it is 10"));
    // Keys at their defaults missing from the start: depth, orifice_shape.
    for (size_t i = 0; i < k.nline; i++) keep[i] = true;
    for (size_t i = 0, s = 0; i < k.nline; i++) {
        if (!is_setting(k.line[i])) continue;
        if (s == 1 || s == 2) {
            keep[i] = false;
            keep[i - 1] = k.line[i - 1][0] != ';';
        }
        s++;
    }
    assert_int_equal(ckpt_load(&c, ckpt_write(&k, keep, "")), GF_OK);
    // an empty stored text: the first key off its default is named
    for (size_t i = 0; i < k.nline; i++) keep[i] = false;
    assert_int_equal(ckpt_load(&c, ckpt_write(&k, keep, "")), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "container.width differs"));
    ckpt_free(&k);
}

// Every single key removed in turn, and every tail of the text: resumed, or
// (for the three keys off their defaults) refused naming the key.
static void every_key_and_every_tail_dropped(void **state)
{
    (void)state;
    gf_config c;
    ckpt k;
    ckpt_make(&k, &c);
    bool keep[512];
    const size_t n = count_settings(&k);
    const char *named[] = {"container.width", "packing.particles", "run.seed"};
    for (size_t s = 0; s < n; s++) {
        drop_settings(&k, keep, s, 1);
        gf_status st = ckpt_load(&c, ckpt_write(&k, keep, ""));
        if (st != GF_OK) {
            assert_int_equal(st, GF_ERR_PARAM);
            bool known = false;
            for (size_t j = 0; j < 3; j++) known = known || strstr(gf_last_error(), named[j]) != NULL;
            if (!known) fail_msg("setting %zu dropped: %s", s, gf_last_error());
        }
    }
    for (size_t s = 0; s < n; s++) { // the settings from s on dropped
        drop_settings(&k, keep, s, n - s);
        gf_status st = ckpt_load(&c, ckpt_write(&k, keep, ""));
        assert_true(st == GF_OK || st == GF_ERR_PARAM);
    }
    ckpt_free(&k);
}

// A key this version does not know (a newer version's checkpoint) and a key
// listed twice are refused by name; so is a value that differs.
static void unknown_and_repeated_keys_are_named(void **state)
{
    (void)state;
    gf_config c;
    ckpt k;
    ckpt_make(&k, &c);
    bool keep[512];
    for (size_t i = 0; i < k.nline; i++) keep[i] = true;
    assert_int_equal(ckpt_load(&c, ckpt_write(&k, keep, "")), GF_OK);
    assert_int_equal(ckpt_load(&c, ckpt_write(&k, keep, "new_key = 1\n")), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "has the key dem.new_key, which this granflow does not know"));
    assert_int_equal(ckpt_load(&c, ckpt_write(&k, keep, "mpi_ranks = 0\n")), GF_ERR_FORMAT);
    assert_non_null(strstr(gf_last_error(), "lists dem.mpi_ranks twice"));
    assert_int_equal(ckpt_load(&c, ckpt_write(&k, keep, "[nosection]\n")), GF_OK); // a header alone changes nothing
    c.spot_radius = 2.5;
    assert_int_equal(ckpt_load(&c, ckpt_write(&k, keep, "")), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "spot.radius differs from the configuration"));
    ckpt_free(&k);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(keys_dropped_from_the_end_resume),
    cmocka_unit_test(keys_dropped_from_the_middle_resume),
    cmocka_unit_test(keys_dropped_from_the_start_are_named),
    cmocka_unit_test(every_key_and_every_tail_dropped),
    cmocka_unit_test(unknown_and_repeated_keys_are_named),
};

GF_TEST_MAIN("checkpoint_compat", tests)
