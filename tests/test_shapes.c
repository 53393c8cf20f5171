// SPDX-License-Identifier: MIT
// The shape table (src/geom/shapes.c, docs/geometry.md "Adding a shape"):
// every built-in shape answers every op, and a third shape planted in the
// table is asked, not silently given the box's walls, by everything that
// used to say "cylinder, else box": walls, outline, mesh, LAMMPS walls,
// profile coordinate, bounds, volumes, messages, the analysis' choice of
// radial profiles and the packing's bulk region; and gf_config_validate asks
// a planted row to check its keys (its validate op and wall_key).
#include "support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "geom/container.h"
#include "geom/mesh.h"
#include "granflow/granflow.h"

// Every op of a table, as a list of "is it there".
static void assert_complete(const gf_shape *s)
{
    const gf_shape_ops *o = s->ops;
    const bool there[] = {
        o->walls != NULL,       o->push != NULL,         o->contains != NULL,    o->spot_clamp != NULL,
        o->mirrors != NULL,     o->inside_xy != NULL,    o->floor_z != NULL,     o->section_area != NULL,
        o->slice_volume != NULL, o->clear != NULL,       o->radii != NULL,       o->profile != NULL,
        o->outline != NULL,     o->mesh != NULL,         o->lammps_walls != NULL, o->lammps_base != NULL,
        o->lammps_pour != NULL, o->describe != NULL,     o->outlet_name != NULL,
    };
    for (size_t k = 0; k < sizeof there / sizeof *there; k++)
        if (!there[k]) fail_msg("shape %s: op %zu missing", s->name, k);
    assert_non_null(s->keys);
    for (int k = 0; k < 3; k++) assert_non_null(s->keys[k]); // the three that describe it
    assert_ptr_equal(gf_shape_find(s->id), s);
}

static void builtin_shapes_answer_every_op(void **state)
{
    (void)state;
    assert_complete(&gf_box_shape);
    assert_complete(&gf_cylinder_shape);
    assert_complete(&gf_wedge_shape);
    assert_complete(&gf_mesh_shape);
}

// ---- a fake third shape: a slab 0 < x < 3 (any y, z), radial on purpose ----

enum { OP_WALLS, OP_PUSH, OP_CONTAINS, OP_CLAMP, OP_MIRRORS, OP_INSIDE_XY, OP_FLOOR, OP_SECTION, OP_SLICE, OP_CLEAR,
       OP_RADII, OP_PROFILE, OP_OUTLINE, OP_MESH, OP_LMP_WALLS, OP_LMP_BASE, OP_LMP_POUR, OP_DESCRIBE, OP_OUTLET,
       OP_MAKE, OP_N };
static int asked[OP_N];

