// SPDX-License-Identifier: MIT
// Shared by the LGA test suites: an independent count of the particles on a lattice.
#ifndef GF_TEST_LGA_SUPPORT_H
#define GF_TEST_LGA_SUPPORT_H

#include <stdint.h>

#include "lga/lattice.h"

/// Particles counted from the site states (and the stacks of surplus
/// resting particles), independently of the engine's own counters.
static inline int64_t recount(const gf_lga *l)
{
    int64_t n = 0;
    for (int j = 0; j < l->h; j++)
        for (int i = 0; i < l->w; i++) {
            size_t s = gf_lga_index(l, i, j);
            n += __builtin_popcount(l->state[s] & GF_LGA_PARTICLES) + l->excess[s];
        }
    return n;
}

#endif
