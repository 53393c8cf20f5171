// SPDX-License-Identifier: MIT
// The built-in packing generator (SPEC 1.2): no overlaps, inside the walls,
// random with a bulk packing fraction of 0.58-0.64 and the g(r) of a random
// packing, sorted and tagged output, determinism, fill-to-height mode, bad
// input. Small containers keep every case to a few seconds under ASan.
#include "support.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "granflow/granflow.h"

// ---------------------------------------------------------------------------
// helpers

static gf_config box(double width, double depth, int64_t particles, uint64_t seed)
{
    gf_config c = gf_config_default();
    c.container_width = width;
    c.container_depth = depth;
    c.packing_particles = particles;
    c.packing_fill_height = 0.0;
    c.run_seed = seed;
    return c;
}

static void generate(const gf_config *c, gf_packing *p)
{
    gf_status st = gf_packing_generate(c, NULL, p);
    if (st != GF_OK) print_error("gf_packing_generate: %s: %s\n", gf_status_str(st), gf_last_error());
    assert_int_equal(st, GF_OK);
}

static double top_of(const gf_packing *p)
{
    double top = 0.0;
    for (size_t i = 0; i < p->n; i++) top = fmax(top, p->z[i]);
    return top;
}

/// The bulk region of a packing in container c: away from the side walls,
/// the base and the top (SPEC 1.2 "bulk").
typedef struct region {
    double x, y, z0, z1; // |x| < x, |y| < y, z0 < z < z1
} region;

static region bulk_of(const gf_config *c, const gf_packing *p)
{
    return (region){0.5 * c->container_width - 2.0, 0.5 * c->container_depth - 1.5, 2.0,
                    top_of(p) - 3.0};
}

static int in_region(const region *r, double x, double y, double z)
{
    return fabs(x) < r->x && fabs(y) < r->y && z > r->z0 && z < r->z1;
}

