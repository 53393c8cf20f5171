// SPDX-License-Identifier: MIT
// The one cell list (src/geom/celllist.c) against brute force: every point
// listed once in its cell, in index order; range walks and the forward
// stencil find exactly the pairs a search over all pairs finds, for random
// points, clustered ones, far outliers and non-finite ones. (No caller wants
// a periodic list, so it has none.)
#include "support.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "geom/celllist.h"

#define NPT 1500

typedef struct pts {
    double x[NPT], y[NPT], z[NPT];
    size_t n;
} pts;

// n random points in [0, w) x [0, d) x [0, hgt); with `odd` a dense cluster,
// two far outliers and two non-finite points among them.
static void make_points(pts *p, size_t n, uint64_t seed, double w, double d, double hgt, bool odd)
{
    gf_rng r;
    gf_rng_seed(&r, seed, 7);
    p->n = n;
    for (size_t i = 0; i < n; i++) {
        p->x[i] = w * gf_rng_uniform(&r);
        p->y[i] = d * gf_rng_uniform(&r);
        p->z[i] = hgt * gf_rng_uniform(&r);
        if (odd && i % 5 == 0) { // a cluster around (1, 1, 1)
            p->x[i] = 1.0 + 0.3 * gf_rng_uniform(&r);
            p->y[i] = 1.0 + 0.3 * gf_rng_uniform(&r);
            p->z[i] = 1.0 + 0.3 * gf_rng_uniform(&r);
        }
    }
    if (odd) {
        p->x[3] = 1e4;
        p->z[8] = -3e3;
        p->y[11] = NAN;
        p->z[12] = INFINITY;
    }
}

static bool finite3(const pts *p, size_t i) { return isfinite(p->x[i]) && isfinite(p->y[i]) && isfinite(p->z[i]); }

static double dist2(const pts *p, size_t i, size_t j)
{
    double dx = p->x[i] - p->x[j], dy = p->y[i] - p->y[j], dz = p->z[i] - p->z[j];
    return dx * dx + dy * dy + dz * dz;
}

// Every finite point once, in the cell its coordinates give, increasing index within a cell.
static void check_listing(const gf_celllist *cl, const pts *p)
{
    size_t nfin = 0;
    for (size_t i = 0; i < p->n; i++) nfin += finite3(p, i);
    assert_int_equal(cl->nidx, nfin);
    assert_int_equal(cl->start[0], 0);
    assert_int_equal(cl->start[cl->ncell], nfin);
    unsigned char *seen = calloc(p->n, 1);
    assert_non_null(seen);
    for (size_t c = 0; c < cl->ncell; c++) {
        assert_true(cl->start[c] <= cl->start[c + 1]);
        for (size_t q = cl->start[c]; q < cl->start[c + 1]; q++) {
            size_t i = cl->idx[q];
            assert_true(i < p->n);
            assert_false(seen[i]);
            seen[i] = 1;
            if (q > cl->start[c]) assert_true(cl->idx[q - 1] < i);
            size_t want = gf_celllist_index(cl, gf_celllist_axis(cl, 0, p->x[i]), gf_celllist_axis(cl, 1, p->y[i]),
                                            gf_celllist_axis(cl, 2, p->z[i]));
            assert_int_equal(want, c);
        }
    }
    for (size_t i = 0; i < p->n; i++) assert_int_equal(seen[i], finite3(p, i));
    free(seen);
}

// For every finite point and radius r <= the cell edge: the range walk finds
// exactly the finite points within r (brute force), each once.
static void check_near(const gf_celllist *cl, const pts *p, double r)
{
    unsigned char *hit = calloc(p->n, 1);
    assert_non_null(hit);
    size_t total = 0;
    for (size_t i = 0; i < p->n; i++) {
        if (!finite3(p, i)) continue;
        const double c[3] = {p->x[i], p->y[i], p->z[i]};
        memset(hit, 0, p->n);
        gf_celllist_near it;
        gf_celllist_near_start(&it, cl, c, r);
        size_t found = 0;
        for (size_t j; gf_celllist_near_next(&it, &j);) {
            assert_false(hit[j]);
            hit[j] = 1;
            if (dist2(p, i, j) <= r * r) found++;
        }
        size_t want = 0;
        for (size_t j = 0; j < p->n; j++) {
            if (!finite3(p, j) || dist2(p, i, j) > r * r) continue;
            want++;
            assert_true(hit[j]); // no neighbour missed
        }
        assert_int_equal(found, want);
        total += want;
    }
    assert_true(total > p->n); // the test sees real neighbours, not just each point itself
    free(hit);
}

