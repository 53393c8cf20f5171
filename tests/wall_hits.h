// SPDX-License-Identifier: MIT
// Test helpers for the walls of a container (geom/container.h): the one wall
// element near a point, and a hit against its hand-computed gap and normal.
// Shared by the suites of each shape (test_geometry.c, test_wedge.c).
#ifndef GF_TEST_WALL_HITS_H
#define GF_TEST_WALL_HITS_H

#include "support.h"

#include <stdbool.h>

#include "geom/container.h"

/// The one hit of walls() at p within reach; fails the test unless there is exactly one.
static inline gf_wall_hit gf_test_one_hit(const gf_container *c, double x, double y, double z, double reach)
{
    gf_wall_hit hit[GF_WALL_HITS];
    const double p[3] = {x, y, z};
    int n = gf_container_walls(c, p, reach, hit);
    if (n != 1) fail_msg("%d walls within %g of (%g, %g, %g), expected 1", n, reach, x, y, z);
    return hit[0];
}

/// Gap and normal within 1e-12 of the hand-computed ones, and the side flag.
static inline void gf_test_assert_hit(gf_wall_hit h, double gap, double nx, double ny, double nz, bool side)
{
    gf_assert_near(h.gap, gap, 1e-12);
    gf_assert_near(h.n[0], nx, 1e-12);
    gf_assert_near(h.n[1], ny, 1e-12);
    gf_assert_near(h.n[2], nz, 1e-12);
    assert_true(h.side == side);
}

#endif
