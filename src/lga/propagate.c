// SPDX-License-Identifier: MIT
// The two propagation steps (LGA paper Sec. 2), the feed and the sinks.
#include <math.h>
#include <string.h>

#include "core/error.h"
#include "lga/step.h"

// Where a resting particle may drop under gravity h (Sec. 2): v3 v4 v5 v9 v10.
static const int gf_lga_h_dirs[5] = {3, 4, 5, 9, 10};

void gf_lga_feed(gf_lga *l)
{
    if (l->feed_total <= 0 || l->nfeed == 0) return;
    l->feed_due += l->feed_rate;
    while (l->feed_due >= 1.0 && l->feed_total > 0) {
        // A random feed site with its v4 slot free (a few tries, then in order).
        size_t at = l->nsites;
        for (int tries = 0; tries < 8 && at == l->nsites; tries++) {
            size_t s = l->feed_sites[gf_rng_below(&l->rng, l->nfeed)];
            if (!(l->state[s] & (1u << 4))) at = s;
        }
        for (size_t k = 0; k < l->nfeed && at == l->nsites; k++)
            if (!(l->state[l->feed_sites[k]] & (1u << 4))) at = l->feed_sites[k];
        if (at == l->nsites) break; // all full: the rest waits for the next iteration
        l->state[at] |= (uint16_t)(1u << 4);
        gf_lga_mark_busy(l, at);
        l->feed_due -= 1.0;
        l->feed_total--;
        l->added++;
        l->particles++;
    }
    if (l->feed_total == 0) l->feed_due = 0;
}

// The site nearest to idx (breadth first over non-wall sites, at most
// `radius` steps) with a free v0 slot and room: of the nearest ring that has
// one, the emptiest, then the lowest (surplus grains roll down rather than
// climb), ties at random; nsites if none.
static size_t gf_lga_scatter_target(gf_lga *l, size_t idx, int radius)
{
    uint16_t *st = l->state;
    if (++l->stamp_now == 0) { // wrapped: clear the marks
        for (size_t k = 0; k < l->nsites; k++) l->stamp[k] = 0;
        l->stamp_now = 1;
    }
    // A start inside the ball of a search that failed this iteration only
    // looks at its neighbours (its own ball would hardly have room either).
    uint32_t tag = (uint32_t)l->iteration + 1u;
    if (l->crowded[idx] == tag) radius = 1;
    size_t head = 0, tail = 0, ring_end;
    l->queue[tail] = idx;
    l->qdy[tail++] = 0;
    l->stamp[idx] = l->stamp_now;
    for (int ring = 1; ring <= radius && head < tail; ring++) {
        ring_end = tail;
        size_t best_n = 0, pick = l->nsites;
        int best = 99, best_dy = 0;
        for (; head < ring_end; head++) {
            size_t from = l->queue[head];
            int dy0 = l->qdy[head];
            int odd = (int)((from % (size_t)l->stride) + GF_LGA_HALO) & 1; // the halo width is even
            for (int e = 1; e <= 6; e++) {
                if (l->wall[from] & (1u << e)) continue;
                size_t t = gf_lga_neighbour_idx(l, from, odd, e);
                if (l->stamp[t] == l->stamp_now) continue;
                l->stamp[t] = l->stamp_now;
                int dy = dy0 + gf_lga_db[e]; // height relative to idx, half spacings
                if (tail < GF_LGA_SCATTER_QUEUE) {
                    l->queue[tail] = t;
                    l->qdy[tail++] = (int16_t)dy;
                }
                uint16_t s = st[t];
                int c = gf_lga_count(l, s) + l->excess[t];
                if ((s & GF_LGA_REST) || c >= 13) continue;
                if (c < best || (c == best && dy < best_dy)) {
                    best = c;
                    best_dy = dy;
                    best_n = 0;
                }
                // reservoir choice among the emptiest and lowest of this ring
                if (c == best && dy == best_dy && gf_rng_below(&l->rng, ++best_n) == 0) pick = t;
            }
        }
        if (pick != l->nsites) return pick;
    }
    if (radius > 1)
        for (size_t k = 0; k < tail; k++) l->crowded[l->queue[k]] = tag;
    return l->nsites;
}

void gf_lga_scatter(gf_lga *l)
{
    uint16_t *st = l->state;
    size_t keep = 0;
    for (size_t k = 0; k < l->npending; k++) {
        size_t idx = l->pending[k];
        // A stack that found no room before only looks at its neighbours (room
        // reaches it as vacancies move); a new one searches the whole radius.
        int radius = k < l->npersist ? 1 : GF_LGA_SCATTER_RADIUS;
        while (l->excess[idx] > 0) {
            size_t t = gf_lga_scatter_target(l, idx, radius);
            if (t == l->nsites) break; // no room nearby: stays stacked here
            st[t] |= GF_LGA_REST | GF_LGA_MARK;
            gf_lga_mark_busy(l, t);
            l->excess[idx]--;
        }
    }
    // Keep the sites still holding a stack, each once (a site may have been listed twice).
    if (++l->stamp_now == 0) {
        for (size_t k = 0; k < l->nsites; k++) l->stamp[k] = 0;
        l->stamp_now = 1;
    }
    for (size_t k = 0; k < l->npending; k++) {
        size_t idx = l->pending[k];
        if (!l->excess[idx] || l->stamp[idx] == l->stamp_now) continue;
        l->stamp[idx] = l->stamp_now;
        l->pending[keep++] = idx;
    }
    l->npending = keep;
    l->npersist = keep;
}

