// SPDX-License-Identifier: MIT
// Voronoi cells through Voro++ (2009 paper Figs. 4, 6): lattices whose cells
// are known exactly (unit cubes; cubes cut by the walls), volumes summing to
// the box, and the local packing-fraction measurement on known packings.
#include "support.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "granflow/granflow.h"
#include "granflow/analysis.h"

#define PI 3.14159265358979323846

// Simple cubic lattice, spacing 1, points at lo + off + i on each axis, in
// the box of the container W x D x ztop (nx x ny x nz points).
static void cubic(gf_packing *p, double W, double D, double off, int nx, int ny, int nz)
{
    int64_t id = 1;
    for (int k = 0; k < nz; k++)
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++)
                assert_int_equal(gf_packing_push(p, id++, 1, -0.5 * W + off + i, -0.5 * D + off + j, off + k, 0.5),
                                 GF_OK);
}

static void unit_cells_of_a_cubic_lattice(void **state)
{
    (void)state;
    const double W = 6, D = 4, H = 5;
    gf_packing p = {0};
    cubic(&p, W, D, 0.5, 6, 4, 5); // fills the box exactly: every cell a unit cube
    double *vol = GF_NEW(double, p.n), *phi = GF_NEW(double, p.n);
    assert_int_equal(gf_voronoi_volumes(&p, W, D, H, vol), GF_OK);
    assert_int_equal(gf_voronoi_fraction(&p, W, D, H, phi), GF_OK);
    for (size_t i = 0; i < p.n; i++) {
        gf_assert_near(vol[i], 1.0, 1e-9);
        gf_assert_near(phi[i], PI / 6, 1e-9);
    }
    GF_DELETE(vol, p.n);
    GF_DELETE(phi, p.n);
    gf_packing_free(&p);
}

// Cell edge along one axis for lattice index i of n at lo + 0.3 + i in a box
// of length n: the first cell runs from the wall to 0.8, the last from
// n - 1.2 to the wall, the others are unit.
static double cut_edge(int i, int n)
{
    return i == 0 ? 0.8 : i == n - 1 ? 1.2 : 1.0;
}

static void cells_cut_by_the_walls(void **state)
{
    (void)state;
    const int nx = 6, ny = 4, nz = 5;
    const double W = nx, D = ny, H = nz;
    gf_packing p = {0};
    cubic(&p, W, D, 0.3, nx, ny, nz);
    size_t nlat = p.n;
    // Outside the box: below the base, beyond a wall, above the top, NaN.
    assert_int_equal(gf_packing_push(&p, 1001, 1, 0, 0, -0.4, 0.5), GF_OK);
    assert_int_equal(gf_packing_push(&p, 1002, 1, 3.5, 0, 2, 0.5), GF_OK);
    assert_int_equal(gf_packing_push(&p, 1003, 1, 0, 0, 5.2, 0.5), GF_OK);
    assert_int_equal(gf_packing_push(&p, 1004, 1, NAN, 0, 2, 0.5), GF_OK);
    double *vol = GF_NEW(double, p.n);
    assert_int_equal(gf_voronoi_volumes(&p, W, D, H, vol), GF_OK);
    double sum = 0;
    size_t q = 0;
    for (int k = 0; k < nz; k++)
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++, q++) {
                double expect = cut_edge(i, nx) * cut_edge(j, ny) * cut_edge(k, nz);
                gf_assert_near(vol[q], expect, 1e-9); // corners: 0.8^3 = 0.512, 1.2^3 = 1.728, ...
                sum += vol[q];
            }
    gf_assert_near(sum, W * D * H, 1e-9);
    for (size_t i = nlat; i < p.n; i++) assert_true(isnan(vol[i]));
    GF_DELETE(vol, p.n);
    gf_packing_free(&p);
}

static double uniform(uint64_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    return (double)(*s >> 11) * (1.0 / 9007199254740992.0);
}

static void random_cells_fill_the_box(void **state)
{
    (void)state;
    const double W = 10, D = 6, H = 9;
    gf_packing p = {0};
    uint64_t seed = 12345;
    for (int i = 0; i < 3000; i++)
        assert_int_equal(gf_packing_push(&p, i + 1, 1, W * (uniform(&seed) - 0.5), D * (uniform(&seed) - 0.5),
                                         H * uniform(&seed), 0.5),
                         GF_OK);
    double *vol = GF_NEW(double, p.n);
    assert_int_equal(gf_voronoi_volumes(&p, W, D, H, vol), GF_OK);
    double sum = 0;
    for (size_t i = 0; i < p.n; i++) {
        assert_true(vol[i] > 0.0);
        sum += vol[i];
    }
    gf_assert_near(sum, W * D * H, 1e-9 * W * D * H);
    // A degenerate box is refused rather than handed to Voro++.
    assert_int_equal(gf_voronoi_volumes(&p, W, D, 0.0, vol), GF_ERR_PARAM);
    GF_DELETE(vol, p.n);
    gf_packing_free(&p);
}

