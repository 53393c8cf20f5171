// SPDX-License-Identifier: MIT
// Internal: the slabs of the domain engine across MPI ranks (issue 23). The
// domains are cut along one axis (the one with the most domains, the
// tallest) into R contiguous slabs, one a rank: rank r owns the cell layers
// of its slab and runs exactly its slab's sectors in every phase. Its region
// is its slab and a halo of `halo` layers each side (gf_par_reach and a cell
// diagonal: everything its moves read or write lies in it); the records a
// phase changes go to the ranks whose region holds them, i.e. to the
// neighbour slabs. No MPI here: the geometry is tested in every build.
#ifndef GF_SPOT_SLABS_H
#define GF_SPOT_SLABS_H

#include <stddef.h>
#include <stdint.h>

#include "granflow/core.h"

typedef struct gf_slabs {
    int axis;        ///< 0, 1, 2: x, y, z
    int n;           ///< cell layers along it
    int R;           ///< ranks
    int nx, ny;      ///< the grid's cells along x and y (a cell's layer)
    int *lo, *hi;    ///< per rank: owned layers [lo, hi) (none when lo == hi: more ranks than domains)
    int *rlo, *rhi;  ///< per rank: layers of its region [rlo, rhi) (slab and halo; empty with the slab)
    uint32_t *zone;  ///< per layer: the region edges at or below it; equal zones, same regions
} gf_slabs;

/// The slabs of R ranks over n layers cut into `D` domains of `per` layers
/// each along `axis` (the last may be shorter): rank r owns domains
/// [r D / R, (r + 1) D / R) (rounded down; when D < R one each, the last
/// ranks none);
/// its region adds `halo` layers each side.
gf_status gf_slabs_make(gf_slabs *s, int axis, int n, int nx, int ny, int D, int per, int R, int halo);
void gf_slabs_free(gf_slabs *s);

/// Layer of grid cell c along the slabs' axis.
static inline int gf_slabs_layer(const gf_slabs *s, uint32_t c)
{
    return s->axis == 0 ? (int)(c % (uint32_t)s->nx)
           : s->axis == 1 ? (int)(c / (uint32_t)s->nx % (uint32_t)s->ny)
                          : (int)(c / ((uint32_t)s->nx * (uint32_t)s->ny));
}

/// The rank that owns a layer.
int gf_slabs_owner(const gf_slabs *s, int layer);

/// Whether a move from cell a to cell b takes a particle into or out of
/// some rank's region (it then needs its whole record and list row there).
static inline int gf_slabs_crosses(const gf_slabs *s, uint32_t a, uint32_t b)
{
    return s->zone[gf_slabs_layer(s, a)] != s->zone[gf_slabs_layer(s, b)];
}

/// Whether rank r's region holds layer L.
static inline int gf_slabs_holds(const gf_slabs *s, int r, int L) { return L >= s->rlo[r] && L < s->rhi[r]; }

/// Whether the regions of ranks a and b overlap (they exchange after every phase).
int gf_slabs_partners(const gf_slabs *s, int a, int b);

#endif