// Failures before the next success of Bernoulli(x) trials, 0 < x <= 1.
static int64_t gf_lga_geometric_gap(gf_lga *l, double x)
{
    if (x >= 1.0) return 0;
    double g = floor(log(gf_rng_uniform_pos(&l->rng)) / log1p(-x));
    return g < 4e18 ? (int64_t)g : INT64_MAX;
}

void gf_lga_settle(gf_lga *l)
{
    if (!l->thr_h) return;
    uint16_t *st = l->state;
    for (int j = 0; j < l->h; j++) {
        if (!l->busy[j]) continue;
        size_t row = gf_lga_index(l, 0, j);
        for (int i = 0; i < l->w; i++) {
            size_t idx = row + (size_t)i;
            uint16_t s = st[idx];
            if ((s & (GF_LGA_REST | GF_LGA_MARK)) != GF_LGA_REST) continue;
            // Bernoulli(h) per resting particle, drawn as geometric gaps between
            // successes (the same law, one random number per success).
            if (l->settle_skip < 0) l->settle_skip = gf_lga_geometric_gap(l, l->d.h);
            if (l->settle_skip > 0) {
                l->settle_skip--;
                continue;
            }
            l->settle_skip = gf_lga_geometric_gap(l, l->d.h); // failures before the next success
            uint64_t r = gf_rng_next(&l->rng);
            size_t cand[5];
            int nc = 0;
            for (int k = 0; k < 5; k++) {
                int e = gf_lga_h_dirs[k];
                if (l->wall[idx] & (1u << e)) continue;
                size_t t = gf_lga_neighbour_idx(l, idx, i & 1, e);
                if (!(st[t] & (GF_LGA_PARTICLES | GF_LGA_WALL))) cand[nc++] = t;
            }
            if (!nc) continue;
            size_t t = cand[((r & 0xFFFFFFFFu) * (uint64_t)nc) >> 32];
            if (l->excess[idx]) l->excess[idx]--; // the next stacked particle takes v0
            else st[idx] &= (uint16_t)~GF_LGA_REST;
            st[t] |= GF_LGA_REST | GF_LGA_MARK;
            gf_lga_mark_busy(l, t);
        }
    }
}

// One site's new state: what arrives from its neighbours, plus what the walls send back.
static inline uint16_t gf_lga_stream_site(const gf_lga *l, const uint16_t *restrict st, size_t idx,
                                          const ptrdiff_t *o, const gf_lga_table *t)
{
    uint16_t s = st[idx];
    if (s & GF_LGA_WALL) return s;
    uint32_t in = 0;
    for (int e = 1; e < 13; e++) in |= st[(ptrdiff_t)idx + o[e]] & (1u << e);
    uint16_t blocked = l->wall[idx];
    if (blocked) {
        // Nothing arrives from a blocked direction; what was heading into
        // the wall comes back along the site's reflection map.
        in &= ~(uint32_t)t->reverse[blocked];
        const uint8_t *to = l->maps[l->refl[idx]].to;
        for (uint32_t x = s & blocked; x; x &= x - 1) in |= 1u << to[__builtin_ctz(x)];
    }
    return (uint16_t)((s & (GF_LGA_REST | GF_LGA_WALL | GF_LGA_SINK)) | in);
}

void gf_lga_stream(gf_lga *l)
{
    gf_lga_lattice_ghosts(l, l->state);
    const uint16_t *restrict st = l->state;
    uint16_t *restrict nx = l->next;
    const gf_lga_table *t = l->table;
    // src[odd][e]: offset of the site a particle with velocity e arrives from
    ptrdiff_t src[2][13];
    for (int odd = 0; odd < 2; odd++)
        for (int e = 0; e < 13; e++) src[odd][e] = l->off[odd][gf_lga_opp[e]];
    for (int j = 0; j < l->h; j++) {
        size_t row = gf_lga_index(l, 0, j);
        // Particles reach row j only from rows j-2 .. j+2.
        bool busy = false;
        for (int k = -GF_LGA_HALO; k <= GF_LGA_HALO && !busy; k++) {
            int jj = j + k;
            if (l->periodic) jj = (jj + l->h) % l->h;
            busy = jj >= 0 && jj < l->h && l->busy[jj];
        }
        if (!busy) {
            memcpy(nx + row, st + row, (size_t)l->w * sizeof *st);
            l->busy_next[j] = 0;
            continue;
        }
        uint16_t any = 0;
        // even columns, then odd ones: the offsets are constant along each pass
        for (int odd = 0; odd < 2; odd++) {
            const ptrdiff_t *o = src[odd];
            for (int i = odd; i < l->w; i += 2) {
                uint16_t v = gf_lga_stream_site(l, st, row + (size_t)i, o, t);
                nx[row + (size_t)i] = v;
                any |= v;
            }
        }
        l->busy_next[j] = (any & GF_LGA_PARTICLES) != 0;
    }
    l->next = l->state;
    l->state = nx;
    uint8_t *b = l->busy;
    l->busy = l->busy_next;
    l->busy_next = b;
}

int64_t gf_lga_drain(gf_lga *l)
{
    int64_t out = 0;
    for (size_t k = 0; k < l->nsinks; k++) {
        size_t s = l->sinks[k];
        out += gf_lga_count(l, l->state[s]);
        l->state[s] &= (uint16_t)~GF_LGA_PARTICLES;
    }
    l->particles -= out;
    l->removed += out;
    l->last_outflow = out;
    return out;
}