static void measure_on_a_cubic_lattice(void **state)
{
    (void)state;
    // 8 x 4 x 20 unit cubes: every cell is a unit cube except the top layer's
    // (z = 19.5, cell up to ztop = 20.5). The surface is the top two layers
    // (centres within 1.5 of the top, 19.5); the rest is bulk with phi = pi/6.
    const double W = 8, D = 4;
    gf_series s = gf_test_series(4, W, D);
    for (size_t k = 0; k < 4; k++) cubic(&s.frames[k].pk, W, D, 0.5, 8, 4, 20);
    gf_analysis_opts o = gf_analysis_opts_default(); // window: a quarter in, frames 1..3
    o.gr_x0 = -3;
    o.gr_x1 = 3;
    o.gr_z0 = 2;
    o.gr_z1 = 10;
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_voronoi(&s, &o, &out), GF_OK);
    gf_assert_near(gf_test_value(&out, "bulk_packing_fraction"), PI / 6, 1e-9);
    const gf_table *t = gf_test_table(&out, "voronoi");
    assert_int_equal(t->nrow, 8 * 4 * 20);
    assert_int_equal(t->ncol, 7);
    for (size_t i = 0; i < t->nrow; i++) {
        const double *row = t->v + i * t->ncol;
        double z = row[3];
        gf_assert_near(row[4], z == 19.5 ? PI / 6 / 1.5 : PI / 6, 1e-9);
        gf_assert_near(row[6], z < 18 ? 1.0 : 0.0, 0);
        // The field averages bulk cells only: pi/6 wherever one is within 2.2.
        gf_assert_near(row[5], PI / 6, 1e-9);
    }
    const gf_table *pr = gf_test_table(&out, "voronoi_profile");
    assert_int_equal(pr->nrow, 21); // slabs up to ztop = 20.5
    for (size_t k = 0; k < pr->nrow; k++) {
        const double *row = pr->v + k * 3;
        gf_assert_near(row[0], k + 0.5, 0);
        if (k < 18) {
            gf_assert_near(row[1], PI / 6, 1e-9);
            gf_assert_near(row[2], 32, 0);
        } else {
            assert_true(isnan(row[1]));
            gf_assert_near(row[2], 0, 0);
        }
    }
    assert_non_null(strstr(out.gnuplot, "voronoi.csv"));
    gf_measure_free(&out);
    gf_series_free(&s);
}

// Mean phi over the region's particles from the whole tessellation.
static double region_mean_phi(const gf_packing *p, const gf_analysis_opts *o, double W, double D)
{
    double zmax = 0;
    for (size_t i = 0; i < p->n; i++) zmax = fmax(zmax, p->z[i]);
    double *phi = GF_NEW(double, p->n);
    assert_int_equal(gf_voronoi_fraction(p, W, D, zmax + 1, phi), GF_OK);
    double sum = 0, n = 0;
    for (size_t i = 0; i < p->n; i++)
        if (p->x[i] > o->gr_x0 && p->x[i] < o->gr_x1 && p->z[i] > o->gr_z0 && p->z[i] < o->gr_z1) {
            sum += phi[i];
            n++;
        }
    GF_DELETE(phi, p->n);
    assert_true(n > 50);
    return sum / n;
}

