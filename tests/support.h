// SPDX-License-Identifier: MIT
// Shared test plumbing: cmocka main with a name filter (one CTest per case),
// temporary directories, and the allocation check every test ends with.
#ifndef GF_TEST_SUPPORT_H
#define GF_TEST_SUPPORT_H

#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "granflow/core.h"

/// Runs `tests` (all, or only the one named by argv[1]). Each test is wrapped
/// so that it fails if granflow memory is still allocated when it returns.
int gf_test_run(int argc, char **argv, const char *suite, const struct CMUnitTest *tests, size_t n);

#define GF_TEST_MAIN(suite, tests) \
    int main(int argc, char **argv) { return gf_test_run(argc, argv, suite, tests, sizeof(tests) / sizeof(tests[0])); }

/// A fresh empty directory under $TMPDIR (or /tmp) for this process; the
/// returned path is static storage. Removed recursively at exit.
const char *gf_test_tmpdir(void);

/// Writes `text` into file `dir/name` and returns the full path (static storage,
/// overwritten by the next call).
const char *gf_test_write_file(const char *dir, const char *name, const char *text);

/// Reads a whole file into a malloc'd NUL-terminated buffer (NULL on failure).
char *gf_test_read_file(const char *path, size_t *len);

/// Compresses file `src` with gzip into `dst` (zlib's gzwrite), keeping only
/// the first `keep` bytes of the compressed file when keep > 0 (a truncated
/// .gz). Returns the compressed size before truncation, 0 on failure.
size_t gf_test_gzip(const char *src, const char *dst, size_t keep);

/// True when both files exist and hold the same bytes.
bool gf_test_same_file(const char *a, const char *b);

/// True when snapshot k (snapshots/snap_%06d.dump) of run directories d1 and d2 is the same bytes.
bool gf_test_same_snapshot(const char *d1, const char *d2, int k);

struct gf_sim;
struct gf_config;
/// Runs `whole` straight through into TMP/TAG_whole, then `first` stopped at
/// `stop_at` tau into TMP/TAG_part and `second` resuming it (the same keys
/// on other thread counts), and asserts snapshots 1 and 2 of both are the
/// same bytes: a resume under another thread count changes nothing.
void gf_test_resume_matches(const char *tag, struct gf_config whole, struct gf_config first,
                            struct gf_config second, double stop_at);

/// The papers' silo config with another width, particle count and seed (validated).
struct gf_config gf_test_silo_config(double width, int64_t particles, uint64_t seed);

/// A simulation of the packing gf_packing_generate builds for `c` (asserts success).
struct gf_sim *gf_test_generated_sim(const struct gf_config *c);

struct gf_series;
/// A series of nframes empty frames at times 0, 1, 2, ... in a W x D container
/// (the papers' silo config otherwise); release with gf_series_free.
struct gf_series gf_test_series(size_t nframes, double W, double D);

struct gf_measure_out;
struct gf_table;
/// The table of a measurement's output by name (fails the test when absent).
const struct gf_table *gf_test_table(const struct gf_measure_out *o, const char *name);
/// A headline value of a measurement's output by key (fails the test when absent).
double gf_test_value(const struct gf_measure_out *o, const char *key);

/// Asserts |a - b| <= tol with a message showing both values and the tolerance.
#define gf_assert_near(a, b, tol) gf_assert_near_((a), (b), (tol), #a, #b, __FILE__, __LINE__)
void gf_assert_near_(double a, double b, double tol, const char *ea, const char *eb, const char *file,
                     int line);

#endif
