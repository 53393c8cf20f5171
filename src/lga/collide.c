// SPDX-License-Identifier: MIT
// The collision step (LGA paper Sec. 2): p, q, gravity g, friction k, wall roughness b.
#include <string.h>

#include "core/error.h"
#include "lga/step.h"

// Index of the k-th (0-based) set bit of x.
static inline int gf_lga_nth_bit(uint32_t x, int k)
{
    while (k-- > 0) x &= x - 1;
    return __builtin_ctz(x);
}

// A uniformly chosen free slot of `out` among `mask`, or -1 if none.
static inline int gf_lga_random_free(gf_lga *l, uint16_t out, uint32_t mask)
{
    uint32_t free = (uint32_t)~out & mask;
    int c = l->table->count[free & GF_LGA_PARTICLES];
    if (!c) return -1;
    return gf_lga_nth_bit(free, (int)((gf_lga_u32(&l->rng) * (uint64_t)c) >> 32));
}

// Removes a uniformly chosen velocity of `*mv` and returns it.
static inline int gf_lga_take_random(gf_lga *l, uint16_t *mv)
{
    int e = gf_lga_random_free(l, (uint16_t)~*mv, *mv);
    if (e >= 0) *mv &= (uint16_t)~(1u << e);
    return e;
}

uint16_t gf_lga_collide_state(gf_lga *l, uint16_t s, bool gravity, int *excess)
{
    const gf_lga_table *t = l->table;
    s &= GF_LGA_PARTICLES;
    uint16_t mv = s & GF_LGA_MOVERS;
    int rest = s & GF_LGA_REST;
    int nm = t->count[mv], N = nm + rest;
    int a = t->ma[s], b = t->mb[s], cap = t->energy[s];
    int n = 0, nr = 0;
    if (N >= 2) {
        // Sec. 2: n particles stop with p^(n+1) < r1 < p^n, l are randomised
        // with q^(l+1) < r2 < q^l (both among the moving ones).
        uint64_t r = gf_rng_next(&l->rng);
        uint64_t u1 = r >> 32, u2 = r & 0xFFFFFFFFu;
        while (n < nm && u1 < l->thr_p[n + 1]) n++;
        while (nr < nm - n && u2 < l->thr_q[nr + 1]) nr++;
        // The stopped and the randomised take their momentum and energy with them.
        for (int k = 0; k < n + nr; k++) {
            int e = gf_lga_take_random(l, &mv);
            if (e < 0) break; // cannot happen: n + nr <= the movers in mv
            a -= gf_lga_da[e];
            b -= gf_lga_db[e];
            cap -= e < 7 ? 1 : 3;
        }
    }
    // The carriers: the moving particles left, plus the resting one unless
    // particles were stopped (then v0 is theirs).
    int m = t->count[mv] + (n ? 0 : rest);
    if (N >= 2 && m > 0 && l->thr_k) {
        uint64_t r = gf_rng_next(&l->rng);
        if ((r >> 32) < l->thr_k) {
            // Friction k: the outgoing momentum becomes the sum of min(m, 6)
            // distinct random horizontal-ish velocities (v2 v3 v5 v6 v8 v11).
            int dirs[6] = {2, 3, 5, 6, 8, 11};
            uint32_t u = (uint32_t)r;
            int c = m < 6 ? m : 6;
            a = b = 0;
            for (int i = 0; i < c; i++) {
                int j = i + (int)(u % (uint32_t)(6 - i));
                u /= (uint32_t)(6 - i);
                int tmp = dirs[i];
                dirs[i] = dirs[j];
                dirs[j] = tmp;
                a += gf_lga_da[dirs[i]];
                b += gf_lga_db[dirs[i]];
            }
        }
    }
    uint64_t r = gf_rng_next(&l->rng);
    if (gravity && (r >> 32) < l->thr_g) {
        // Gravity g: v4 added to the resultant; it may add up to 2 units of
        // energy (v3 -> v9, one step of a falling particle).
        b += gf_lga_db[4];
        cap += 2;
    }
    uint16_t out = gf_lga_table_pick(t, n ? GF_LGA_SET_MOVING : GF_LGA_SET_ALL, m, a, b, cap, r & 0xFFFFFFFFu);
    int ex = 0;
    if (n) {
        out |= GF_LGA_REST;
        ex = rest + n - 1;
    }
    for (int k = 0; k < nr; k++) {
        // the randomised particles leave slowly: a free nearest-neighbour velocity if any
        int e = gf_lga_random_free(l, out, 0x7Eu);
        if (e < 0) e = gf_lga_random_free(l, out, GF_LGA_MOVERS);
        if (e >= 0) out |= (uint16_t)(1u << e);
        else if (!(out & GF_LGA_REST)) out |= GF_LGA_REST;
        else ex++;
    }
    *excess = ex;
    return out;
}