static int fk_walls(const gf_container *c, const double p[3], double reach, gf_wall_hit *hit)
{
    (void)c;
    asked[OP_WALLS]++;
    if (p[0] >= reach) return 0;
    hit[0] = (gf_wall_hit){p[0], {1, 0, 0}, true};
    return 1;
}
static void fk_push(const gf_container *c, double x, double y, double z, double r, double a, double *dx, double *dy,
                    double *dz)
{
    asked[OP_PUSH]++;
    gf_container_push_walls(c, x, y, z, r, a, dx, dy, dz);
}
static bool fk_contains(const gf_container *c, double x, double y, double z, double r, double tol)
{
    (void)c, (void)y, (void)z;
    asked[OP_CONTAINS]++;
    return x >= r - tol && x <= 3 - r + tol;
}
static void fk_clamp(const gf_container *c, double n[3], double dw)
{
    (void)c, (void)n, (void)dw;
    asked[OP_CLAMP]++;
}
static int fk_mirrors(const gf_container *c, const double ctr[3], double rs, double m[][3])
{
    asked[OP_MIRRORS]++;
    return gf_container_mirror_walls(c, ctr, rs, m);
}
static bool fk_inside_xy(const gf_container *c, double x, double y, double r)
{
    (void)c, (void)y;
    asked[OP_INSIDE_XY]++;
    return x >= r;
}
static double fk_floor(const gf_container *c, double x, double y, double r)
{
    (void)c, (void)x, (void)y;
    asked[OP_FLOOR]++;
    return r + 1;
}
static double fk_section(const gf_container *c, double z)
{
    (void)c, (void)z;
    asked[OP_SECTION]++;
    return 7.0;
}
static double fk_slice(const gf_container *c, double z0, double z1)
{
    asked[OP_SLICE]++;
    return gf_container_slice_volume_by_sections(c, z0, z1);
}
static bool fk_clear(const gf_container *c, double x, double y, double z, double m)
{
    (void)c, (void)y, (void)z;
    asked[OP_CLEAR]++;
    return x >= m;
}
static void fk_radii(const gf_container *c, double r[2])
{
    (void)c;
    asked[OP_RADII]++;
    r[0] = 1.0;
    r[1] = 9.0;
}
static gf_profile_coord fk_profile(const gf_container *c)
{
    (void)c;
    asked[OP_PROFILE]++;
    return GF_PROFILE_R;
}
static void fk_outline(const gf_container *c, double ztop, gf_outline *o)
{
    (void)c;
    asked[OP_OUTLINE]++;
    const double p[3][2] = {{0, 0}, {3, 0}, {0, ztop}};
    for (int k = 0; k < 3; k++) o->p[k][0] = p[k][0], o->p[k][1] = p[k][1];
    o->n = 3;
}
static gf_status fk_mesh(const gf_container *c, double top, int segments, struct gf_mesh *m)
{
    (void)c, (void)segments;
    asked[OP_MESH]++;
    size_t a = gf_mesh_vertex(m, 0, 0, 0), b = gf_mesh_vertex(m, 3, 0, 0), d = gf_mesh_vertex(m, 0, 0, top);
    return gf_mesh_tri(m, a, b, d) ? GF_OK : GF_ERR_NOMEM;
}
static gf_status fk_lmp_walls(const gf_container *c, FILE *f, const char *pre, const char *law, double zlo, double zhi)
{
    if (!f) return GF_OK; // LAMMPS holds these walls
    (void)c, (void)zlo, (void)zhi;
    asked[OP_LMP_WALLS]++;
    fprintf(f, "region %s_fake plane 0 0 0 1 0 0 units box\nfix walls flow wall/gran/region %s region %s_fake\n", pre,
            law, pre);
    return GF_OK;
}
static void fk_lmp_base(const gf_container *c, FILE *f, const char *law, double zlo)
{
    (void)c, (void)law, (void)zlo;
    asked[OP_LMP_BASE]++;
    fprintf(f, "# fake base\n");
}
static gf_status fk_lmp_pour(const gf_container *c, FILE *f, double inset, double zlo, double zhi)
{
    (void)c;
    asked[OP_LMP_POUR]++;
    if (f) fprintf(f, "region pour block %g 3 INF INF %g %g units box\n", inset, zlo, zhi);
    return GF_OK;
}
static int fk_describe(const gf_container *c, const char *const where[3], char *buf, size_t n)
{
    (void)c;
    asked[OP_DESCRIBE]++;
    return snprintf(buf, n, "a fake slab (%s)", where[0]);
}
static const char *fk_outlet(const gf_container *c)
{
    (void)c;
    asked[OP_OUTLET]++;
    return "fake outlet";
}
static void fk_make(gf_container *c, const gf_container_defs *d)
{
    (void)d;
    asked[OP_MAKE]++;
    c->xlo = 0;
    c->xhi = 3;
    c->z_col = 0.5;
}

static const gf_shape_ops fake_ops = {
    .walls = fk_walls,       .push = fk_push,         .contains = fk_contains,   .spot_clamp = fk_clamp,
    .mirrors = fk_mirrors,   .inside_xy = fk_inside_xy, .floor_z = fk_floor,     .section_area = fk_section,
    .slice_volume = fk_slice, .clear = fk_clear,      .radii = fk_radii,         .profile = fk_profile,
    .outline = fk_outline,   .mesh = fk_mesh,         .lammps_walls = fk_lmp_walls, .lammps_base = fk_lmp_base,
    .lammps_pour = fk_lmp_pour, .describe = fk_describe, .outlet_name = fk_outlet,
};
static const char *const fake_keys[] = {"container.width", "container.depth", "container.exit_z", NULL};
static const gf_shape fake_shape = {
    .name = "fake", .id = (gf_container_shape)77, .ops = &fake_ops, .keys = fake_keys, .make = fk_make,
};

