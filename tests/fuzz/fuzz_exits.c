// SPDX-License-Identifier: MIT
// Fuzz target: a run's exits.csv (gf_exits_read).
#include "core/alloc.h"
#include "fuzz.h"
#include "granflow/granflow.h"
#include "io/exits_read.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = gf_fuzz_file(".csv", data, size);
    if (!path) return 0;
    gf_exit *e = NULL;
    size_t n = 0;
    if (gf_exits_read(path, &e, &n) == GF_OK) GF_DELETE(e, n);
    return 0;
}
