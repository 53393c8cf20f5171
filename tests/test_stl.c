// SPDX-License-Identifier: MIT
// Containers from STL (geom/stl.c, sdf.c, meshshape.c; docs/geometry.md,
// "Containers from STL"): the field and the walls of scripts/make-stl.py's
// box and hopper against the analytic box and cylinder at 10,000 random
// points near the walls (distances within 0.02 d, inside tests agreeing);
// every malformed mesh refused with its file, triangle and key; the path
// read from the INI file's folder; granflow dem refusing a mesh.
#include "support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "geom/container.h"
#include "geom/mesh.h"
#include "geom/meshshape.h"
#include "geom/stl.h"
#include "granflow/granflow.h"

#define GF_MAKE_STL GF_TEST_DATA "/../../scripts/make-stl.py"

static const char *make_stl(const char *kind, const char *name, const char *args)
{
    static char path[1024];
    snprintf(path, sizeof path, "%s/%s", gf_test_tmpdir(), name);
    char cmd[4096];
    snprintf(cmd, sizeof cmd, "python3 %s %s %s %s 2>/dev/null", GF_MAKE_STL, kind, path, args);
    assert_int_equal(system(cmd), 0);
    return path;
}

// The analytic distance: the nearest of the shape's walls (all within 3 d).
static double analytic_gap(const gf_container *c, const double p[3])
{
    gf_wall_hit hit[GF_WALL_HITS];
    int n = c->ops->walls(c, p, 3.0, hit);
    double g = 3.0;
    for (int k = 0; k < n; k++) g = fmin(g, hit[k].gap);
    return g;
}

static double uniform(uint64_t *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*s >> 11) * 0x1.0p-53;
}

// 10,000 points inside `ana` within 1.5 d of its walls, in the box lo..hi:
// the mesh's field and walls give the analytic distance within 0.02 d, and
// the inside tests agree (away from the walls by more than that).
static void compare(const gf_container *ana, const gf_container *mesh, const double lo[3], const double hi[3])
{
    uint64_t seed = 12345;
    int n = 0, tries = 0;
    double worst = 0.0, worst_walls = 0.0;
    while (n < 10000) {
        assert_true(++tries < 10000000);
        double p[3];
        for (int a = 0; a < 3; a++) p[a] = lo[a] + (hi[a] - lo[a]) * uniform(&seed);
        bool in_a = ana->ops->contains(ana, p[0], p[1], p[2], 0.0, 0.0);
        double d = gf_sdf_distance(&mesh->u.mesh->sdf, p, 3.0);
        if (in_a) {
            double g = analytic_gap(ana, p);
            if (g > 1.5) continue;
            worst = fmax(worst, fabs(d - g));
            if (fabs(d - g) > 0.02) fail_msg("(%g, %g, %g): field %g, analytic %g", p[0], p[1], p[2], d, g);
            double gw = analytic_gap(mesh, p);
            worst_walls = fmax(worst_walls, fabs(gw - g));
            if (fabs(gw - g) > 0.02) fail_msg("(%g, %g, %g): mesh walls %g, analytic %g", p[0], p[1], p[2], gw, g);
        }
        if (fabs(d) > 0.02 && (in_a != (d > 0.0) || in_a != gf_sdf_inside(&mesh->u.mesh->sdf, p)))
            fail_msg("(%g, %g, %g): inside %d analytic, field %g", p[0], p[1], p[2], in_a, d);
        if (in_a) n++;
    }
    print_message("%d points: field within %.4f d, walls within %.4f d of the analytic distances\n", n, worst,
                  worst_walls);
}

// Area of an outline's inside polygon (shoelace).
static double outline_area(const gf_outline *o)
{
    double a = 0.0;
    for (int j = 0; j < o->n; j++) {
        const double *p = o->p[j], *q = o->p[(j + 1) % o->n];
        a += p[0] * q[1] - p[1] * q[0];
    }
    return 0.5 * fabs(a);
}

