// SPDX-License-Identifier: MIT
// Fuzz target: the reader of analysis/summary.json (gf_summary_read), which
// `granflow analyze --only NAME` uses to keep the other measurements'
// numbers. What it read is written and read again: the second reading must
// give the same entries (a failure aborts).
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/summary.h"
#include "fuzz.h"

// Whether the summary.json writer keeps this key as it is (it escapes
// backslashes and control characters, which the line reader does not undo).
static int gf_fuzz_plain_key(const char *key)
{
    for (; *key; key++)
        if (*key == '\\' || (unsigned char)*key < 0x20) return 0;
    return 1;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = gf_fuzz_file(".json", data, size);
    if (!path) return 0;
    gf_summary *a = calloc(2, sizeof *a);
    if (!a) return 0;
    gf_summary *b = a + 1;
    gf_summary_read(a, path);
    if (a->n > sizeof a->item / sizeof a->item[0]) abort();
    if (gf_summary_write(a, path) == GF_OK) {
        gf_summary_read(b, path);
        size_t plain = 0;
        for (size_t k = 0; k < a->n; k++) plain += gf_fuzz_plain_key(a->item[k].key);
        if (plain == a->n) {
            if (b->n != a->n) abort();
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
    }
    free(a);
    return 0;
}
