// SPDX-License-Identifier: MIT
// Fuzz target: one frame of a dump as Python's read_snapshot reads it
// (gf_snapshot_read: the first and the last frame, radius and pass columns,
// gzip), every array copied out.
#include <stdlib.h>

#include "fuzz.h"
#include "granflow/granflow.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = gf_fuzz_file(".dump", data, size);
    if (!path) return 0;
    for (long frame = -1; frame <= 0; frame++) {
        gf_snapshot *s;
        if (gf_snapshot_read(path, frame, &s) != GF_OK) continue;
        size_t n = gf_snapshot_count(s);
        int64_t *id = malloc(sizeof *id * (n + 1));
        int32_t *type = malloc(sizeof *type * (n + 1)), *pass = malloc(sizeof *pass * (n + 1));
        double *xyz = malloc(sizeof *xyz * (3 * n + 1)), *r = malloc(sizeof *r * (n + 1));
        double lo[3], hi[3];
        if (id && type && pass && xyz && r) {
            size_t got;
            if (gf_snapshot_copy(s, id, type, xyz, r, pass, n, &got) != GF_OK || got != n) abort();
            for (size_t i = 0; i < n; i++)
                if (pass[i] < 1 || !(r[i] > 0)) abort(); // what the reader promises
        }
        (void)gf_snapshot_box(s, lo, hi);
        (void)gf_snapshot_time(s);
        (void)gf_snapshot_step(s);
        (void)gf_snapshot_frames(s);
        free(id);
        free(type);
        free(pass);
        free(xyz);
        free(r);
        gf_snapshot_destroy(s);
    }
    return 0;
}