// Whether the site at `idx` (its state before this collision step: `pre`)
// cannot hold a particle up: no resting particle there and no wall.
static inline bool gf_lga_unsupporting(uint16_t pre) { return !(pre & (GF_LGA_REST | GF_LGA_WALL)); }

void gf_lga_collide(gf_lga *l)
{
    uint16_t *st = l->state;
    const uint16_t *wall = l->wall;
    // Rows from the top down, so that the row below still holds its state from
    // before the collision (the update is parallel); the ghost row below row 0
    // is the top row before the collision (periodic lattices); the row itself
    // is read from a copy taken before it is updated.
    gf_lga_lattice_ghosts(l, st);
    const ptrdiff_t down = -(ptrdiff_t)l->stride;
    for (int j = l->h - 1; j >= 0; j--) {
        if (!l->busy[j]) continue; // no particle in the row
        size_t row = gf_lga_index(l, 0, j);
        memcpy(l->rowbuf, st + row - GF_LGA_HALO, (size_t)l->stride * sizeof *st);
        const uint16_t *pre = l->rowbuf + GF_LGA_HALO; // pre[i]: site (i, j) before this step
        for (int i = 0; i < l->w; i++) {
            size_t idx = row + (size_t)i;
            uint16_t s = st[idx];
            bool free_below = gf_lga_unsupporting(st[(size_t)((ptrdiff_t)idx + down)]);
            if (!(s & GF_LGA_MOVERS)) {
                if (!(s & GF_LGA_REST) || l->excess[idx]) continue;
                if (!free_below) {
                    // A resting particle on a resting one: with a free lower
                    // neighbour (v3 or v5) it rolls off that way with probability g;
                    // held from below and both sides, it stays (the 30 degree
                    // lattice slope is the steepest that holds).
                    bool odd = i & 1;
                    uint16_t dl = odd ? pre[i - 1] : st[(size_t)((ptrdiff_t)idx + l->off[0][3])];
                    uint16_t dr = odd ? pre[i + 1] : st[(size_t)((ptrdiff_t)idx + l->off[0][5])];
                    bool fl = gf_lga_unsupporting(dl), fr = gf_lga_unsupporting(dr);
                    if (!fl && !fr) continue;
                    uint64_t r = gf_rng_next(&l->rng);
                    if ((r >> 32) >= l->thr_g) continue;
                    int e = fl && fr ? ((r & 1) ? 5 : 3) : fl ? 3 : 5;
                    st[idx] = (uint16_t)((s & ~GF_LGA_PARTICLES) | (1u << e));
                    continue;
                }
            }
            int ex = 0;
            uint16_t out;
            if (l->table->count[s & GF_LGA_PARTICLES] == 1 && (s & GF_LGA_MOVERS)) {
                // One moving particle. Unsupported: only gravity (what
                // gf_lga_collide_state does for it, without its random draws).
                // On a resting particle or a wall: in contact, it collides with
                // what holds it and stops with probability p (the n = 1 of Sec. 2).
                out = s & GF_LGA_PARTICLES;
                uint64_t r = gf_rng_next(&l->rng);
                if (free_below) {
                    if ((r >> 32) < l->thr_g)
                        out = gf_lga_table_pick(l->table, GF_LGA_SET_ALL, 1, l->table->ma[out],
                                                l->table->mb[out] + gf_lga_db[4], l->table->energy[out] + 2,
                                                r & 0xFFFFFFFFu);
                } else if ((r >> 32) < l->thr_p[1]) {
                    out = GF_LGA_REST;
                }
            } else {
                out = gf_lga_collide_state(l, s, free_below, &ex);
            }
            // Wall roughness b: a particle about to hit a wall stops with probability b.
            uint16_t hit = out & wall[idx] & GF_LGA_MOVERS;
            if (hit && l->thr_b) {
                for (uint32_t x = hit; x; x &= x - 1) {
                    int e = __builtin_ctz(x);
                    if (gf_lga_u32(&l->rng) >= l->thr_b) continue;
                    out &= (uint16_t)~(1u << e);
                    if (!(out & GF_LGA_REST)) out |= GF_LGA_REST;
                    else ex++;
                }
            }
            // Particles already stacked here (excess) refill an emptied v0 slot.
            if (!(out & GF_LGA_REST) && l->excess[idx]) {
                out |= GF_LGA_REST;
                l->excess[idx]--;
            }
            st[idx] = (uint16_t)((s & ~GF_LGA_PARTICLES) | out);
            if (ex) gf_lga_add_excess(l, idx, ex);
        }
    }
}
