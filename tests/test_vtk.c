// SPDX-License-Identifier: MIT
// VTK output (output.format = vtk | both, src/io/vtk.c): the .vtu snapshots
// read back with the right particle count and values, and the container
// surface (container.vtk) is a valid polydata whose area is the walls' and
// the base's minus the hole.
#include "support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geom/mesh.h"
#include "granflow/granflow.h"
#include "io/vtk.h"

static const double PI = 3.14159265358979323846;

// The numbers of the DataArray named `name` (or the first without a name
// when name is NULL) in a .vtu text: up to max of them into v; returns how many.
static size_t vtu_array(const char *text, const char *name, double *v, size_t max)
{
    char key[64];
    const char *p = text;
    if (name) {
        snprintf(key, sizeof key, "Name=\"%s\"", name);
        p = strstr(text, key);
    } else {
        p = strstr(text, "<Points>");
        if (p) p = strstr(p, "<DataArray");
    }
    assert_non_null(p);
    p = strchr(p, '>');
    assert_non_null(p);
    const char *end = strstr(p, "</DataArray>");
    assert_non_null(end);
    size_t n = 0;
    for (char *q = (char *)p + 1; q < end;) {
        char *after;
        double x = strtod(q, &after);
        if (after == q) break;
        if (n < max) v[n] = x;
        n++;
        q = after;
    }
    return n;
}

static void particles_read_back(void **state)
{
    (void)state;
    gf_packing pk = {0};
    for (int i = 0; i < 5; i++) assert_int_equal(gf_packing_push(&pk, 10 + i, 1 + i / 2, i, -i, 2.0 * i, 0.5 + 0.1 * i), GF_OK);
    int32_t pass[5] = {1, 2, 3, 1, 7};
    char path[600];
    snprintf(path, sizeof path, "%s/five.vtu", gf_test_tmpdir());
    assert_int_equal(gf_vtk_write_particles(path, &pk, pass, 3.5), GF_OK);
    size_t len;
    char *t = gf_test_read_file(path, &len);
    assert_non_null(strstr(t, "<VTKFile type=\"UnstructuredGrid\""));
    assert_non_null(strstr(t, "NumberOfPoints=\"5\" NumberOfCells=\"5\""));
    double v[16];
    assert_int_equal(vtu_array(t, "id", v, 16), 5);
    assert_true(v[0] == 10 && v[4] == 14);
    assert_int_equal(vtu_array(t, "pass", v, 16), 5);
    assert_true(v[1] == 2 && v[4] == 7);
    assert_int_equal(vtu_array(t, "radius", v, 16), 5);
    gf_assert_near(v[3], 0.8, 1e-12);
    assert_int_equal(vtu_array(t, "layer", v, 16), 5);
    assert_true(v[4] == 3);
    assert_int_equal(vtu_array(t, NULL, v, 16), 15); // x y z per point
    assert_true(v[12] == 4 && v[13] == -4 && v[14] == 8);
    assert_int_equal(vtu_array(t, "TIME", v, 16), 1);
    assert_true(v[0] == 3.5);
    assert_int_equal(vtu_array(t, "types", v, 16), 5);
    free(t);
    gf_packing_free(&pk);
}

// Area of the triangles of a legacy VTK polydata file; checks its indices.
static double vtk_area(const char *path)
{
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    char line[256];
    size_t nv = 0, nt = 0, tot = 0;
    while (fgets(line, sizeof line, f) && sscanf(line, "POINTS %zu double", &nv) != 1) {}
    assert_true(nv > 0);
    double(*v)[3] = malloc(sizeof *v * nv);
    assert_non_null(v);
    for (size_t i = 0; i < nv; i++) assert_int_equal(fscanf(f, "%lf %lf %lf", &v[i][0], &v[i][1], &v[i][2]), 3);
    assert_int_equal(fscanf(f, " POLYGONS %zu %zu", &nt, &tot), 2);
    assert_int_equal(tot, 4 * nt);
    double area = 0.0;
    for (size_t k = 0; k < nt; k++) {
        size_t c, a, b, d;
        assert_int_equal(fscanf(f, "%zu %zu %zu %zu", &c, &a, &b, &d), 4);
        assert_int_equal(c, 3);
        assert_true(a < nv && b < nv && d < nv);
        double u[3], w[3];
        for (int j = 0; j < 3; j++) {
            u[j] = v[b][j] - v[a][j];
            w[j] = v[d][j] - v[a][j];
        }
        double cx = u[1] * w[2] - u[2] * w[1], cy = u[2] * w[0] - u[0] * w[2], cz = u[0] * w[1] - u[1] * w[0];
        area += 0.5 * sqrt(cx * cx + cy * cy + cz * cz);
    }
    fclose(f);
    free(v);
    return area;
}