// The ops beyond the engine's (the shape table's row): the slice y = 0 of
// the picture encloses what the analytic shape's does, the walls are two
// polylines, LAMMPS is refused with the reason, z_col and z_bottom agree.
static void other_ops_agree(const gf_container *ca, const gf_container *cm, double ztop)
{
    gf_outline oa, om;
    gf_container_outline(ca, ztop, &oa);
    gf_container_outline(cm, ztop, &om);
    double aa = outline_area(&oa), am = outline_area(&om);
    if (fabs(aa - am) > 0.01 * aa) fail_msg("outline area %g, analytic %g", am, aa);
    assert_true(om.nwall[0] >= 2 && om.nwall[1] >= 2);
    for (int j = 0; j < om.n; j++)
        assert_true(om.p[j][1] <= ztop && om.p[j][0] >= cm->xlo - 1e-9 && om.p[j][0] <= cm->xhi + 1e-9);
    assert_true(gf_container_lammps_walls(cm, NULL, NULL, NULL, 0.0, 0.0) == GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "LAMMPS' granular walls"));
    assert_true(gf_container_lammps_pour(cm, NULL, 0.0, 0.0, 1.0) == GF_ERR_PARAM);
    gf_error_clear();
    // A solid of revolution about z (the hopper) is measured as the cylinder
    // is, radially, out to its wall; the box across x.
    assert_int_equal(gf_container_profile_radial(cm), gf_container_profile_radial(ca));
    if (gf_container_profile_radial(ca) &&
        fabs(gf_container_outer_radius(cm) - gf_container_outer_radius(ca)) > 1e-6)
        fail_msg("outer radius %g, analytic %g", gf_container_outer_radius(cm), gf_container_outer_radius(ca));
    if (fabs(cm->z_col - ca->z_col) > 1.0) fail_msg("z_col %g, analytic %g", cm->z_col, ca->z_col);
    assert_true(fabs(cm->z_bottom - ca->z_bottom) < 1e-9);
    gf_mesh mesh;
    assert_int_equal(gf_container_mesh(cm, ztop, 64, &mesh), GF_OK);
    assert_int_equal(mesh.nt, cm->u.mesh->sdf.mesh.nt);
    gf_mesh_free(&mesh);
}

static void the_box_from_stl_matches_the_box(void **state)
{
    (void)state;
    const char *stl = make_stl("box", "box.stl", "--width 20 --depth 8 --height 40 --orifice 6 --orifice-x 2");
    gf_config a = gf_config_default(), m = gf_config_default();
    a.container_width = 20;
    a.orifice_diameter = 6;
    a.orifice_x = 2;
    assert_int_equal(gf_config_validate(&a), GF_OK);
    m.container_shape = GF_SHAPE_MESH;
    snprintf(m.container_mesh, sizeof m.container_mesh, "%s", stl);
    m.orifice_diameter = 6;
    m.orifice_x = 2;
    if (gf_config_validate(&m) != GF_OK) fail_msg("%s", gf_last_error());
    assert_true(m.container_width == 20 && m.container_depth == 8);
    gf_container ca = gf_container_make(&a), cm = gf_container_make(&m);
    assert_non_null(cm.u.mesh);
    compare(&ca, &cm, (double[3]){-10.5, -4.5, 0.001}, (double[3]){10.5, 4.5, 30});
    other_ops_agree(&ca, &cm, 30.0);
    gf_meshshape_cache_clear();
}

static void the_hopper_from_stl_matches_the_cylinder(void **state)
{
    (void)state;
    const char *stl = make_stl("hopper", "hopper.stl", "--radius 10 --angle 60 --outlet 6 --pipe 4 --height 50 --binary");
    gf_config a = gf_config_default(), m = gf_config_default();
    a.container_shape = GF_SHAPE_CYLINDER;
    a.container_radius = 10;
    a.hopper_angle = 60;
    a.outlet_diameter = 6;
    a.outlet_length = 4;
    assert_int_equal(gf_config_validate(&a), GF_OK);
    m.container_shape = GF_SHAPE_MESH;
    snprintf(m.container_mesh, sizeof m.container_mesh, "%s", stl);
    m.orifice_diameter = 6;
    m.exit_z = -4;
    if (gf_config_validate(&m) != GF_OK) fail_msg("%s", gf_last_error());
    gf_container ca = gf_container_make(&a), cm = gf_container_make(&m);
    assert_non_null(cm.u.mesh);
    // The cross-sections agree with the cylinder's (faceting: within 0.1%).
    for (double z = 0.5; z < 45; z += 2.5) { // (the cylinder's own area in its pipe is not pi r_o^2)
        double sa = ca.ops->section_area(&ca, z), sm = cm.ops->section_area(&cm, z);
        if (fabs(sa - sm) > 2e-3 * sa) fail_msg("z = %g: section %g, cylinder %g", z, sm, sa);
    }
    compare(&ca, &cm, (double[3]){-10.5, -10.5, -3.0}, (double[3]){10.5, 10.5, 40});
    other_ops_agree(&ca, &cm, 30.0);
    gf_meshshape_cache_clear();
}

