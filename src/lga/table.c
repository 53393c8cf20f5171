// SPDX-License-Identifier: MIT
// The collision table (LGA paper Sec. 2, Fig. 3): built once per engine.
#include "lga/table.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "lga/lattice.h"

// Bit mask of a state after mapping every velocity through map[e].
static uint16_t gf_lga_table_map(uint16_t s, const int map[13])
{
    uint16_t out = 0;
    for (int e = 0; e < 13; e++)
        if (s & (1u << e)) out |= (uint16_t)(1u << map[e]);
    return out;
}

static int gf_lga_table_cmp(const void *pa, const void *pb)
{
    uint32_t x = *(const uint32_t *)pa, y = *(const uint32_t *)pb;
    return x < y ? -1 : x > y;
}

// Makes room for n more states in t->list.
static bool gf_lga_table_grow(gf_lga_table *t, size_t *cap, size_t n)
{
    if (t->nlist + n <= *cap) return true;
    size_t ncap = *cap ? *cap : 16384;
    while (ncap < t->nlist + n) ncap *= 2;
    uint16_t *p = gf_realloc(t->list, *cap * sizeof *p, ncap * sizeof *p);
    if (!p) return false;
    t->list = p;
    *cap = ncap;
    return true;
}

// Appends n states from `src` (outside the list); returns the start index or -1.
static long gf_lga_table_append(gf_lga_table *t, size_t *cap, const uint16_t *src, size_t n)
{
    if (!gf_lga_table_grow(t, cap, n)) return -1;
    long at = (long)t->nlist;
    memcpy(t->list + t->nlist, src, n * sizeof *src);
    t->nlist += n;
    return at;
}

// Appends a copy of list[from .. from + n); returns the start index or -1.
static long gf_lga_table_append_range(gf_lga_table *t, size_t *cap, size_t from, size_t n)
{
    if (!gf_lga_table_grow(t, cap, n)) return -1;
    long at = (long)t->nlist;
    memmove(t->list + t->nlist, t->list + from, n * sizeof *t->list);
    t->nlist += n;
    return at;
}

// One class: the states of one set with the same count, energy and momentum.
typedef struct gf_lga_class {
    uint32_t start, len;
    int a, b, e;
    double norm; ///< |momentum| x 2
} gf_lga_class;

#define GF_LGA_MAX_CLASSES 1024
#define GF_LGA_MAX_TIES 64

// Fills start/len of (set, m) for every target and cap. The set's states,
// sorted by (count, energy, momentum), are at list[base .. base + n).
static gf_status gf_lga_table_targets(gf_lga_table *t, size_t *cap, int set, int m, size_t base, size_t n,
                                      gf_lga_class *cls)
{
    size_t ncls = 0;
    for (size_t i = 0; i < n;) {
        uint16_t s = t->list[base + i];
        if (t->count[s] != m) {
            i++;
            continue;
        }
        size_t j = i;
        while (j < n && t->count[t->list[base + j]] == m && t->energy[t->list[base + j]] == t->energy[s] &&
               t->ma[t->list[base + j]] == t->ma[s] && t->mb[t->list[base + j]] == t->mb[s])
            j++;
        GF_ASSERT(ncls < GF_LGA_MAX_CLASSES);
        cls[ncls++] = (gf_lga_class){(uint32_t)(base + i), (uint32_t)(j - i), t->ma[s], t->mb[s], t->energy[s],
                                     sqrt(3.0 * t->ma[s] * t->ma[s] + (double)t->mb[s] * t->mb[s])};
        i = j;
    }
    for (int a = -GF_LGA_AMAX; a <= GF_LGA_AMAX; a++)
        for (int b = -GF_LGA_BMAX; b <= GF_LGA_BMAX; b++) {
            int key = gf_lga_table_key(a, b);
            uint32_t *start = t->start[set][m][key];
            uint16_t *len = t->len[set][m][key];
            memset(len, 0, sizeof t->len[0][0][0]);
            if (ncls == 0) continue;
            double tn = sqrt(3.0 * a * a + (double)b * b);
            long exact = -1;                  // the exact-momentum class with the most energy so far
            size_t ties[GF_LGA_MAX_TIES], nties = 0;
            long best_d = -1;
            double best_cos = 0;
            int best_e = -1;
            bool changed = false;
            uint32_t last_start = 0;
            uint16_t last_len = 0;
            size_t c = 0;
            int first_cap = -1;
            for (int e = 0; e <= GF_LGA_EMAX; e++) {
                // admit the classes of energy e (classes are in ascending energy)
                for (; c < ncls && cls[c].e == e; c++) {
                    if (cls[c].a == a && cls[c].b == b) exact = (long)c;
                    long da = cls[c].a - a, db = cls[c].b - b;
                    long d = 3 * da * da + db * db;
                    if (best_d >= 0 && d > best_d) continue; // farther than the best: out
                    double pn = cls[c].norm;
                    double cosv = tn > 0 && pn > 0 ? (3.0 * a * cls[c].a + (double)b * cls[c].b) / (tn * pn) : 0.0;
                    int better = best_d < 0 || d < best_d ? 1 : d > best_d ? -1
                               : cosv > best_cos + 1e-9 ? 1 : cosv < best_cos - 1e-9 ? -1
                               : cls[c].e > best_e ? 1 : cls[c].e < best_e ? -1 : 0;
                    if (better > 0) {
                        best_d = d;
                        best_cos = cosv;
                        best_e = cls[c].e;
                        nties = 0;
                    }
                    if (better >= 0 && nties < GF_LGA_MAX_TIES) {
                        ties[nties++] = c;
                        changed = true;
                    }
                }
                if (c == 0) continue; // no state of m particles this cheap yet
                if (first_cap < 0) first_cap = e;
                if (exact >= 0) {
                    start[e] = cls[exact].start;
                    len[e] = (uint16_t)cls[exact].len;
                    continue;
                }
                if (nties == 1) {
                    start[e] = cls[ties[0]].start;
                    len[e] = (uint16_t)cls[ties[0]].len;
                    continue;
                }
                if (changed) {
                    // several classes tie: their states, concatenated, at the list's end
                    long at = -1;
                    size_t total = 0;
                    for (size_t k = 0; k < nties; k++) {
                        long p = gf_lga_table_append_range(t, cap, cls[ties[k]].start, cls[ties[k]].len);
                        if (p < 0) return gf_error_set(GF_ERR_NOMEM, "out of memory (LGA collision table)");
                        if (at < 0) at = p;
                        total += cls[ties[k]].len;
                    }
                    GF_ASSERT(total < 65536);
                    last_start = (uint32_t)at;
                    last_len = (uint16_t)total;
                    changed = false;
                }
                start[e] = last_start;
                len[e] = last_len;
            }
            // caps below the cheapest state: use the cheapest
            for (int e = 0; e < first_cap; e++) {
                start[e] = start[first_cap];
                len[e] = len[first_cap];
            }
        }
    return GF_OK;
}