// A short run with output.format = both writes a .vtu beside each dump with
// the dump's particles (same ids, same count), and container.vtk: side walls
// 2 (W + D) H plus the base W D less the hole pi R^2 (to the polygon's 0.1%).
static void run_writes_vtk(void **state)
{
    (void)state;
    gf_config c = gf_test_silo_config(10, 300, 2);
    c.orifice_diameter = 4;
    c.run_duration = 0.2;
    c.output_snapshot_interval = 0.2;
    c.output_format = GF_OUTPUT_BOTH;
    char dir[600], path[700];
    snprintf(dir, sizeof dir, "%s/vtkrun", gf_test_tmpdir());
    gf_run_opts o = {.dir = dir, .force = 1};
    assert_int_equal(gf_run_dir(&c, &o, NULL), GF_OK);
    double top0 = 1.0;
    for (int k = 0; k <= 1; k++) {
        snprintf(path, sizeof path, "%s/snapshots/snap_%06d.dump", dir, k);
        gf_packing pk = {0};
        assert_int_equal(gf_packing_read(path, GF_FORMAT_LAMMPS, &pk), GF_OK);
        for (size_t i = 0; k == 0 && i < pk.n; i++) top0 = fmax(top0, pk.z[i] + pk.r[i] + 1.0);
        snprintf(path, sizeof path, "%s/snapshots/snap_%06d.vtu", dir, k);
        size_t len;
        char *t = gf_test_read_file(path, &len);
        double *v = malloc(sizeof *v * 3 * pk.n);
        assert_non_null(v);
        assert_int_equal(vtu_array(t, "id", v, pk.n), pk.n);
        for (size_t i = 0; i < pk.n; i++) assert_true(v[i] == (double)pk.id[i]);
        assert_int_equal(vtu_array(t, NULL, v, 3 * pk.n), 3 * pk.n);
        free(v);
        free(t);
        gf_packing_free(&pk);
    }
    snprintf(path, sizeof path, "%s/container.vtk", dir);
    // The walls reach a diameter above the top of the packing at t = 0.
    double area = vtk_area(path), W = 10, D = 8, R = 2, base = W * D - PI * R * R;
    gf_assert_near(area, 2.0 * (W + D) * top0 + base, 1e-3 * PI * R * R);
    gf_container box = gf_container_make(&c);
    gf_mesh m;
    // And the mesh function itself at a known height.
    snprintf(path, sizeof path, "%s/box.vtk", gf_test_tmpdir());
    assert_int_equal(gf_container_mesh(&box, 7.0, 96, &m), GF_OK);
    assert_int_equal(gf_vtk_write_mesh(path, &m, "test"), GF_OK);
    gf_mesh_free(&m);
    gf_assert_near(vtk_area(path), 2.0 * (W + D) * 7.0 + base, 1e-3 * PI * R * R);
}

// A cylinder's container.vtk: wall, 45 degree funnel, outlet pipe and central
// column, each a surface of revolution whose area is known by hand (it used
// to be drawn as the bounding box with a flat base).
static void cylinder_mesh_areas(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    c.container_shape = GF_SHAPE_CYLINDER;
    c.container_radius = 5.0;
    c.hopper_angle = 45.0;
    c.outlet_diameter = 2.0;
    c.outlet_length = 3.0;
    c.inner_radius = 1.5;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    gf_container cyl = gf_container_make(&c);
    gf_mesh m;
    char path[700];
    snprintf(path, sizeof path, "%s/cylinder.vtk", gf_test_tmpdir());
    assert_int_equal(gf_container_mesh(&cyl, 12.0, 96, &m), GF_OK);
    assert_int_equal(gf_vtk_write_mesh(path, &m, "test"), GF_OK);
    gf_mesh_free(&m);
    // z_top = (R - r_out) tan 45 = 4: wall 2 pi 5 (12 - 4), cone pi (5 + 1) 4 sqrt 2,
    // pipe 2 pi 1 3, column side 2 pi 1.5 (12 - 4) and its bottom pi 1.5^2.
    double want = PI * (80.0 + 24.0 * sqrt(2.0) + 6.0 + 24.0 + 2.25);
    gf_assert_near(vtk_area(path), want, 1e-3 * want); // 96-gons: within 2e-4
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(particles_read_back),
    cmocka_unit_test(run_writes_vtk),
    cmocka_unit_test(cylinder_mesh_areas),
};

GF_TEST_MAIN("vtk", tests)