// A square box is not a solid of revolution (its field differs between the
// faces and the corners), nor is a hopper whose outlet is off the axis.
static void only_solids_of_revolution_are_radial(void **state)
{
    (void)state;
    const char *box = make_stl("box", "square.stl", "--width 12 --depth 12 --height 30 --orifice 5");
    gf_config m = gf_config_default();
    m.container_shape = GF_SHAPE_MESH;
    snprintf(m.container_mesh, sizeof m.container_mesh, "%s", box);
    m.orifice_diameter = 5;
    if (gf_config_validate(&m) != GF_OK) fail_msg("%s", gf_last_error());
    gf_container c = gf_container_make(&m);
    assert_non_null(c.u.mesh);
    assert_false(gf_container_profile_radial(&c));
    const char *hop = make_stl("hopper", "hopper-r.stl", "--radius 7 --angle 60 --outlet 5 --pipe 2 --height 30");
    snprintf(m.container_mesh, sizeof m.container_mesh, "%s", hop);
    m.exit_z = -2;
    assert_int_equal(gf_config_validate(&m), GF_OK);
    c = gf_container_make(&m);
    assert_true(gf_container_profile_radial(&c));
    assert_true(fabs(gf_container_outer_radius(&c) - 7.0) < 1e-6);
    m.orifice_shape = GF_ORIFICE_SLIT; // the outlet's keys describe no disc about the axis
    if (gf_config_validate(&m) == GF_OK) {
        c = gf_container_make(&m);
        if (c.u.mesh) assert_false(gf_container_profile_radial(&c));
    }
    gf_error_clear();
    gf_meshshape_cache_clear();
}

// ---- malformed meshes -----------------------------------------------------------

// A closed cube [-2, 2]^2 x [0, 4] as ASCII STL; `mutate` edits its
// triangles (vertex order, normals) before it is written.
typedef struct cube_tri {
    double n[3], v[3][3];
} cube_tri;

static int cube(cube_tri *t)
{
    static const int q[6][4][3] = {
        {{-1, -1, -1}, {-1, 1, -1}, {1, 1, -1}, {1, -1, -1}}, // base, seen from below
        {{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}},     // lid
        {{-1, -1, -1}, {1, -1, -1}, {1, -1, 1}, {-1, -1, 1}}, // y = -2
        {{1, 1, -1}, {-1, 1, -1}, {-1, 1, 1}, {1, 1, 1}},     // y = 2
        {{-1, 1, -1}, {-1, -1, -1}, {-1, -1, 1}, {-1, 1, 1}}, // x = -2
        {{1, -1, -1}, {1, 1, -1}, {1, 1, 1}, {1, -1, 1}},     // x = 2
    };
    int n = 0;
    for (int f = 0; f < 6; f++)
        for (int h = 0; h < 2; h++) {
            const int idx[3] = {0, 1 + h, 2 + h};
            for (int k = 0; k < 3; k++) {
                t[n].v[k][0] = 2.0 * q[f][idx[k]][0];
                t[n].v[k][1] = 2.0 * q[f][idx[k]][1];
                t[n].v[k][2] = 2.0 + 2.0 * q[f][idx[k]][2];
            }
            memset(t[n].n, 0, sizeof t[n].n);
            n++;
        }
    return n;
}