static void measure_headline_equals_full_tessellation(void **state)
{
    (void)state;
    // The same packing in two frames: the first is measured from a sub-box
    // around the region, the last from the whole container. Both must give
    // the mean phi of the whole tessellation. First a dense random packing
    // built by the library (the sub-box is exact), then sparse random points
    // (cells too big for the sub-box: the whole tessellation is redone).
    gf_config c = gf_config_default();
    c.container_width = 16;
    c.container_depth = 6;
    c.packing_particles = 3000;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    gf_analysis_opts o = gf_analysis_opts_default();
    o.t0 = 0;
    o.t1 = 1;
    o.gr_x0 = -4;
    o.gr_x1 = 4;
    o.gr_z0 = 6;
    o.gr_z1 = 14; // far below the surface: every region particle is bulk
    for (int sparse = 0; sparse < 2; sparse++) {
        gf_series s = gf_test_series(2, c.container_width, c.container_depth);
        s.cfg = c;
        if (!sparse) {
            assert_int_equal(gf_packing_generate(&c, NULL, &s.frames[0].pk), GF_OK);
        } else {
            uint64_t seed = 777;
            for (int i = 0; i < 600; i++) // density 0.2 per d^3
                assert_int_equal(gf_packing_push(&s.frames[0].pk, i + 1, 1, 16 * (uniform(&seed) - 0.5),
                                                 6 * (uniform(&seed) - 0.5), 30 * uniform(&seed), 0.5),
                                 GF_OK);
        }
        const gf_packing *p = &s.frames[0].pk;
        for (size_t i = 0; i < p->n; i++)
            assert_int_equal(gf_packing_push(&s.frames[1].pk, p->id[i], 1, p->x[i], p->y[i], p->z[i], p->r[i]),
                             GF_OK);
        double expect = region_mean_phi(p, &o, c.container_width, c.container_depth);
        gf_measure_out out = {0};
        assert_int_equal(gf_measure_voronoi(&s, &o, &out), GF_OK);
        double bulk = gf_test_value(&out, "bulk_packing_fraction");
        gf_assert_near(bulk, expect, 1e-12);
        if (!sparse) assert_true(bulk > 0.55 && bulk < 0.68);
        else assert_true(bulk < 0.2);
        gf_measure_free(&out);
        gf_series_free(&s);
    }
}

// The averaged field by brute force on the lattice of cells_cut_by_the_walls:
// centres at -L/2 + 0.3 + i per axis, cells of edge cut_edge(i, n), box top
// at nz. Bulk: the centres more than 1.5 d below the top layer, that is layers
// k <= nz - 3 (layer nz - 2 is 1 d below the top, the top layer's cells reach
// the box top). The field at i: sum of pi/6 over the bulk j with |x_j - x_i|
// <= R, over the sum of their cell volumes. R = 2.2: squared lattice
// distances are whole numbers, none near 4.84, so no pair sits on the edge.
static void field_by_hand_on_a_cut_lattice(void **state)
{
    (void)state;
    const int nx = 7, ny = 5, nz = 8;
    const double W = nx, D = ny, R = 2.2;
    gf_packing p = {0};
    cubic(&p, W, D, 0.3, nx, ny, nz);
    size_t nlat = p.n;
    assert_int_equal(gf_packing_push(&p, 1001, 1, NAN, 0, 2, 0.5), GF_OK); // not in the box
    assert_int_equal(gf_packing_push(&p, 1002, 1, 0, 0, -0.4, 0.5), GF_OK); // below the base
    double *avg = GF_NEW(double, p.n);
    assert_int_equal(gf_voronoi_field(&p, W, D, nz, R, avg), GF_OK);
    size_t q = 0, wall = 0;
    for (int k = 0; k < nz; k++)
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++, q++) {
                double vp = 0, vc = 0;
                for (int c = 0; c <= nz - 3; c++)
                    for (int b = 0; b < ny; b++)
                        for (int a = 0; a < nx; a++) {
                            int d2 = (a - i) * (a - i) + (b - j) * (b - j) + (c - k) * (c - k);
                            if (d2 > R * R) continue;
                            vp += PI / 6;
                            vc += cut_edge(a, nx) * cut_edge(b, ny) * cut_edge(c, nz);
                        }
                assert_true(vc > 0); // even the top layer has bulk particles 2 d below it (2 < 2.2)
                double expect = vp / vc;
                gf_assert_near(avg[q], expect, 1e-12);
                wall += fabs(expect - PI / 6) > 1e-3; // the cut cells make the field differ from pi/6
            }
    assert_true(wall > nlat / 2);
    for (size_t i = nlat; i < p.n; i++) assert_true(isnan(avg[i]));
    // Radius 0: each bulk particle alone, pi/6 over its own cell; no one else.
    assert_int_equal(gf_voronoi_field(&p, W, D, nz, 0.0, avg), GF_OK);
    q = 0;
    for (int k = 0; k < nz; k++)
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++, q++) {
                if (k <= nz - 3) gf_assert_near(avg[q], PI / 6 / (cut_edge(i, nx) * cut_edge(j, ny) * cut_edge(k, nz)), 1e-12);
                else assert_true(isnan(avg[q])); // surface particles, no bulk particle within 0
            }
    // Bad arguments.
    assert_int_equal(gf_voronoi_field(&p, 0, D, nz, R, avg), GF_ERR_PARAM);
    assert_int_equal(gf_voronoi_field(&p, W, D, -1, R, avg), GF_ERR_PARAM);
    assert_int_equal(gf_voronoi_field(&p, W, D, INFINITY, R, avg), GF_ERR_PARAM);
    assert_int_equal(gf_voronoi_field(&p, W, D, nz, -0.5, avg), GF_ERR_PARAM);
    assert_int_equal(gf_voronoi_field(&p, W, D, nz, NAN, avg), GF_ERR_PARAM);
    GF_DELETE(avg, p.n);
    gf_packing_free(&p);
}

