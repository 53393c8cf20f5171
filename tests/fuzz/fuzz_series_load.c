// SPDX-License-Identifier: MIT
// Fuzz target: a run directory as `granflow analyze` and `granflow dem
// analyze` load it (gf_dem_series_load over gf_series_load: the dumps of
// DIR/snapshots or DIR, DIR/config.ini, DIR/exits.csv, the box moved to
// x = y = 0, layer tags, packing.types and the particles below the base).
// The input holds the files: each starts with a line `=== NAME` (NAME of
// letters, digits, '.', '_', '-', possibly under `snapshots/`), the lines
// after it being its text; lines of a part named `set` are --set overrides.
// Frames without ITEM: TIME are 0.5 tau per TIMESTEP.
#include <stdlib.h>
#include <string.h>

#include "fuzz.h"
#include "granflow/granflow.h"

enum { GF_FUZZ_MAXSETS = 8 };

// Whether `name` is a file name the harness makes (no "..", one optional snapshots/).
static int gf_fuzz_name_ok(const char *name)
{
    if (!strncmp(name, "snapshots/", 10)) name += 10;
    if (!*name || name[0] == '.') return 0;
    for (const char *c = name; *c; c++)
        if (!((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') || *c == '.' ||
              *c == '_' || *c == '-'))
            return 0;
    return strlen(name) < 64;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *dir = gf_fuzz_dir();
    if (!dir) return 0;
    char *text = gf_fuzz_string(data, size);
    const char *sets[GF_FUZZ_MAXSETS];
    size_t nsets = 0;
    // Parts: from one `=== NAME` line to the next.
    char *p = strncmp(text, "=== ", 4) == 0 ? text : strstr(text, "\n=== ");
    if (p && *p == '\n') p++;
    while (p) {
        char *name = p + 4, *eol = strchr(name, '\n');
        char *start = eol ? eol + 1 : name + strlen(name);
        if (eol) *eol = '\0';
        char *end = eol ? strstr(start, "\n=== ") : NULL; // the newline that ends the part
        size_t len = end ? (size_t)(end - start) + 1 : strlen(start);
        p = end ? end + 1 : NULL;
        if (end) *end = '\0';
        if (!strcmp(name, "set")) {
            for (char *l = start, *nx; l && nsets < GF_FUZZ_MAXSETS; l = nx) {
                nx = strchr(l, '\n');
                if (nx) *nx++ = '\0';
                if (*l) sets[nsets++] = l;
            }
        } else if (gf_fuzz_name_ok(name)) {
            if (end) *end = '\n';
            gf_fuzz_dir_file(dir, name, (const uint8_t *)start, len);
            if (end) *end = '\0';
        }
    }
    gf_dem_source src = {.dump_dt = 0.5, .sets = sets, .nsets = nsets};
    gf_series s;
    gf_dem_load_report rep;
    if (gf_dem_series_load(dir, &src, &s, &rep) == GF_OK) {
        if (s.nframes == 0 || s.n_initial != s.frames[0].pk.n) abort();
        for (size_t k = 1; k < s.nframes; k++)
            if (!(s.frames[k].time > s.frames[k - 1].time)) abort(); // sorted, no two at one time
        gf_series_free(&s);
    }
    free(text);
    return 0;
}