/// First index with z >= z0 in a packing sorted by z.
static size_t lower_z(const gf_packing *p, double z0)
{
    size_t lo = 0, hi = p->n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (p->z[mid] < z0)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/// Solid fraction of region r: the share of `samples` random points of r
/// that lie inside a sphere. Unlike a count of centres it does not depend on
/// where the region's faces cut the layers that form along flat walls.
static double solid_fraction(const gf_packing *p, const region *r, int samples)
{
    gf_rng rng;
    gf_rng_seed(&rng, 12345, 1);
    int inside = 0;
    for (int k = 0; k < samples; k++) {
        double x = r->x * (2.0 * gf_rng_uniform(&rng) - 1.0);
        double y = r->y * (2.0 * gf_rng_uniform(&rng) - 1.0);
        double z = r->z0 + (r->z1 - r->z0) * gf_rng_uniform(&rng);
        for (size_t i = lower_z(p, z - 0.5); i < p->n && p->z[i] <= z + 0.5; i++) {
            double dx = p->x[i] - x, dy = p->y[i] - y, dz = p->z[i] - z;
            if (dx * dx + dy * dy + dz * dz < p->r[i] * p->r[i]) {
                inside++;
                break;
            }
        }
    }
    return (double)inside / samples;
}

enum { RDF_BINS = 125 }; // bins of 0.02 d up to r = 2.5

/// Radial distribution function g(r) of a packing: centres in the bulk at
/// least RDF_BINS * dr from every face of region r, partners anywhere; pair
/// counts divided by (centres x density x shell volume). Bin k is centred on
/// r = k * dr, so a contact at r = 1 falls in the middle of its bin.
static void pair_correlation(const gf_packing *p, const region *r, double *g)
{
    const double dr = 0.02, rmax = (RDF_BINS - 0.5) * dr;
    region inner = {r->x - rmax, r->y - rmax, r->z0 + rmax, r->z1 - rmax};
    assert_true(inner.x > 0 && inner.y > 0 && inner.z1 > inner.z0);
    size_t in_bulk = 0, centres = 0;
    for (size_t i = 0; i < p->n; i++) in_bulk += in_region(r, p->x[i], p->y[i], p->z[i]);
    double density = (double)in_bulk / (4.0 * r->x * r->y * (r->z1 - r->z0));
    double count[RDF_BINS] = {0};
    for (size_t i = 0; i < p->n; i++) {
        if (!in_region(&inner, p->x[i], p->y[i], p->z[i])) continue;
        centres++;
        for (size_t j = lower_z(p, p->z[i] - rmax); j < p->n && p->z[j] <= p->z[i] + rmax; j++) {
            if (j == i) continue;
            double dx = p->x[j] - p->x[i], dy = p->y[j] - p->y[i], dz = p->z[j] - p->z[i];
            double d = sqrt(dx * dx + dy * dy + dz * dz);
            long k = lround(d / dr);
            if (k < RDF_BINS) count[k]++;
        }
    }
    assert_true(centres > 200);
    for (int k = 0; k < RDF_BINS; k++) {
        double a = fmax(0.0, (k - 0.5) * dr), b = (k + 0.5) * dr;
        double shell = 4.0 / 3.0 * 3.14159265358979323846 * (b * b * b - a * a * a);
        g[k] = count[k] / ((double)centres * density * shell);
    }
}

// ---------------------------------------------------------------------------
// geometry: distances, walls, ids, order, tags

static void no_overlap_inside_walls(void **state)
{
    (void)state;
    gf_config c = box(16, 8, 3000, 1);
    gf_packing p = {0};
    generate(&c, &p);
    assert_int_equal(p.n, 3000);
    double dmin = gf_packing_min_distance(&p);
    if (!(dmin >= 0.99)) print_error("closest pair %.6f < 0.99\n", dmin);
    assert_true(dmin >= 0.99);
    for (size_t i = 0; i < p.n; i++) {
        assert_true(fabs(p.x[i]) <= 8.0 - 0.5);
        assert_true(fabs(p.y[i]) <= 4.0 - 0.5);
        assert_true(p.z[i] >= 0.5);
        assert_true(p.r[i] == 0.5);
    }
    // Something rests on every wall and on the base.
    double xmax = 0, ymax = 0, zmin = INFINITY;
    for (size_t i = 0; i < p.n; i++) {
        xmax = fmax(xmax, fabs(p.x[i]));
        ymax = fmax(ymax, fabs(p.y[i]));
        zmin = fmin(zmin, p.z[i]);
    }
    gf_assert_near(xmax, 7.5, 1e-12);
    gf_assert_near(ymax, 3.5, 1e-12);
    gf_assert_near(zmin, 0.5, 1e-12);
    gf_packing_free(&p);
}

static void ids_order_and_layers(void **state)
{
    (void)state;
    gf_config c = box(16, 8, 2500, 3);
    c.packing_layer_thickness = 4.0;
    gf_packing p = {0};
    generate(&c, &p);
    assert_int_equal(p.n, 2500);
    int32_t top_layer = 0;
    for (size_t i = 0; i < p.n; i++) {
        assert_int_equal(p.id[i], (int64_t)i + 1); // ids 1..N in height order
        if (i > 0) assert_true(p.z[i] >= p.z[i - 1]);
        assert_int_equal(p.layer[i], 1 + (int32_t)floor(p.z[i] / 4.0));
        if (p.layer[i] > top_layer) top_layer = p.layer[i];
    }
    assert_int_equal(p.layer[0], 1);
    assert_true(top_layer >= 4); // the column is ~17 d tall
    gf_packing_free(&p);
}

// ---------------------------------------------------------------------------
// randomness: packing fraction and g(r)

static void bulk_fraction(void **state)
{
    (void)state;
    // A square section: the wall-induced layers are a small part of the bulk
    // region, so counting centres measures the fraction fairly.
    gf_config c = box(16, 16, 5000, 2);
    gf_packing p = {0};
    generate(&c, &p);
    region r = bulk_of(&c, &p);
    double phi = gf_packing_fraction(&p, -r.x, r.x, -r.y, r.y, r.z0, r.z1);
    print_message("16 x 16, 5000 spheres: top %.2f, bulk phi (centres) %.4f\n", top_of(&p), phi);
    assert_true(phi >= 0.58 && phi <= 0.64);
    double solid = solid_fraction(&p, &r, 40000);
    print_message("                       bulk solid fraction %.4f\n", solid);
    assert_true(solid >= 0.58 && solid <= 0.64);
    gf_packing_free(&p);

    // The silo's 8 d depth: layers along the front and back walls make a
    // count of centres depend on where |y| < 2.5 cuts them; the solid
    // fraction does not.
    c = box(16, 8, 3000, 2);
    generate(&c, &p);
    r = bulk_of(&c, &p);
    solid = solid_fraction(&p, &r, 40000);
    print_message("16 x 8, 3000 spheres: bulk solid fraction %.4f\n", solid);
    assert_true(solid >= 0.58 && solid <= 0.64);
    gf_packing_free(&p);
}

static void pair_correlation_is_amorphous(void **state)
{
    (void)state;
    gf_config c = box(16, 16, 5000, 4);
    gf_packing p = {0};
    generate(&c, &p);
    region r = bulk_of(&c, &p);
    double g[RDF_BINS];
    pair_correlation(&p, &r, g);
    // Nothing closer than contact: g = 0 below r = 0.98.
    for (int k = 0; (k + 0.5) * 0.02 <= 0.98 + 1e-9; k++) {
        if (!(g[k] < 0.1)) print_error("g(%.2f) = %.3f\n", k * 0.02, g[k]);
        assert_true(g[k] < 0.1);
    }
    // The first (contact) peak, the highest value below r = 1.3.
    int peak = 0;
    for (int k = 1; k * 0.02 < 1.3; k++)
        if (g[k] > g[peak]) peak = k;
    print_message("g(r): first peak %.3f at r = %.2f; g(1.41) %.2f, g(1.73) %.2f, g(2.00) %.2f\n",
                  g[peak], peak * 0.02, g[70], g[87], g[100]);
    assert_true(peak * 0.02 >= 1.0 - 1e-9 && peak * 0.02 <= 1.1 + 1e-9);
    assert_true(g[peak] > 3.0);
    // Amorphous, not crystal: no peak at sqrt(2) (face-centred cubic's
    // second shell), the split second peak of random packings at sqrt(3)
    // and 2 instead.
    double at_sqrt2 = (g[70] + g[71] + g[72]) / 3.0, at_sqrt3 = (g[86] + g[87] + g[88]) / 3.0,
           at_2 = (g[99] + g[100] + g[101]) / 3.0;
    assert_true(at_sqrt2 < 1.0);
    assert_true(at_sqrt3 > at_sqrt2 && at_2 > at_sqrt2);
    // Far out, g(r) -> 1.
    double tail = 0.0;
    for (int k = 110; k < RDF_BINS; k++) tail += g[k] / (RDF_BINS - 110);
    assert_true(tail > 0.8 && tail < 1.2);
    gf_packing_free(&p);
}

// ---------------------------------------------------------------------------
// determinism, fill height, odd containers, bad input

static void same_seed_same_bits(void **state)
{
    (void)state;
    gf_config c = box(16, 8, 2000, 7);
    gf_packing a = {0}, b = {0}, d = {0};
    generate(&c, &a);
    generate(&c, &b);
    assert_int_equal(a.n, b.n);
    assert_memory_equal(a.x, b.x, a.n * sizeof *a.x);
    assert_memory_equal(a.y, b.y, a.n * sizeof *a.y);
    assert_memory_equal(a.z, b.z, a.n * sizeof *a.z);
    assert_memory_equal(a.id, b.id, a.n * sizeof *a.id);
    assert_memory_equal(a.layer, b.layer, a.n * sizeof *a.layer);
    c.run_seed = 8;
    generate(&c, &d);
    assert_int_equal(d.n, a.n);
    assert_true(memcmp(a.x, d.x, a.n * sizeof *a.x) != 0);
    assert_true(memcmp(a.z, d.z, a.n * sizeof *a.z) != 0);
    gf_packing_free(&a);
    gf_packing_free(&b);
    gf_packing_free(&d);
}

static void fill_to_height(void **state)
{
    (void)state;
    gf_config c = box(16, 8, 1, 5); // packing_particles is ignored
    c.packing_fill_height = 15.0;
    gf_packing p = {0};
    generate(&c, &p);
    double top = top_of(&p);
    print_message("fill 15: %zu spheres, top centre %.3f\n", p.n, top);
    assert_true(top <= 15.0 - 0.5); // every sphere below the fill height
    assert_true(top >= 15.0 - 1.5); // and the column reaches it
    // The count fits the volume at a fraction (walls included) of 0.55-0.64.
    double per = (3.14159265358979323846 / 6.0) / (16.0 * 8.0 * 15.0);
    assert_true((double)p.n * per > 0.55 && (double)p.n * per < 0.64);
    assert_true(gf_packing_min_distance(&p) >= 0.99);
    for (size_t i = 0; i < p.n; i++) assert_int_equal(p.id[i], (int64_t)i + 1);
    gf_packing_free(&p);

    // packing.particles (1 here, not its default) was set but is not used: a
    // warning says so (a --set packing.particles over an example with
    // fill_height was silently ignored).
    assert_true(gf_warning_count() >= 1);
    assert_non_null(strstr(gf_warning(gf_warning_count() - 1), "packing.particles = 1 is ignored"));
    gf_warnings_clear();

    // One diameter: a single layer on the base.
    c.packing_fill_height = 1.0;
    generate(&c, &p);
    assert_true(p.n > 80);
    for (size_t i = 0; i < p.n; i++) assert_true(p.z[i] == 0.5);
    assert_true(gf_packing_min_distance(&p) >= 0.99);
    gf_packing_free(&p);
}

static void odd_containers(void **state)
{
    (void)state;
    struct {
        double w, d;
        int64_t n;
    } cases[] = {
        {1, 1, 30},     // a single file: a vertical stack
        {2, 1.5, 200},  // narrower than two diameters
        {100, 100, 10}, // a few spheres on a wide floor
        {16, 8, 1},     // one sphere
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        gf_config c = box(cases[k].w, cases[k].d, cases[k].n, 11);
        gf_packing p = {0};
        generate(&c, &p);
        assert_int_equal(p.n, (size_t)cases[k].n);
        assert_true(gf_packing_min_distance(&p) >= 0.99);
        for (size_t i = 0; i < p.n; i++) {
            assert_true(fabs(p.x[i]) <= 0.5 * cases[k].w - 0.5);
            assert_true(fabs(p.y[i]) <= 0.5 * cases[k].d - 0.5);
            assert_true(p.z[i] >= 0.5);
        }
        gf_packing_free(&p);
    }
    // The single file is a stack of touching spheres.
    gf_config c = box(1, 1, 30, 11);
    gf_packing p = {0};
    generate(&c, &p);
    for (size_t i = 0; i < p.n; i++) {
        assert_true(p.x[i] == 0.0 && p.y[i] == 0.0);
        gf_assert_near(p.z[i], 0.5 + (double)i, 0.01 * (double)(i + 1));
    }
    gf_packing_free(&p);
}

static void expect_param_error(const gf_config *c, const char *phrase)
{
    gf_packing p = {0};
    assert_int_equal(gf_packing_push(&p, 1, 1, 0.0, 0.0, 0.5, 0.5), GF_OK);
    gf_status st = gf_packing_generate(c, NULL, &p);
    if (st != GF_ERR_PARAM) print_error("status %s, message \"%s\"\n", gf_status_str(st), gf_last_error());
    assert_int_equal(st, GF_ERR_PARAM);
    assert_int_equal(p.n, 0); // comes back empty
    assert_null(p.x);
    if (!strstr(gf_last_error(), phrase)) {
        print_error("message \"%s\" does not contain \"%s\"\n", gf_last_error(), phrase);
        fail();
    }
}

static void bad_input(void **state)
{
    (void)state;
    gf_config c = box(16, 8, 0, 1);
    expect_param_error(&c, "number of particles");
    c.packing_particles = -5;
    expect_param_error(&c, "number of particles");
    c = box(0.9, 8, 100, 1);
    expect_param_error(&c, "cannot hold");
    c = box(16, NAN, 100, 1);
    expect_param_error(&c, "cannot hold");
    c = box(16, 8, 100, 1);
    c.packing_fill_height = 0.7;
    expect_param_error(&c, "fill height");
    c.packing_fill_height = INFINITY;
    expect_param_error(&c, "fill height");
    c = box(16, 8, 100, 1);
    c.packing_layer_thickness = 0.0;
    expect_param_error(&c, "layer thickness");
    c = box(16, 8, (int64_t)1 << 40, 1);
    expect_param_error(&c, "limit");
    gf_packing p = {0};
    assert_int_equal(gf_packing_generate(NULL, NULL, &p), GF_ERR_PARAM);
    assert_int_equal(gf_packing_generate(&c, NULL, NULL), GF_ERR_PARAM);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(no_overlap_inside_walls),
    cmocka_unit_test(ids_order_and_layers),
    cmocka_unit_test(bulk_fraction),
    cmocka_unit_test(pair_correlation_is_amorphous),
    cmocka_unit_test(same_seed_same_bits),
    cmocka_unit_test(fill_to_height),
    cmocka_unit_test(odd_containers),
    cmocka_unit_test(bad_input),
};

GF_TEST_MAIN("pack", tests)
