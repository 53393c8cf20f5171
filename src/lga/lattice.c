// SPDX-License-Identifier: MIT
// The hexagonal lattice: directions (LGA paper Fig. 1), neighbours, walls, memory.
#include "lga/lattice.h"

#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"

// Fig. 1, read so that v4 points down, v3 v4 v5 v9 v10 point downwards (the
// directions of h) and v2 v3 v5 v6 v8 v11 are the horizontal-ish ones (k):
// v1..v6 nearest neighbours at 90, 150, 210, 270, 330, 30 degrees (speed 1),
// v7..v12 second-nearest at 120, 180, 240, 300, 0, 60 degrees (speed sqrt 3).
const int gf_lga_da[13] = {0, 0, -1, -1, 0, 1, 1, -1, -2, -1, 1, 2, 1};
const int gf_lga_db[13] = {0, 2, 1, -1, -2, -1, 1, 3, 0, -3, -3, 0, 3};
const int gf_lga_opp[13] = {0, 4, 5, 6, 1, 2, 3, 10, 11, 12, 7, 8, 9};

// The two nearest directions a second-nearest move passes between (v7 = v1 + v2, ...).
static const int gf_lga_flank[13][2] = {{0, 0}, {0, 0}, {0, 0}, {0, 0}, {0, 0}, {0, 0}, {0, 0},
                                        {1, 2}, {2, 3}, {3, 4}, {4, 5}, {5, 6}, {6, 1}};

int gf_lga_di(int e) { return gf_lga_da[e]; }

int gf_lga_dj(int e, int odd)
{
    // y = j + odd/2; the target column has parity odd ^ (da & 1).
    int odd2 = odd ^ (gf_lga_da[e] & 1);
    return (odd + gf_lga_db[e] - odd2) / 2;
}

// The lattice's geometry lives here, not in lga.c, so that scenario.c (which
// lga.c calls to build a lattice) needs nothing of lga.c.
void gf_lga_site_position(int i, int j, double *x, double *y)
{
    *x = i * 0.86602540378443864676;
    *y = j + 0.5 * (i & 1);
}

size_t gf_lga_neighbour(const gf_lga *l, int i, int j, int e)
{
    int ni = i + gf_lga_da[e];
    int nj = j + gf_lga_dj(e, i & 1);
    if (l->periodic) nj = (nj + l->h) % l->h;
    return gf_lga_index(l, ni, nj);
}

// 32-bit fixed-point threshold of probability x: u32 < thr happens with probability x.
static uint64_t gf_lga_thr(double x) { return (uint64_t)llround(x * 4294967296.0); }

bool gf_lga_lattice_fits(int w, int h) { return (double)w * (double)h <= GF_LGA_MAX_SITES; }

gf_status gf_lga_lattice_alloc(gf_lga *l, int w, int h, bool periodic)
{
    if (w < 1 || h < 1 || (periodic && h < 2 * GF_LGA_HALO))
        return gf_error_set(GF_ERR_PARAM, "LGA lattice of %d x %d sites is too small", w, h);
    if (!gf_lga_lattice_fits(w, h))
        return gf_error_set(GF_ERR_PARAM, "LGA lattice of %d x %d sites is too large (at most %.0f sites)", w, h,
                            (double)GF_LGA_MAX_SITES);
    l->w = w;
    l->h = h;
    l->periodic = periodic;
    l->stride = w + 2 * GF_LGA_HALO;
    l->rows = h + 2 * GF_LGA_HALO;
    l->nsites = (size_t)l->stride * (size_t)l->rows;
    l->state = GF_NEW(uint16_t, l->nsites);
    l->next = GF_NEW(uint16_t, l->nsites);
    l->wall = GF_NEW(uint16_t, l->nsites);
    l->refl = GF_NEW(uint16_t, l->nsites);
    l->excess = GF_NEW(uint8_t, l->nsites);
    l->pending = GF_NEW(size_t, 2 * l->nsites);
    l->stamp = GF_NEW(uint32_t, l->nsites);
    l->crowded = GF_NEW(uint32_t, l->nsites);
    l->queue = GF_NEW(size_t, GF_LGA_SCATTER_QUEUE);
    l->qdy = GF_NEW(int16_t, GF_LGA_SCATTER_QUEUE);
    l->rowbuf = GF_NEW(uint16_t, (size_t)l->stride);
    l->busy = GF_NEW(uint8_t, (size_t)h);
    l->busy_next = GF_NEW(uint8_t, (size_t)h);
    gf_status st = l->state && l->next && l->wall && l->refl && l->excess && l->pending && l->stamp && l->crowded && l->queue && l->qdy && l->rowbuf && l->busy && l->busy_next
                       ? gf_lga_table_create(&l->table)
                       : gf_error_set(GF_ERR_NOMEM, "out of memory (LGA lattice of %d x %d sites)", w, h);
    if (st != GF_OK) {
        gf_lga_lattice_free(l);
        return st;
    }
    for (int odd = 0; odd < 2; odd++)
        for (int e = 0; e < 13; e++)
            l->off[odd][e] = (ptrdiff_t)gf_lga_dj(e, odd) * l->stride + gf_lga_da[e];
    // The halo: walls, except the ghost rows of a periodic lattice.
    for (int j = -GF_LGA_HALO; j < h + GF_LGA_HALO; j++)
        for (int i = -GF_LGA_HALO; i < w + GF_LGA_HALO; i++) {
            bool halo_col = i < 0 || i >= w, halo_row = j < 0 || j >= h;
            if (halo_col || (halo_row && !periodic)) l->state[gf_lga_index(l, i, j)] = GF_LGA_WALL;
        }
    memcpy(l->next, l->state, l->nsites * sizeof *l->state);

    for (int k = 0; k < 14; k++) {
        l->thr_p[k] = gf_lga_thr(pow(l->d.p, k));
        l->thr_q[k] = gf_lga_thr(pow(l->d.q, k));
    }
    l->thr_g = gf_lga_thr(l->d.g);
    l->thr_h = gf_lga_thr(l->d.h);
    l->thr_k = gf_lga_thr(l->d.k);
    l->thr_b = gf_lga_thr(l->d.b);
    return GF_OK;
}

