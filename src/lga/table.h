// SPDX-License-Identifier: MIT
// Internal: the precomputed collision table of the LGA (paper Sec. 2, Fig. 3):
// mass, momentum and kinetic energy of every site state, and for every
// (particle count, target momentum, energy cap) the outgoing states to choose from.
#ifndef GF_LGA_TABLE_H
#define GF_LGA_TABLE_H

#include <stddef.h>
#include <stdint.h>

#include "granflow/core.h"

/// Number of site states: 13 Boolean velocities.
#define GF_LGA_STATES 8192
/// Target momenta kept in the table, half units: a in [-8, 8], b in [-14, 14]
/// (every sum of distinct velocities, plus gravity, lies inside).
#define GF_LGA_AMAX 8
#define GF_LGA_BMAX 14
#define GF_LGA_NA (2 * GF_LGA_AMAX + 1)
#define GF_LGA_NB (2 * GF_LGA_BMAX + 1)
/// Kinetic energy in units of |v1|^2: a nearest mover 1, a second-nearest 3; at most 6 + 18.
#define GF_LGA_EMAX 24

/// The two sets outgoing particles are drawn from.
enum {
    GF_LGA_SET_ALL = 0,    ///< any of the 13 states, the rest state v0 included
    GF_LGA_SET_MOVING = 1, ///< v1..v12 only (v0 is taken by a particle brought to rest)
};

typedef struct gf_lga_table {
    uint8_t count[GF_LGA_STATES];       ///< particles in the state
    uint8_t energy[GF_LGA_STATES];      ///< kinetic energy of the state
    int8_t ma[GF_LGA_STATES];           ///< momentum, x in units of sqrt(3)/2
    int8_t mb[GF_LGA_STATES];           ///< momentum, y in units of 1/2
    uint16_t reverse[GF_LGA_STATES];    ///< every velocity reversed (v_e -> -v_e)
    /// Candidates for (set, m, target, cap): list[start .. start + len). Among
    /// the states of m particles from the set with energy <= cap (or, if there
    /// is none, the least energy possible): the one whose momentum equals the
    /// target with the most energy; when no momentum equals it, those nearest
    /// to it, then closest in direction, then with the most energy.
    uint32_t start[2][14][GF_LGA_NA * GF_LGA_NB][GF_LGA_EMAX + 1];
    uint16_t len[2][14][GF_LGA_NA * GF_LGA_NB][GF_LGA_EMAX + 1];
    uint16_t *list;
    size_t nlist;
} gf_lga_table;

/// Builds the table (a few milliseconds).
gf_status gf_lga_table_create(gf_lga_table **out);

/// Frees it (NULL is fine).
void gf_lga_table_destroy(gf_lga_table *t);

/// Key of a target momentum, clamped into the table's range.
static inline int gf_lga_table_key(int a, int b)
{
    a = a < -GF_LGA_AMAX ? -GF_LGA_AMAX : a > GF_LGA_AMAX ? GF_LGA_AMAX : a;
    b = b < -GF_LGA_BMAX ? -GF_LGA_BMAX : b > GF_LGA_BMAX ? GF_LGA_BMAX : b;
    return (a + GF_LGA_AMAX) * GF_LGA_NB + (b + GF_LGA_BMAX);
}

/// One outgoing state of m particles from `set` for target momentum (a, b)
/// and energy cap `cap`, chosen by the 32-bit uniform u (m <= 13, or 12 for
/// GF_LGA_SET_MOVING).
static inline uint16_t gf_lga_table_pick(const gf_lga_table *t, int set, int m, int a, int b, int cap, uint64_t u)
{
    int key = gf_lga_table_key(a, b);
    cap = cap < 0 ? 0 : cap > GF_LGA_EMAX ? GF_LGA_EMAX : cap;
    uint64_t len = t->len[set][m][key][cap];
    return t->list[t->start[set][m][key][cap] + ((u * len) >> 32)];
}

#endif