static const char *write_cube(const char *name, const cube_tri *t, int n, const char *extra)
{
    static char text[16384];
    size_t len = (size_t)snprintf(text, sizeof text, "solid cube\n");
    for (int i = 0; i < n; i++) {
        len += (size_t)snprintf(text + len, sizeof text - len, "facet normal %g %g %g\nouter loop\n", t[i].n[0], t[i].n[1],
                                t[i].n[2]);
        for (int k = 0; k < 3; k++)
            len += (size_t)snprintf(text + len, sizeof text - len, "vertex %g %g %g\n", t[i].v[k][0], t[i].v[k][1],
                                    t[i].v[k][2]);
        len += (size_t)snprintf(text + len, sizeof text - len, "endloop\nendfacet\n");
    }
    snprintf(text + len, sizeof text - len, "%sendsolid cube\n", extra ? extra : "");
    return gf_test_write_file(gf_test_tmpdir(), name, text);
}

// Validating a mesh config of `path` fails with every one of `want` in the message.
static void refused(const char *path, const char *want1, const char *want2)
{
    gf_config c = gf_config_default();
    assert_int_equal(gf_config_set(&c, "container.shape=mesh", "--set"), GF_OK);
    char set[2048];
    snprintf(set, sizeof set, "container.mesh=%s", path);
    assert_int_equal(gf_config_set(&c, set, "--set"), GF_OK);
    assert_int_equal(gf_config_set(&c, "container.orifice_diameter=1", "--set"), GF_OK);
    gf_status st = gf_config_validate(&c);
    const char *msg = gf_last_error();
    if (st == GF_OK) fail_msg("%s: accepted, expected '%s'", path, want1);
    if (!strstr(msg, want1) || (want2 && !strstr(msg, want2)) || !strstr(msg, "container.mesh") || !strstr(msg, path))
        fail_msg("message '%s' lacks '%s' / '%s' / the key / the file", msg, want1, want2 ? want2 : "");
    print_message("%s\n", msg);
    gf_meshshape_cache_clear();
}

static void a_good_cube_is_accepted(void **state)
{
    (void)state;
    cube_tri t[12];
    int n = cube(t);
    const char *path = write_cube("good.stl", t, n, NULL);
    gf_config c = gf_config_default();
    c.container_shape = GF_SHAPE_MESH;
    snprintf(c.container_mesh, sizeof c.container_mesh, "%s", path);
    c.orifice_diameter = 1;
    if (gf_config_validate(&c) != GF_OK) fail_msg("%s", gf_last_error());
    gf_container b = gf_container_make(&c);
    assert_true(b.ops->contains(&b, 0, 0, 2, 0.5, 0));
    assert_false(b.ops->contains(&b, 1.8, 0, 2, 0.5, 0));
    gf_assert_near(b.ops->section_area(&b, 1.0), 16.0, 1e-9);
    gf_assert_near(b.ops->floor_z(&b, 1.0, 1.0, 0.5), 0.5, 1e-6);
    gf_meshshape_cache_clear();
}

