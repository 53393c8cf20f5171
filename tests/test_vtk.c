// SPDX-License-Identifier: MIT
// VTK output (output.format = vtk | both, src/io/vtk.c): the .vtu snapshots
// read back (decompressed here with zlib, independently of the writer) with
// the right particle count, values and time, snapshots.pvd lists them with
// their times, and the container surfaces (container.vtk, container.vtp) are
// valid polydata whose area is the walls' and the base's minus the hole.
// python/tests/test_vtk_readback.py reads the same files with VTK and meshio.
#include "support.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "geom/mesh.h"
#include "granflow/granflow.h"
#include "io/vtk.h"

static const double PI = 3.14159265358979323846;

// One value of VTK type `type` at p, as a double.
static double vtu_value(const char *type, const unsigned char *p)
{
    if (!strcmp(type, "Float64")) {
        double v;
        memcpy(&v, p, 8);
        return v;
    }
    if (!strcmp(type, "Int64")) {
        int64_t v;
        memcpy(&v, p, 8);
        return (double)v;
    }
    if (!strcmp(type, "Int32")) {
        int32_t v;
        memcpy(&v, p, 4);
        return v;
    }
    assert_string_equal(type, "UInt8");
    return *p;
}

// The values of an appended, zlib-compressed array (header_type UInt64) at
// byte `offset` of the raw block starting at `data`: up to max into v.
static size_t vtu_appended(const unsigned char *data, const unsigned char *end, uint64_t offset, const char *type,
                           double *v, size_t max)
{
    const unsigned char *p = data + offset;
    uint64_t h[3];
    assert_true(p + 24 <= end);
    memcpy(h, p, 24);
    const uint64_t nb = h[0], bs = h[1], last = h[2];
    size_t width = !strcmp(type, "UInt8") ? 1 : !strcmp(type, "Int32") ? 4 : 8, n = 0;
    const unsigned char *z = p + 24 + 8 * nb;
    unsigned char *buf = malloc(bs ? bs : 1);
    assert_non_null(buf);
    for (uint64_t b = 0; b < nb; b++) {
        uint64_t cs;
        memcpy(&cs, p + 24 + 8 * b, 8);
        assert_true(z + cs <= end);
        uLongf len = (uLongf)bs;
        assert_int_equal(uncompress(buf, &len, z, (uLong)cs), Z_OK);
        assert_int_equal(len, b + 1 < nb ? bs : last);
        for (size_t i = 0; i + width <= len; i += width, n++)
            if (n < max) v[n] = vtu_value(type, buf + i);
        z += cs;
    }
    free(buf);
    return n;
}

// The numbers of the DataArray named `name` (or the first without a name
// when name is NULL) in a .vtu or .vtp file's text (len bytes), ASCII or
// appended: up to max of them into v; returns how many.
static size_t vtu_array(const char *text, size_t len, const char *name, double *v, size_t max)
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
    const char *el = p;
    while (el > text && strncmp(el, "<DataArray", 10) != 0) el--;
    char type[16] = "";
    assert_int_equal(sscanf(strstr(el, "type=\"") + 6, "%15[A-Za-z0-9]", type), 1);
    p = strchr(p, '>');
    assert_non_null(p);
    const char *fmt = strstr(el, "format=\"appended\"");
    if (fmt && fmt < p) {
        unsigned long long off;
        assert_int_equal(sscanf(strstr(el, "offset=\"") + 8, "%llu", &off), 1);
        const char *data = strstr(text, "<AppendedData encoding=\"raw\">");
        assert_non_null(data);
        data = strchr(data, '_') + 1;
        return vtu_appended((const unsigned char *)data, (const unsigned char *)text + len, off, type, v, max);
    }
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