static void a_planted_shape_is_asked_everything(void **state)
{
    (void)state;
    memset(asked, 0, sizeof asked);
    assert_true(gf_shape_register(&fake_shape));
    gf_config cfg = gf_config_default();
    cfg.container_shape = (gf_container_shape)77;
    gf_container c = gf_container_make(&cfg);
    assert_ptr_equal(c.type, &fake_shape);
    assert_string_equal(gf_container_name(&c), "fake");
    assert_false(gf_container_rectangular(&c));
    assert_true(gf_container_reads_key(&c, "container.exit_z"));

    // The spot engine's questions.
    gf_wall_hit hit[GF_WALL_HITS];
    const double p[3] = {0.2, 0, 1};
    assert_int_equal(gf_container_walls(&c, p, 0.5, hit), 1);
    double dx = 0, dy = 0, dz = 0, n[3] = {1, 1, 1}, m[GF_WALL_HITS][3];
    gf_container_push(&c, 0.2, 0, 1, 0.5, 1.0, &dx, &dy, &dz);
    gf_assert_near(dx, 0.3, 1e-15);
    assert_true(gf_container_contains(&c, 1, 0, 0, 0.5, 0));
    c.ops->spot_clamp(&c, n, 0.1);
    assert_int_equal(c.ops->mirrors(&c, p, 0.5, m), 1);
    assert_true(gf_container_inside_xy(&c, 1, 0, 0.5));
    gf_assert_near(gf_container_floor_z(&c, 1, 0, 0.5), 1.5, 0);
    // Everything else the code asks.
    gf_assert_near(gf_container_slice_volume(&c, 0, 2), 14, 1e-12); // section 7 by the fake
    assert_true(gf_container_clear(&c, 2, 0, 0, 1));
    gf_assert_near(gf_container_outer_radius(&c), 9, 0);
    gf_assert_near(gf_container_inner_radius(&c), 1, 0);
    assert_true(gf_container_profile_radial(&c)); // was "cylinder, else x"
    gf_assert_near(gf_container_width(&c), 3, 0);  // bounds from its make
    double lo[3], hi[3];
    gf_container_bounds(&c, 10, lo, hi);
    assert_true(lo[0] == 0 && hi[0] == 3);
    gf_outline ol;
    gf_container_outline(&c, 10, &ol); // was "cylinder, else the box's rectangle"
    assert_int_equal(ol.n, 3);
    gf_bulk_region b;
    gf_container_bulk(&c, 20, &b);
    assert_true(b.annulus && b.r0 == 4 && b.r1 == 6 && b.lo[2] == 2.5);
    gf_mesh mesh;
    assert_int_equal(gf_container_mesh(&c, 5, 8, &mesh), GF_OK); // was "cylinder, else the box's walls"
    assert_int_equal(mesh.nt, 1);
    gf_mesh_free(&mesh);
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    assert_non_null(f);
    gf_container_lammps_walls(&c, f, "drain", "LAW", -5, 50); // was "cylinder, else xplane/yplane"
    gf_container_lammps_base(&c, f, "LAW", -5);
    assert_int_equal(gf_container_lammps_pour(&c, f, 0.55, 10, 20), GF_OK);
    fclose(f);
    assert_non_null(strstr(buf, "region drain_fake plane"));
    assert_null(strstr(buf, "xplane"));
    assert_non_null(strstr(buf, "# fake base"));
    assert_non_null(strstr(buf, "region pour block 0.55 3"));
    free(buf);
    char d[256];
    gf_container_describe(&c, &cfg, d, sizeof d);
    assert_non_null(strstr(d, "a fake slab ("));
    assert_string_equal(gf_container_outlet_name(&c), "fake outlet");
    // Through the modules above geom: the analysis and the packing ask it too.
    assert_true(gf_velocity_radial(&cfg));
    assert_string_equal(gf_velocity_profile_name(&cfg), "v_z(r)");
    gf_packing pk = {0};
    double phi = gf_packing_bulk_fraction(&pk, &cfg);
    (void)phi;
    for (int k = 0; k < OP_N; k++)
        if (!asked[k]) fail_msg("op %d of the planted shape was never asked", k);
}

