// SPDX-License-Identifier: MIT
// The packing readers' harness, shared by fuzz_packing_{dump,xyz,csv}.c:
// the input as a file of the given suffix through gf_packing_read and, for
// dumps, the every-frame reader; an input starting with the gzip magic bytes
// is named SUFFIX.gz, so the readers' gzip path is fuzzed where they have one.
#ifndef GF_TESTS_FUZZ_PACKING_H
#define GF_TESTS_FUZZ_PACKING_H

#include <string.h>

#include "fuzz.h"
#include "granflow/granflow.h"
#include "io/packing_frames.h"

static gf_status gf_fuzz_frame(void *ctx, const gf_packing_frame *f, gf_packing *pk)
{
    (void)ctx;
    (void)f;
    (void)pk;
    return GF_OK;
}

static int gf_fuzz_packing(const char *suffix, int frames, const uint8_t *data, size_t size)
{
    char name[32];
    bool gz = size >= 2 && data[0] == 0x1f && data[1] == 0x8b;
    snprintf(name, sizeof name, "%s%s", suffix, gz ? ".gz" : "");
    const char *path = gf_fuzz_file(name, data, size);
    if (!path) return 0;
    gf_packing pk = {0};
    if (gf_packing_read(path, GF_FORMAT_AUTO, &pk) == GF_OK) {
        gf_config cfg = gf_config_default();
        gf_packing_check(&pk, &cfg);
        gf_packing_min_distance(&pk);
    }
    gf_packing_free(&pk);
    if (frames) gf_packing_read_frames(path, gf_fuzz_frame, NULL);
    return 0;
}

#endif