void gf_lga_lattice_free(gf_lga *l)
{
    if (l->state) GF_DELETE(l->state, l->nsites);
    if (l->next) GF_DELETE(l->next, l->nsites);
    if (l->wall) GF_DELETE(l->wall, l->nsites);
    if (l->refl) GF_DELETE(l->refl, l->nsites);
    if (l->maps) GF_DELETE(l->maps, l->capmaps);
    if (l->excess) GF_DELETE(l->excess, l->nsites);
    if (l->pending) GF_DELETE(l->pending, 2 * l->nsites);
    if (l->stamp) GF_DELETE(l->stamp, l->nsites);
    if (l->crowded) GF_DELETE(l->crowded, l->nsites);
    if (l->queue) GF_DELETE(l->queue, GF_LGA_SCATTER_QUEUE);
    if (l->qdy) GF_DELETE(l->qdy, GF_LGA_SCATTER_QUEUE);
    if (l->rowbuf) GF_DELETE(l->rowbuf, (size_t)l->stride);
    if (l->busy) GF_DELETE(l->busy, (size_t)l->h);
    if (l->busy_next) GF_DELETE(l->busy_next, (size_t)l->h);
    if (l->sinks) GF_DELETE(l->sinks, l->nsinks);
    if (l->feed_sites) GF_DELETE(l->feed_sites, l->nfeed);
    gf_lga_table_destroy(l->table);
    l->state = l->next = l->wall = l->refl = NULL;
    l->maps = NULL;
    l->nmaps = l->capmaps = 0;
    l->excess = NULL;
    l->pending = l->sinks = l->feed_sites = l->queue = NULL;
    l->stamp = l->crowded = NULL;
    l->qdy = NULL;
    l->rowbuf = NULL;
    l->busy = l->busy_next = NULL;
    l->table = NULL;
}