// The five particles written in both encodings read back the same.
static void particles_read_back(void **state)
{
    (void)state;
    gf_packing pk = {0};
    for (int i = 0; i < 5; i++) assert_int_equal(gf_packing_push(&pk, 10 + i, 1 + i / 2, i, -i, 2.0 * i, 0.5 + 0.1 * i), GF_OK);
    int32_t pass[5] = {1, 2, 3, 1, 7};
    char path[600];
    for (int e = 0; e < 2; e++) {
        gf_vtk_encoding enc = e ? GF_VTK_ASCII : GF_VTK_BINARY;
        snprintf(path, sizeof path, "%s/five%d.vtu", gf_test_tmpdir(), e);
        assert_int_equal(gf_vtk_write_particles_as(path, &pk, pass, 3.5, enc), GF_OK);
        size_t len;
        char *t = gf_test_read_file(path, &len);
        assert_non_null(strstr(t, "<VTKFile type=\"UnstructuredGrid\""));
        assert_true((strstr(t, "compressor=\"vtkZLibDataCompressor\"") != NULL) == (enc == GF_VTK_BINARY));
        assert_non_null(strstr(t, "NumberOfPoints=\"5\" NumberOfCells=\"5\""));
        double v[16];
        assert_int_equal(vtu_array(t, len, "id", v, 16), 5);
        assert_true(v[0] == 10 && v[4] == 14);
        assert_int_equal(vtu_array(t, len, "pass", v, 16), 5);
        assert_true(v[1] == 2 && v[4] == 7);
        assert_int_equal(vtu_array(t, len, "radius", v, 16), 5);
        gf_assert_near(v[3], 0.8, 1e-12);
        assert_int_equal(vtu_array(t, len, "layer", v, 16), 5);
        assert_true(v[4] == 3);
        assert_int_equal(vtu_array(t, len, NULL, v, 16), 15); // x y z per point
        assert_true(v[12] == 4 && v[13] == -4 && v[14] == 8);
        assert_int_equal(vtu_array(t, len, "TimeValue", v, 16), 1); // the name ParaView reads
        assert_true(v[0] == 3.5);
        assert_int_equal(vtu_array(t, len, "types", v, 16), 5);
        assert_true(v[0] == 1 && v[4] == 1); // vertex cells
        double back;
        assert_int_equal(gf_vtk_read_time(path, &back), GF_OK);
        assert_true(back == 3.5);
        free(t);
    }
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

// Area of the triangles of a .vtp (XML polydata, appended or ASCII).
static double vtp_area(const char *path)
{
    size_t len;
    char *t = gf_test_read_file(path, &len);
    assert_non_null(t);
    assert_non_null(strstr(t, "<VTKFile type=\"PolyData\""));
    size_t nv, nt;
    const char *piece = strstr(t, "<Piece ");
    assert_non_null(piece);
    assert_int_equal(sscanf(strstr(piece, "NumberOfPoints=\"") + 16, "%zu", &nv), 1);
    assert_int_equal(sscanf(strstr(piece, "NumberOfPolys=\"") + 15, "%zu", &nt), 1);
    double *v = malloc(sizeof *v * 3 * nv), *c = malloc(sizeof *c * 3 * nt), *o = malloc(sizeof *o * nt);
    assert_true(v && c && o);
    assert_int_equal(vtu_array(t, len, NULL, v, 3 * nv), 3 * nv);
    assert_int_equal(vtu_array(t, len, "connectivity", c, 3 * nt), 3 * nt);
    assert_int_equal(vtu_array(t, len, "offsets", o, nt), nt);
    double area = 0.0;
    for (size_t k = 0; k < nt; k++) {
        assert_true(o[k] == 3.0 * (double)(k + 1));
        size_t a = (size_t)c[3 * k], b = (size_t)c[3 * k + 1], d = (size_t)c[3 * k + 2];
        assert_true(a < nv && b < nv && d < nv);
        double u[3], w[3];
        for (int j = 0; j < 3; j++) {
            u[j] = v[3 * b + j] - v[3 * a + j];
            w[j] = v[3 * d + j] - v[3 * a + j];
        }
        double cx = u[1] * w[2] - u[2] * w[1], cy = u[2] * w[0] - u[0] * w[2], cz = u[0] * w[1] - u[1] * w[0];
        area += 0.5 * sqrt(cx * cx + cy * cy + cz * cz);
    }
    free(v);
    free(c);
    free(o);
    free(t);
    return area;
}

// A short run with output.format = both writes a .vtu beside each dump with
// the dump's particles (same ids, same count) and its time, snapshots.pvd
// listing them with their times, and container.vtk and container.vtp: side
// walls 2 (W + D) H plus the base W D less the hole pi R^2 (to the polygon's 0.1%).
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
        assert_int_equal(vtu_array(t, len, "id", v, pk.n), pk.n);
        for (size_t i = 0; i < pk.n; i++) assert_true(v[i] == (double)pk.id[i]);
        assert_int_equal(vtu_array(t, len, NULL, v, 3 * pk.n), 3 * pk.n);
        for (size_t i = 0; i < pk.n; i++) gf_assert_near(v[3 * i + 2], pk.z[i], 1e-7); // the dump's %.7f
        assert_int_equal(vtu_array(t, len, "TimeValue", v, 1), 1);
        assert_true(v[0] == 0.2 * k);
        free(v);
        free(t);
        gf_packing_free(&pk);
    }
    snprintf(path, sizeof path, "%s/container.vtk", dir);
    // The walls reach a diameter above the top of the packing at t = 0.
    double area = vtk_area(path), W = 10, D = 8, R = 2, base = W * D - PI * R * R;
    gf_assert_near(area, 2.0 * (W + D) * top0 + base, 1e-3 * PI * R * R);
    // container.vtp: the same surface as XML polydata.
    snprintf(path, sizeof path, "%s/container.vtp", dir);
    gf_assert_near(vtp_area(path), area, 1e-9 * area);
    // snapshots.pvd: both snapshots with their times.
    snprintf(path, sizeof path, "%s/snapshots.pvd", dir);
    char *pvd = gf_test_read_file(path, NULL);
    assert_non_null(pvd);
    assert_non_null(strstr(pvd, "<VTKFile type=\"Collection\""));
    assert_non_null(strstr(pvd, "<DataSet timestep=\"0\" part=\"0\" file=\"snapshots/snap_000000.vtu\"/>"));
    assert_non_null(strstr(pvd, "<DataSet timestep=\"0.20000000000000001\" part=\"0\" file=\"snapshots/snap_000001.vtu\"/>"));
    free(pvd);
    gf_container box = gf_container_make(&c);
    gf_mesh m;
    // And the mesh function itself at a known height.
    snprintf(path, sizeof path, "%s/box.vtk", gf_test_tmpdir());
    assert_int_equal(gf_container_mesh(&box, 7.0, 96, &m), GF_OK);
    assert_int_equal(gf_vtk_write_mesh(path, &m, "test"), GF_OK);
    gf_mesh_free(&m);
    gf_assert_near(vtk_area(path), 2.0 * (W + D) * 7.0 + base, 1e-3 * PI * R * R);
}