gf_status gf_lga_table_create(gf_lga_table **out)
{
    *out = NULL;
    gf_lga_table *t = gf_alloc(sizeof *t);
    if (!t) return gf_error_set(GF_ERR_NOMEM, "out of memory (LGA collision table)");
    for (int s = 0; s < GF_LGA_STATES; s++) {
        int a = 0, b = 0;
        for (int e = 1; e < 13; e++)
            if (s & (1 << e)) {
                a += gf_lga_da[e];
                b += gf_lga_db[e];
            }
        t->count[s] = (uint8_t)__builtin_popcount((unsigned)s);
        t->energy[s] = (uint8_t)(__builtin_popcount((unsigned)s & 0x7Eu) + 3 * __builtin_popcount((unsigned)s & 0x1F80u));
        t->ma[s] = (int8_t)a;
        t->mb[s] = (int8_t)b;
        t->reverse[s] = gf_lga_table_map((uint16_t)s, gf_lga_opp);
    }

    // The two sets, each sorted by (count, energy, momentum): the classes are runs.
    size_t cap = 0;
    gf_status st = GF_OK;
    uint32_t *keys = gf_alloc(GF_LGA_STATES * sizeof *keys);
    uint16_t *all = gf_alloc(GF_LGA_STATES * sizeof *all);
    gf_lga_class *cls = gf_alloc(GF_LGA_MAX_CLASSES * sizeof *cls);
    if (!all || !keys || !cls) st = gf_error_set(GF_ERR_NOMEM, "out of memory (LGA collision table)");
    size_t base[2] = {0, 0}, n[2] = {0, 0};
    for (int set = 0; st == GF_OK && set < 2; set++) {
        size_t k = 0;
        for (int s = 0; s < GF_LGA_STATES; s++)
            if (set == GF_LGA_SET_ALL || !(s & 1))
                keys[k++] = ((uint32_t)(((t->count[s] * 32 + t->energy[s]) * 32 + t->ma[s] + 16) * 32 + t->mb[s] + 16) << 13) |
                            (uint32_t)s;
        qsort(keys, k, sizeof *keys, gf_lga_table_cmp);
        for (size_t i = 0; i < k; i++) all[i] = (uint16_t)(keys[i] & 0x1FFFu);
        long at = gf_lga_table_append(t, &cap, all, k);
        if (at < 0) st = gf_error_set(GF_ERR_NOMEM, "out of memory (LGA collision table)");
        base[set] = (size_t)at;
        n[set] = k;
    }
    if (all) gf_free(all, GF_LGA_STATES * sizeof *all);
    if (keys) gf_free(keys, GF_LGA_STATES * sizeof *keys);
    for (int set = 0; st == GF_OK && set < 2; set++)
        for (int m = 0; st == GF_OK && m < 14; m++) st = gf_lga_table_targets(t, &cap, set, m, base[set], n[set], cls);
    if (cls) gf_free(cls, GF_LGA_MAX_CLASSES * sizeof *cls);
    if (st == GF_OK && cap > t->nlist) {
        // Trim to size so that destroy knows the exact allocation.
        uint16_t *p = gf_realloc(t->list, cap * sizeof *p, t->nlist * sizeof *p);
        if (p) {
            t->list = p;
            cap = t->nlist;
        }
    }
    if (st != GF_OK || cap != t->nlist) {
        if (t->list) gf_free(t->list, cap * sizeof *t->list);
        gf_free(t, sizeof *t);
        return st != GF_OK ? st : gf_error_set(GF_ERR_NOMEM, "out of memory (LGA collision table)");
    }
    *out = t;
    return GF_OK;
}

void gf_lga_table_destroy(gf_lga_table *t)
{
    if (!t) return;
    if (t->list) gf_free(t->list, t->nlist * sizeof *t->list);
    gf_free(t, sizeof *t);
}