// The reflection map of a site whose blocked directions are B: specular
// reflection about the wall normal estimated from B, onto the free velocity of
// the same speed nearest the mirror image; a slot qualifies only if streaming
// brings nothing into it (the direction it is filled from is blocked) and it
// is not taken yet. Where that fails, bounce-back (v -> -v, always safe).
static void gf_lga_reflection_map(uint16_t B, gf_lga_reflection *map)
{
    for (int e = 0; e < 13; e++) map->to[e] = (uint8_t)e;
    double nx = 0, ny = 0;
    for (int pass = 0; pass < 2 && nx * nx + ny * ny < 1e-12; pass++)
        for (int e = pass ? 7 : 1; e <= (pass ? 12 : 6); e++)
            if (B & (1u << e)) {
                double vx = gf_lga_da[e] * 0.86602540378443864676, vy = 0.5 * gf_lga_db[e];
                double len = sqrt(vx * vx + vy * vy);
                nx += vx / len;
                ny += vy / len;
            }
    double nn = sqrt(nx * nx + ny * ny);
    bool ok = nn > 1e-6;
    if (ok) {
        nx /= nn;
        ny /= nn;
    }
    uint16_t used = 0;
    for (int e = 1; ok && e < 13; e++) {
        if (!(B & (1u << e))) continue;
        double vx = gf_lga_da[e] * 0.86602540378443864676, vy = 0.5 * gf_lga_db[e];
        double dot = vx * nx + vy * ny;
        double rx = vx - 2 * dot * nx, ry = vy - 2 * dot * ny;
        int best = -1;
        double best_cos = -2;
        for (int f = 1; f < 13; f++) {
            if ((f >= 7) != (e >= 7) || (B & (1u << f)) || !(B & (1u << gf_lga_opp[f])) || (used & (1u << f)))
                continue;
            double fx = gf_lga_da[f] * 0.86602540378443864676, fy = 0.5 * gf_lga_db[f];
            double c = (fx * rx + fy * ry) / (sqrt(fx * fx + fy * fy) * sqrt(rx * rx + ry * ry) + 1e-300);
            if (c > best_cos + 1e-9) {
                best_cos = c;
                best = f;
            }
        }
        if (best < 0) ok = false;
        else {
            map->to[e] = (uint8_t)best;
            used |= (uint16_t)(1u << best);
        }
    }
    if (!ok)
        for (int e = 1; e < 13; e++) map->to[e] = (uint8_t)((B & (1u << e)) ? gf_lga_opp[e] : e);
}

gf_status gf_lga_lattice_walls(gf_lga *l)
{
    memset(l->wall, 0, l->nsites * sizeof *l->wall);
    memset(l->refl, 0, l->nsites * sizeof *l->refl);
    l->nmaps = 0;
    for (int j = 0; j < l->h; j++)
        for (int i = 0; i < l->w; i++) {
            size_t s = gf_lga_index(l, i, j);
            if (l->state[s] & GF_LGA_WALL) continue;
            uint16_t b = 0;
            for (int e = 1; e < 13; e++) {
                bool blocked = l->state[gf_lga_neighbour(l, i, j, e)] & GF_LGA_WALL;
                if (e >= 7 && (l->state[gf_lga_neighbour(l, i, j, gf_lga_flank[e][0])] & GF_LGA_WALL) &&
                    (l->state[gf_lga_neighbour(l, i, j, gf_lga_flank[e][1])] & GF_LGA_WALL))
                    blocked = true;
                if (blocked) b |= (uint16_t)(1u << e);
            }
            l->wall[s] = b;
            if (!b) continue;
            gf_lga_reflection map;
            gf_lga_reflection_map(b, &map);
            size_t k = 0;
            while (k < l->nmaps && memcmp(&l->maps[k], &map, sizeof map) != 0) k++;
            if (k == l->nmaps) {
                if (l->nmaps == l->capmaps) {
                    size_t ncap = l->capmaps ? 2 * l->capmaps : 64;
                    if (ncap > 65535) return gf_error_set(GF_ERR_PARAM, "LGA walls: too many kinds of wall site");
                    gf_lga_reflection *p = gf_realloc(l->maps, l->capmaps * sizeof *p, ncap * sizeof *p);
                    if (!p) return gf_error_set(GF_ERR_NOMEM, "out of memory (LGA walls)");
                    l->maps = p;
                    l->capmaps = ncap;
                }
                l->maps[l->nmaps++] = map;
            }
            l->refl[s] = (uint16_t)k;
        }
    return GF_OK;
}

void gf_lga_lattice_busy(gf_lga *l)
{
    for (int j = 0; j < l->h; j++) {
        uint16_t any = 0;
        for (int i = 0; i < l->w; i++) any |= l->state[gf_lga_index(l, i, j)];
        l->busy[j] = (any & GF_LGA_PARTICLES) != 0;
    }
}

void gf_lga_lattice_ghosts(gf_lga *l, uint16_t *buf)
{
    if (!l->periodic) return;
    size_t row = (size_t)l->stride;
    for (int k = 0; k < GF_LGA_HALO; k++) {
        // ghost row -1-k <- row h-1-k; ghost row h+k <- row k
        memcpy(buf + gf_lga_index(l, -GF_LGA_HALO, -1 - k), buf + gf_lga_index(l, -GF_LGA_HALO, l->h - 1 - k),
               row * sizeof *buf);
        memcpy(buf + gf_lga_index(l, -GF_LGA_HALO, l->h + k), buf + gf_lga_index(l, -GF_LGA_HALO, k),
               row * sizeof *buf);
    }
}