// A cylinder's surface: wall 2 pi R (top - z_f), the funnel's frustum
// pi (R + r_o) slant, the pipe 2 pi r_o L, the column's side 2 pi r_i
// (top - z_f) and bottom pi r_i^2 (to the 96-gon's 0.1%).
static void cylinder_mesh_area(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    c.container_shape = GF_SHAPE_CYLINDER;
    c.container_radius = 6;
    c.hopper_angle = 45;
    c.outlet_diameter = 4;
    c.outlet_length = 3;
    c.inner_radius = 1.5;
    assert_int_equal(gf_config_validate(&c), GF_OK);
    gf_container cyl = gf_container_make(&c);
    gf_mesh m;
    char path[700];
    snprintf(path, sizeof path, "%s/cylinder.vtk", gf_test_tmpdir());
    assert_int_equal(gf_container_mesh(&cyl, 12.0, 96, &m), GF_OK);
    assert_int_equal(gf_vtk_write_mesh(path, &m, "test"), GF_OK);
    gf_mesh_free(&m);
    const double R = 6, ro = 2, zf = 4, top = 12, L = 3, ri = 1.5;
    double want = 2 * PI * R * (top - zf) + PI * (R + ro) * hypot(R - ro, zf) + 2 * PI * ro * L +
                  2 * PI * ri * (top - zf) + PI * ri * ri;
    gf_assert_near(vtk_area(path), want, 1e-3 * want);
}

// A resumed run's snapshots.pvd lists the snapshots of both invocations,
// each once, in order, with their times; output.vtk_encoding = ascii writes
// text the same reader reads.
static void resume_keeps_the_series(void **state)
{
    (void)state;
    gf_config c = gf_test_silo_config(10, 300, 2);
    c.orifice_diameter = 4;
    c.run_duration = 0.4;
    c.output_snapshot_interval = 0.2;
    c.output_format = GF_OUTPUT_VTK;
    c.output_vtk_encoding = GF_VTK_ASCII;
    char dir[600], path[700];
    snprintf(dir, sizeof dir, "%s/vtkresume", gf_test_tmpdir());
    gf_run_opts o = {.dir = dir, .force = 1};
    assert_int_equal(gf_run_dir(&c, &o, NULL), GF_OK);
    c.run_duration = 0.8;
    o.resume = 1;
    o.force = 0;
    assert_int_equal(gf_run_dir(&c, &o, NULL), GF_OK);
    snprintf(path, sizeof path, "%s/snapshots.pvd", dir);
    char *pvd = gf_test_read_file(path, NULL);
    assert_non_null(pvd);
    const char *p = pvd;
    for (int k = 0; k <= 4; k++) {
        char want[128];
        snprintf(want, sizeof want, "file=\"snapshots/snap_%06d.vtu\"", k);
        const char *at = strstr(p, want);
        assert_non_null(at);
        assert_null(strstr(at + 1, want)); // once
        const char *ts = strstr(at - 60 > pvd ? at - 60 : pvd, "timestep=\"");
        assert_non_null(ts);
        gf_assert_near(strtod(ts + 10, NULL), 0.2 * k, 1e-9);
        snprintf(path, sizeof path, "%s/snapshots/snap_%06d.vtu", dir, k);
        size_t len;
        char *t = gf_test_read_file(path, &len);
        assert_null(strstr(t, "AppendedData"));
        double v[1];
        assert_int_equal(vtu_array(t, len, "TimeValue", v, 1), 1);
        gf_assert_near(v[0], 0.2 * k, 1e-9);
        free(t);
        p = at;
    }
    free(pvd);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(resume_keeps_the_series),
    cmocka_unit_test(particles_read_back),
    cmocka_unit_test(cylinder_mesh_area),
    cmocka_unit_test(run_writes_vtk),
};

GF_TEST_MAIN("vtk", tests)
