// SPDX-License-Identifier: MIT
// Shared test plumbing: cmocka main with a name filter (one CTest per case),
// temporary directories, and the allocation check every test ends with.
#ifndef GF_TEST_SUPPORT_H
#define GF_TEST_SUPPORT_H

#include <setjmp.h>
#include <stdarg.h>
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

/// Asserts |a - b| <= tol with a message showing both values and the tolerance.
#define gf_assert_near(a, b, tol) gf_assert_near_((a), (b), (tol), #a, #b, __FILE__, __LINE__)
void gf_assert_near_(double a, double b, double tol, const char *ea, const char *eb, const char *file,
                     int line);

#endif
