// SPDX-License-Identifier: MIT
// The slabs of the domain engine across MPI ranks (slabs.h).
#include "spot/slabs.h"

#include "core/alloc.h"
#include "core/error.h"

void gf_slabs_free(gf_slabs *s)
{
    const int R = s->R;
    if (s->lo) GF_DELETE(s->lo, R);
    if (s->hi) GF_DELETE(s->hi, R);
    if (s->rlo) GF_DELETE(s->rlo, R);
    if (s->rhi) GF_DELETE(s->rhi, R);
    if (s->zone) GF_DELETE(s->zone, s->n);
    *s = (gf_slabs){0};
}

gf_status gf_slabs_make(gf_slabs *s, int axis, int n, int nx, int ny, int D, int per, int R, int halo)
{
    *s = (gf_slabs){.axis = axis, .n = n, .R = R, .nx = nx, .ny = ny};
    if (axis < 0 || axis > 2 || n < 1 || D < 1 || per < 1 || R < 1 || halo < 0)
        return gf_error_set(GF_ERR_PARAM, "slabs: axis %d, %d layers, %d domains of %d, %d ranks, halo %d", axis, n,
                            D, per, R, halo);
    s->lo = GF_NEW(int, R);
    s->hi = GF_NEW(int, R);
    s->rlo = GF_NEW(int, R);
    s->rhi = GF_NEW(int, R);
    s->zone = GF_NEW(uint32_t, n);
    if (!s->lo || !s->hi || !s->rlo || !s->rhi || !s->zone) {
        gf_slabs_free(s);
        return gf_error_set(GF_ERR_NOMEM, "out of memory for the slabs of %d ranks", R);
    }
    for (int r = 0; r < R; r++) {
        // With fewer domains than ranks, one each and the last ranks none.
        long d0 = D >= R ? (long)r * D / R : (r < D ? r : D), d1 = D >= R ? (long)(r + 1) * D / R : (r + 1 < D ? r + 1 : D);
        s->lo[r] = (int)(d0 * per < n ? d0 * per : n);
        s->hi[r] = (int)(d1 * per < n ? d1 * per : n);
        if (r == R - 1) s->hi[r] = n;
        if (s->lo[r] >= s->hi[r]) {
            s->lo[r] = s->hi[r] = s->rlo[r] = s->rhi[r] = 0;
            continue;
        }
        s->rlo[r] = s->lo[r] - halo > 0 ? s->lo[r] - halo : 0;
        s->rhi[r] = s->hi[r] + halo < n ? s->hi[r] + halo : n;
    }
    // A region's membership changes only at a region edge: the edges at or
    // below a layer number its zone.
    for (int L = 0; L < n; L++) {
        uint32_t z = 0;
        for (int r = 0; r < R; r++)
            if (s->rlo[r] < s->rhi[r]) z += (uint32_t)(s->rlo[r] > 0 && s->rlo[r] <= L) + (uint32_t)(s->rhi[r] <= L);
        s->zone[L] = z;
    }
    return GF_OK;
}

int gf_slabs_owner(const gf_slabs *s, int layer)
{
    for (int r = 0; r < s->R; r++)
        if (layer >= s->lo[r] && layer < s->hi[r]) return r;
    return 0;
}

int gf_slabs_partners(const gf_slabs *s, int a, int b)
{
    if (a == b || s->rlo[a] >= s->rhi[a] || s->rlo[b] >= s->rhi[b]) return 0;
    return s->rlo[a] < s->rhi[b] && s->rlo[b] < s->rhi[a];
}
