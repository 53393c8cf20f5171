// SPDX-License-Identifier: MIT
// Shared pieces of the fuzz harnesses (tests/fuzz/fuzz_*.c): each defines
// LLVMFuzzerTestOneInput for one parser. Built with libFuzzer by clang
// (GF_FUZZ=ON, `make fuzz`), or with replay_main.c by any compiler, which
// runs the saved inputs (seeds/ and regressions/) as a CTest.
#ifndef GF_TESTS_FUZZ_H
#define GF_TESTS_FUZZ_H

#include <stddef.h>
#include <stdint.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/// Writes data to a per-process scratch file whose name ends in `suffix`
/// (".dump", ".csv", ...: the readers pick the format by it) and returns its
/// path, or NULL. The parsers read files, so the harnesses hand them one.
const char *gf_fuzz_file(const char *suffix, const uint8_t *data, size_t size);

/// A per-process scratch directory, emptied (its files and those of its
/// subdirectories; harnesses make no deeper ones), or NULL.
const char *gf_fuzz_dir(void);

/// Writes data to the file `name` of directory `dir`, making a subdirectory
/// named by a '/' in `name` (one level); 0 on success.
int gf_fuzz_dir_file(const char *dir, const char *name, const uint8_t *data, size_t size);

/// data as a NUL-terminated string (malloc'ed; free it).
char *gf_fuzz_string(const uint8_t *data, size_t size);

#endif