// On the lattice of measure_on_a_cubic_lattice (filling the box: every bulk
// cell a unit cube) the field is pi/6 everywhere, with the automatic top.
static void field_on_a_cubic_lattice(void **state)
{
    (void)state;
    const double W = 8, D = 4;
    gf_packing p = {0};
    cubic(&p, W, D, 0.5, 8, 4, 20);
    double *avg = GF_NEW(double, p.n);
    assert_int_equal(gf_voronoi_field(&p, W, D, NAN, 2.2, avg), GF_OK);
    for (size_t i = 0; i < p.n; i++) gf_assert_near(avg[i], PI / 6, 1e-9);
    GF_DELETE(avg, p.n);
    gf_packing_free(&p);
}

// The public field is the phi_avg column of gf_measure_voronoi on the same
// frame, to the last bit: one implementation. A dense random packing with a
// free surface, so bulk, surface and NaN-free neighbourhoods all occur; the
// automatic top and the explicit top (highest centre + 1) agree too.
static void field_equals_the_measure_column(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    c.container_width = 14;
    c.container_depth = 6;
    c.packing_particles = 2500;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    gf_series s = gf_test_series(1, c.container_width, c.container_depth);
    s.cfg = c;
    assert_int_equal(gf_packing_generate(&c, NULL, &s.frames[0].pk), GF_OK);
    const gf_packing *p = &s.frames[0].pk;
    gf_analysis_opts o = gf_analysis_opts_default();
    o.vor_avg_radius = 1.7; // not the default, to see that the radius is passed on
    gf_measure_out out = {0};
    assert_int_equal(gf_measure_voronoi(&s, &o, &out), GF_OK);
    const gf_table *t = gf_test_table(&out, "voronoi");
    assert_int_equal(t->nrow, p->n);
    double zmax = -INFINITY;
    for (size_t i = 0; i < p->n; i++) zmax = fmax(zmax, p->z[i]);
    double *avg = GF_NEW(double, p->n), *avg2 = GF_NEW(double, p->n);
    assert_int_equal(gf_voronoi_field(p, c.container_width, c.container_depth, NAN, o.vor_avg_radius, avg), GF_OK);
    assert_int_equal(gf_voronoi_field(p, c.container_width, c.container_depth, zmax + 1, o.vor_avg_radius, avg2),
                     GF_OK);
    size_t surface = 0, differs = 0;
    for (size_t i = 0; i < p->n; i++) {
        const double *row = t->v + i * t->ncol;
        assert_true(row[0] == (double)p->id[i]);
        double col = row[5];
        if (isnan(col)) {
            assert_true(isnan(avg[i]) && isnan(avg2[i]));
        } else {
            assert_true(avg[i] == col); // bit for bit
            assert_true(avg2[i] == col);
            assert_true(col > 0.45 && col < 0.7);
        }
        surface += row[6] == 0.0;
        differs += fabs(row[4] - col) > 1e-3; // the raw value is not the average
    }
    assert_true(surface > 100 && surface < p->n / 2); // a free surface of some 14 x 6 / 0.8 particles
    assert_true(differs > p->n / 2);
    GF_DELETE(avg, p->n);
    GF_DELETE(avg2, p->n);
    gf_measure_free(&out);
    gf_series_free(&s);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(unit_cells_of_a_cubic_lattice),
    cmocka_unit_test(cells_cut_by_the_walls),
    cmocka_unit_test(random_cells_fill_the_box),
    cmocka_unit_test(measure_on_a_cubic_lattice),
    cmocka_unit_test(measure_headline_equals_full_tessellation),
    cmocka_unit_test(field_by_hand_on_a_cut_lattice),
    cmocka_unit_test(field_on_a_cubic_lattice),
    cmocka_unit_test(field_equals_the_measure_column),
};

GF_TEST_MAIN("voronoi", tests)