// Pairs closer than r (r <= every cell edge) through each cell and its forward
// stencil: each pair once, the same count as over all pairs.
static void check_forward(const gf_celllist *cl, const pts *p, double r)
{
    size_t found = 0, want = 0;
    for (int cz = 0; cz < cl->n[2]; cz++)
        for (int cy = 0; cy < cl->n[1]; cy++)
            for (int cx = 0; cx < cl->n[0]; cx++) {
                size_t a = gf_celllist_index(cl, cx, cy, cz), lo[13], hi[13];
                int ns = gf_celllist_forward(cl, cx, cy, cz, lo, hi);
                assert_true(ns >= 0 && ns <= 13);
                for (size_t u = cl->start[a]; u < cl->start[a + 1]; u++)
                    for (int s = -1; s < ns; s++)
                        for (size_t v = s < 0 ? u + 1 : lo[s]; v < (s < 0 ? cl->start[a + 1] : hi[s]); v++)
                            found += dist2(p, cl->idx[u], cl->idx[v]) < r * r;
            }
    for (size_t i = 0; i < p->n; i++)
        for (size_t j = i + 1; j < p->n; j++)
            if (finite3(p, i) && finite3(p, j)) want += dist2(p, i, j) < r * r;
    assert_true(want > 0);
    assert_int_equal(found, want);
}

static void fit_matches_brute_force(void **state)
{
    (void)state;
    static pts p;
    gf_celllist cl = {0};
    const double h[] = {0.5, 1.0, 2.7};
    for (int t = 0; t < 3; t++) {
        make_points(&p, NPT, 11 + (uint64_t)t, 20.0, 6.0, 30.0, false);
        assert_int_equal(gf_celllist_fit(&cl, p.x, p.y, p.z, p.n, h[t]), GF_OK); // rebuilt in place
        assert_true(1.0 / cl.inv[0] >= h[t]);
        check_listing(&cl, &p);
        check_near(&cl, &p, h[t]);
        check_forward(&cl, &p, h[t]);
    }
    gf_celllist_free(&cl);
}

static void outliers_and_nonfinite_points(void **state)
{
    (void)state;
    static pts p;
    make_points(&p, 1000, 5, 10.0, 10.0, 10.0, true);
    gf_celllist cl = {0};
    assert_int_equal(gf_celllist_fit(&cl, p.x, p.y, p.z, p.n, 1.0), GF_OK);
    // The outliers stretch the box, not the cell count: at most ~8 per point.
    assert_true(cl.ncell <= 8 * (p.n + 1) + 3 * 2048 * 2048);
    check_listing(&cl, &p);
    check_near(&cl, &p, 1.0 / cl.inv[0]);
    check_forward(&cl, &p, 1.0 / cl.inv[0]);
    gf_celllist_free(&cl);
}

// A grid given by hand with cells of different edges per axis (as the
// packing generator builds it); points beyond it land in its edge cells.
static void explicit_grid_clamps(void **state)
{
    (void)state;
    static pts p;
    make_points(&p, NPT, 3, 12.0, 5.0, 20.0, false);
    for (size_t i = 0; i < 30; i++) p.z[i] += 21.0; // above the grid's top (16 x 1.3)
    const double lo[3] = {0.0, 0.0, 0.0}, inv[3] = {7.0 / 12.0, 3.0 / 5.0, 1.0 / 1.3};
    const int n[3] = {7, 3, 16};
    gf_celllist cl = {0};
    assert_int_equal(gf_celllist_grid(&cl, lo, inv, n), GF_OK);
    assert_int_equal(cl.ncell, 7 * 3 * 16);
    assert_int_equal(gf_celllist_bin(&cl, p.x, p.y, p.z, p.n), GF_OK);
    check_listing(&cl, &p);
    for (size_t i = 0; i < 30; i++) assert_int_equal(gf_celllist_axis(&cl, 2, p.z[i]), 15);
    check_forward(&cl, &p, 1.3 * 0.999);
    const int bad[3] = {7, 0, 16};
    assert_int_equal(gf_celllist_grid(&cl, lo, inv, bad), GF_ERR_PARAM);
    gf_celllist_free(&cl);
}

// Sorting by given keys: stable, GF_CELLLIST_OUT left out, storage reused.
static void keys_sort_stable(void **state)
{
    (void)state;
    gf_celllist cl = {0};
    for (size_t n = 0; n < 300; n += 37) {
        assert_int_equal(gf_celllist_keys(&cl, 5, n), GF_OK);
        size_t out = 0;
        for (size_t i = 0; i < n; i++) {
            cl.cell[i] = i % 7 == 3 ? GF_CELLLIST_OUT : (uint32_t)((i * 13) % 5);
            out += cl.cell[i] == GF_CELLLIST_OUT;
        }
        gf_celllist_sort(&cl, n);
        assert_int_equal(cl.nidx, n - out);
        for (size_t c = 0; c < 5; c++)
            for (size_t q = cl.start[c]; q < cl.start[c + 1]; q++) {
                assert_int_equal(cl.cell[cl.idx[q]], c);
                if (q > cl.start[c]) assert_true(cl.idx[q - 1] < cl.idx[q]);
            }
    }
    gf_celllist_free(&cl);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(fit_matches_brute_force),
    cmocka_unit_test(outliers_and_nonfinite_points),
    cmocka_unit_test(explicit_grid_clamps),
    cmocka_unit_test(keys_sort_stable),
};

GF_TEST_MAIN("celllist", tests)