// ---- the check of a shape's keys: its own validate op, not config's code ----

static int validated;
static gf_container_shape validated_shape;

// Rejects a width over 40 (worded as config words it), else settles a
// 30 x 20 bounding box and a circular outlet 4 wide through config's setters.
static gf_status fk_validate(const gf_container_defs *d, gf_config *cfg)
{
    validated++;
    validated_shape = d->shape;
    if (d->width > 40) {
        gf_config_msg m;
        gf_config_msg_make(&m, cfg, "container.width", "container.shape");
        return gf_error_set(GF_ERR_PARAM, "%s%s is too wide for a fake with %s", m.lead, m.key[0], m.key[1]);
    }
    gf_config_set_extent(cfg, 30, 20);
    gf_config_set_orifice(cfg, GF_ORIFICE_CIRCLE, 4);
    return GF_OK;
}

// The fake's ops and make, with its own check, standing in for the wedge (a
// value config parses): gf_config_validate must ask it, not check a wedge.
static const gf_shape fake_wedge = {
    .name = "fake", .id = GF_SHAPE_WEDGE, .ops = &fake_ops, .keys = fake_keys, .make = fk_make,
    .validate = fk_validate, .wall_key = "container.exit_z", // a key no built-in names there
};

static void config_validation_asks_the_shape(void **state)
{
    (void)state;
    assert_true(gf_shape_register(&fake_wedge));
    validated = 0;
    gf_config cfg = gf_config_default();
    // A wedge's own check would say hopper_angle = 0 is flat; the fake's is asked instead.
    assert_int_equal(gf_config_set(&cfg, "container.shape=wedge", "--set"), GF_OK);
    assert_int_equal(gf_config_set(&cfg, "container.width=45", "--set"), GF_OK);
    assert_int_equal(gf_config_validate(&cfg), GF_ERR_PARAM);
    assert_int_equal(validated, 1);
    assert_int_equal(validated_shape, GF_SHAPE_WEDGE);
    assert_string_equal(gf_last_error(),
                        "--set: container.width = 45 is too wide for a fake with container.shape = wedge");

    assert_int_equal(gf_config_set(&cfg, "container.width=35", "--set"), GF_OK);
    assert_int_equal(gf_config_validate(&cfg), GF_OK);
    assert_int_equal(validated, 2);
    gf_container_defs d; // what it settled, through the setters
    gf_config_container_defs(&cfg, &d);
    assert_true(d.width == 30 && d.depth == 20);
    assert_true(d.orifice.shape == GF_ORIFICE_CIRCLE && d.orifice.diameter == 4);

    // The key it names as the bound of a spot's room.
    assert_int_equal(gf_config_set(&cfg, "container.width=35", "--set"), GF_OK);
    assert_int_equal(gf_config_set(&cfg, "spot.wall_distance=11", "--set"), GF_OK);
    assert_int_equal(gf_config_validate(&cfg), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "spot.wall_distance = 11 leaves spots no room"));
    assert_non_null(strstr(gf_last_error(), "(container.exit_z = "));
    assert_true(gf_shape_unregister(&fake_wedge));
    assert_ptr_equal(gf_shape_find(GF_SHAPE_WEDGE), &gf_wedge_shape);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(builtin_shapes_answer_every_op),
    cmocka_unit_test(a_planted_shape_is_asked_everything),
    cmocka_unit_test(config_validation_asks_the_shape),
};

GF_TEST_MAIN("shapes", tests)