static void malformed_meshes_are_refused(void **state)
{
    (void)state;
    cube_tri t[12];
    int n = cube(t);
    const char *dir = gf_test_tmpdir();
    refused(gf_test_write_file(dir, "text.stl", "hello, this is not a mesh\n"), "not an STL file", NULL);
    refused(gf_test_write_file(dir, "empty.stl", "solid x\nendsolid x\n"), "no triangles", NULL);
    refused(gf_test_write_file(dir, "nan.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex nan 0 0\n"),
            "not a finite number", "triangle 1");
    refused(gf_test_write_file(dir, "cut.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"),
            "expected 'vertex'", "triangle 1");
    refused(dir, "not a regular file", NULL);
    char missing[1024];
    snprintf(missing, sizeof missing, "%s/missing.stl", dir);
    refused(missing, "missing.stl", NULL);
    // A truncated binary: the header says 12 triangles, the file holds 5 and a bit.
    {
        unsigned char bin[84 + 50 * 5 + 20] = {0};
        bin[80] = 12;
        char p[1024];
        snprintf(p, sizeof p, "%s/short.stl", dir);
        FILE *f = fopen(p, "wb");
        assert_non_null(f);
        assert_int_equal(fwrite(bin, 1, sizeof bin, f), sizeof bin);
        fclose(f);
        refused(p, "truncated binary STL", "triangle 6");
    }
    cube_tri u[12];
    // Degenerate: triangle 4's vertices on one line.
    memcpy(u, t, sizeof u);
    memcpy(u[3].v[2], u[3].v[1], sizeof u[3].v[2]);
    u[3].v[2][0] += 1e-9;
    refused(write_cube("degenerate.stl", u, n, NULL), "triangle 4 is degenerate", NULL);
    // An inverted stored normal (triangle 5's points in).
    memcpy(u, t, sizeof u);
    u[4].n[1] = 1.0; // face y = -2: outward is -y
    refused(write_cube("normal.stl", u, n, NULL), "triangle 5", "inverted normal");
    // One triangle flipped: inconsistent orientation.
    memcpy(u, t, sizeof u);
    double tmp[3];
    memcpy(tmp, u[7].v[1], sizeof tmp);
    memcpy(u[7].v[1], u[7].v[2], sizeof tmp);
    memcpy(u[7].v[2], tmp, sizeof tmp);
    refused(write_cube("flipped.stl", u, n, NULL), "inconsistent orientation", "triangle");
    // Every triangle flipped: inside out.
    memcpy(u, t, sizeof u);
    for (int i = 0; i < n; i++) {
        memcpy(tmp, u[i].v[1], sizeof tmp);
        memcpy(u[i].v[1], u[i].v[2], sizeof tmp);
        memcpy(u[i].v[2], tmp, sizeof tmp);
    }
    refused(write_cube("inverted.stl", u, n, NULL), "inside out", "triangle 1");
    // A triangle missing from a wall: open away from the outlet.
    refused(write_cube("open.stl", t, n - 1, NULL), "is open", "watertight");
    // An edge shared by three triangles.
    memcpy(u, t, sizeof u);
    refused(write_cube("three.stl", u, n, "facet normal 0 0 0\nouter loop\nvertex -2 -2 0\nvertex 2 2 0\n"
                                          "vertex 0 0 -3\nendloop\nendfacet\n"),
            "shared by 3 triangles", "triangle 13");
    // Below the exit plane.
    memcpy(u, t, sizeof u);
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) u[i].v[k][2] -= 1.0;
    refused(write_cube("low.stl", u, n, NULL), "below the exit plane", "triangle");
    // Something after endsolid.
    refused(write_cube("tail.stl", t, n, "endsolid cube\ngarbage\n"), "after endsolid", NULL);
}

// A relative container.mesh is read from the INI file's folder, and
// `granflow dem` refuses a mesh container, saying why.
static void mesh_path_is_relative_to_the_ini(void **state)
{
    (void)state;
    cube_tri t[12];
    int n = cube(t);
    write_cube("cube.stl", t, n, NULL);
    const char *ini = gf_test_write_file(gf_test_tmpdir(), "cube.ini",
                                         "[container]\nshape = mesh\nmesh = cube.stl\norifice_diameter = 1\n");
    gf_config c = gf_config_default();
    assert_int_equal(gf_config_load(&c, ini), GF_OK);
    char want[1024];
    snprintf(want, sizeof want, "%s/cube.stl", gf_test_tmpdir());
    assert_string_equal(c.container_mesh, want);
    if (gf_config_validate(&c) != GF_OK) fail_msg("%s", gf_last_error());
    char out[1024];
    snprintf(out, sizeof out, "%s/dem", gf_test_tmpdir());
    assert_int_equal(gf_dem_write_inputs(&c, out, NULL, NULL), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "LAMMPS' granular walls"));
    assert_non_null(strstr(gf_last_error(), "cube.ini:2"));
    gf_meshshape_cache_clear();
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(the_box_from_stl_matches_the_box),
        cmocka_unit_test(the_hopper_from_stl_matches_the_cylinder),
        cmocka_unit_test(only_solids_of_revolution_are_radial),
        cmocka_unit_test(a_good_cube_is_accepted),
        cmocka_unit_test(malformed_meshes_are_refused),
        cmocka_unit_test(mesh_path_is_relative_to_the_ini),
    };
    return gf_test_run(argc, argv, "stl", tests, sizeof tests / sizeof tests[0]);
}
