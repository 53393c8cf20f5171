// SPDX-License-Identifier: MIT
// Fuzz target: the reader of analysis/summary.json (gf_summary_read, over
// jansson), which `granflow analyze NAME` uses to keep the other
// measurements' numbers. What it read is written and read again: the second
// reading must succeed and give the same entries (a failure aborts). A file
// it refuses must come with a message naming the file.
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/summary.h"
#include "fuzz.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = gf_fuzz_file(".json", data, size);
    if (!path) return 0;
    gf_summary *a = calloc(2, sizeof *a);
    if (!a) return 0;
    gf_summary *b = a + 1;
    gf_status st = gf_summary_read(a, path);
    if (a->n > sizeof a->item / sizeof a->item[0]) abort();
    if (st != GF_OK && !strstr(gf_last_error(), path)) abort();
    // %.10g rounds a number within 1e-10 of DBL_MAX up past it, which no JSON
    // reader takes back; summary.json never holds one (they are measurements).
    int huge = 0;
    for (size_t k = 0; k < a->n; k++) huge |= !a->item[k].is_text && fabs(a->item[k].value) > 1e300;
    if (st == GF_OK && !huge && gf_summary_write(a, path) == GF_OK) {
        if (gf_summary_read(b, path) != GF_OK || b->n != a->n) abort();
        for (size_t k = 0; k < a->n; k++) {
            const gf_summary_item *x = &a->item[k], *y = &b->item[k];
            if (strcmp(x->key, y->key) != 0 || x->is_text != y->is_text) abort();
            if (x->is_text && strcmp(x->text, y->text) != 0) abort();
            // Numbers are written with 10 significant digits; not finite ones as null.
            if (!x->is_text && isfinite(x->value) && !(fabs(x->value - y->value) <= 1e-9 * fabs(x->value)))
                abort();
            if (!x->is_text && !isfinite(x->value) && !isnan(y->value)) abort();
        }
    }
    free(a);
    return 0;
}
