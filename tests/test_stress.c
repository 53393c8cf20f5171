// SPDX-License-Identifier: MIT
// The limit-state stress solver (src/stress/, docs/stress.md) against closed
// forms: Janssen's stresses in a tall box (plane strain) and a tall cylinder
// (axisymmetric), and the radial stress field of a conical and of a wedge
// hopper (sigma proportional to the distance from the apex, the wall friction
// mobilised, equilibrium); and its bad input.
#include "support.h"

#include <math.h>
#include <string.h>

#include "core/error.h"
#include "geom/container.h"
#include "granflow/granflow.h"
#include "stress/radial.h"
#include "stress/stress.h"

#define PI 3.14159265358979323846

static gf_config cfg_of(const char *const *set)
{
    gf_config c = gf_config_default();
    for (; *set; set++) assert_int_equal(gf_config_set(&c, *set, "test"), GF_OK);
    assert_int_equal(gf_config_validate(&c), GF_OK);
    return c;
}

static void solve(const gf_config *c, double ztop, gf_stress_field *f)
{
    gf_container box = gf_container_make(c);
    gf_stress_def def = gf_config_stress_def(c);
    gf_status st = gf_stress_solve(&def, &box, ztop, f);
    if (st != GF_OK) fail_msg("solve: %s", gf_last_error());
    assert_int_equal(f->clamped, 0);
}

// Mean vertical stress of level j across the section (area-weighted about
// the axis when axisymmetric) and the normal stress on the right wall.
static void level_means(const gf_stress_field *f, int j, double *szz, double *wall)
{
    double s = 0.0, w = 0.0;
    int last = -1;
    for (int i = 0; i < f->nu; i++) {
        size_t k = (size_t)j * f->nu + i;
        if (!f->in[k]) continue;
        double u = f->u0 + i * f->du;
        // Trapezoid weights (the end nodes on the walls or the axis).
        bool edge = i == 0 || i == f->nu - 1 || !f->in[k - 1] || !f->in[k + 1];
        double wt = (edge ? 0.5 : 1.0) * (f->axisym ? u : 1.0);
        if (f->axisym && i == 0) wt = f->du / 8.0; // the axis' ring: int_0^{du/2} r dr / du
        s += wt * f->pt[k].szz;
        w += wt;
        last = (int)k;
    }
    *szz = s / w;
    *wall = f->pt[last].suu;
}

// Janssen: a column of width W (plane strain: two walls, perimeter/area =
// 2/W) or diameter D (4/D) whose wall carries mu_w times the horizontal
// stress, sigma_w = K sigma_zz: sigma_zz(h) = (rho g / (mu_w K c)) (1 -
// exp(-mu_w K c h)), c the perimeter over the area. Two closed forms hold
// whatever K is: the wall stress tends to rho g / (mu_w c) deep down
// (rho g W / (2 mu_w), rho g D / (4 mu_w)), and with K = sigma_w / sigma_zz
// measured at one depth the whole curve follows.
static void janssen_check(const char *const *set, double ztop, double c_per, double tol_curve, double tol_asym)
{
    gf_config cfg = cfg_of(set);
    gf_stress_field f;
    solve(&cfg, ztop, &f);
    double mu = tan(cfg.stress_wall_friction_angle * PI / 180.0);
    double szz, wall;
    level_means(&f, 0, &szz, &wall); // the bottom level
    double asym = 1.0 / (mu * c_per);
    print_message("wall stress at the bottom %.4f, Janssen's limit %.4f\n", wall, asym);
    // K from half-way down, then the curve at every level below 1 width.
    int jm = f.nz / 2;
    double szm, wm;
    level_means(&f, jm, &szm, &wm);
    double K = wm / szm, worst = 0.0;
    for (int j = 0; j < f.nz; j++) {
        double h = ztop - (f.z0 + j * f.dz);
        if (h < 2.0 / c_per) continue;
        double s, w;
        level_means(&f, j, &s, &w);
        double jan = (1.0 - exp(-mu * K * c_per * h)) / (mu * K * c_per);
        worst = fmax(worst, fabs(s / jan - 1.0));
    }
    print_message("K = %.4f (Rankine active %.4f); worst deviation from Janssen's curve %.4f\n", K,
                  (1 - sin(cfg.stress_friction_angle * PI / 180)) / (1 + sin(cfg.stress_friction_angle * PI / 180)),
                  worst);
    gf_stress_free(&f);
    assert_true(fabs(wall / asym - 1.0) < tol_asym);
    assert_true(worst < tol_curve);
}

static void janssen_tall_box(void **state)
{
    (void)state;
    const char *set[] = {"container.width=20", "stress.spacing=0.5", NULL};
    janssen_check(set, 600.0, 2.0 / 20.0, 0.02, 0.01);
}

static void janssen_tall_cylinder(void **state)
{
    (void)state;
    const char *set[] = {"container.shape=cylinder", "container.radius=10", "stress.spacing=0.5", NULL};
    janssen_check(set, 200.0, 4.0 / 20.0, 0.025, 0.01);
}

// The radial field of a hopper (Jenike; Nedderman ch. 8): every node of the
// converging section holds rho g r S(theta) about the apex where the walls
// meet (sigma / r constant along a ray), the wall friction is fully
// mobilised there, and the field on the grid is in equilibrium: the
// divergence of sigma by centred differences of the nodes is rho g within
// 5% (the ODE's own check: a wrong sign or term gives O(1)).
static void radial_check(const char *const *set, double ztop)
{
    gf_config cfg = cfg_of(set);
    gf_stress_field f;
    solve(&cfg, ztop, &f);
    bool radial = f.radial;
    if (!radial) gf_stress_free(&f);
    assert_true(radial);
    double mu = tan(cfg.stress_wall_friction_angle * PI / 180.0);
    gf_container box = gf_container_make(&cfg);
    gf_radial rf;
    gf_status rs = gf_radial_solve(cfg.stress_friction_angle, cfg.stress_wall_friction_angle, f.theta_w * 180 / PI,
                                   f.axisym, &rf);
    int checked = 0;
    double worst_lin = 0.0, worst_eq = 0.0;
    for (int j = 1; j < f.nz - 1; j++)
        for (int i = 0; i < f.nu; i++) {
            size_t k = (size_t)j * f.nu + i;
            double u = f.u0 + i * f.du, z = f.z0 + j * f.dz;
            if (!f.in[k] || z > box.z_col - 2.0 || z < 2.0) continue;
            // The node is the radial field rho g r S(theta) about the apex
            // (sigma / r the same all along a ray).
            double sg[4], psi, rr = hypot(u - f.apex_u, z - f.apex_z);
            gf_radial_at(&rf, rr, atan2(u - f.apex_u, z - f.apex_z), sg, &psi);
            worst_lin = fmax(worst_lin, fabs(f.pt[k].szz - sg[1]) / sg[1] + fabs(f.pt[k].suu - sg[0]) / sg[0]);
            // Equilibrium from centred differences of the exact radial field.
            if (i > 0 && i < f.nu - 1 && f.in[k - 1] && f.in[k + 1] && f.in[k - f.nu] && f.in[k + f.nu] &&
                fabs(u) > 2.0) {
                const gf_stress_point *l = &f.pt[k - 1], *r = &f.pt[k + 1], *d = &f.pt[k - f.nu],
                                      *up = &f.pt[k + f.nu], *c = &f.pt[k];
                double geo = f.axisym ? 1.0 / u : 0.0;
                double eu = (r->suu - l->suu) / (2 * f.du) + (up->suz - d->suz) / (2 * f.dz) +
                            geo * (c->suu - c->stt);
                double ez = (r->suz - l->suz) / (2 * f.du) + (up->szz - d->szz) / (2 * f.dz) + geo * c->suz + 1.0;
                worst_eq = fmax(worst_eq, hypot(eu, ez));
                checked++;
            }
        }
    // The wall: the traction on the wall's plane (normal at theta_w from the horizontal).
    double th = f.theta_w, zw = 0.5 * box.z_col, uw = f.apex_u + (zw - f.apex_z) * tan(th) * (1.0 - 1e-9);
    gf_stress_point w;
    bool at = gf_stress_at(&f, uw - 1e-6, zw, &w);
    double sg[4], psi;
    gf_radial_at(&rf, hypot(uw - f.apex_u, zw - f.apex_z), th, sg, &psi);
    double n[2] = {cos(th), -sin(th)}, t[2] = {sin(th), cos(th)};
    double sn[2] = {sg[0] * n[0] + sg[2] * n[1], sg[2] * n[0] + sg[1] * n[1]};
    double normal = n[0] * sn[0] + n[1] * sn[1], shear = t[0] * sn[0] + t[1] * sn[1];
    print_message("theta_w %.2f deg: linearity %.2e, equilibrium residual %.3f (of rho g = 1) at %d nodes, wall "
                  "shear/normal %.4f (tan phi_w %.4f)\n",
                  th * 180 / PI, worst_lin, worst_eq, checked, -shear / normal, mu);
    gf_stress_free(&f);
    assert_true(at);
    assert_int_equal(rs, GF_OK);
    assert_true(checked > 20);
    assert_true(worst_lin < 1e-9);
    assert_true(worst_eq < 0.05);
    assert_true(fabs(-shear / normal - mu) < 1e-3);
}

static void radial_field_of_a_cone(void **state)
{
    (void)state;
    const char *set[] = {"container.shape=cylinder", "container.radius=15", "container.hopper_angle=70",
                         "container.outlet_diameter=2", "stress.spacing=0.25", NULL};
    radial_check(set, 45.0);
}

static void radial_field_of_a_wedge(void **state)
{
    (void)state;
    const char *set[] = {"container.shape=wedge", "container.width=30", "container.hopper_angle=65",
                         "container.orifice_diameter=2", "stress.spacing=0.25", NULL};
    radial_check(set, 45.0);
}

// No radial field for a hopper too shallow for mass flow (Jenike): the
// converging section then keeps the column's active field, flagged.
static void shallow_cone_has_no_radial_field(void **state)
{
    (void)state;
    gf_radial rf;
    assert_int_equal(gf_radial_solve(30, 20, 25, 1, &rf), GF_OK);
    assert_int_equal(gf_radial_solve(30, 20, 35, 1, &rf), GF_ERR_STATE);
    assert_non_null(strstr(gf_last_error(), "too shallow for mass flow"));
}

// The papers' 60-degree cone (a half-angle of 30) is too shallow for a radial
// field with phi_w = 20: the field takes the most wall friction that has one,
// mobilised at the wall, and its force still drives spots up the axis.
static void shallow_cone_mobilises_less_wall_friction(void **state)
{
    (void)state;
    gf_config cfg = cfg_of((const char *const[]){"container.shape=cylinder", "container.radius=8",
                                                 "container.hopper_angle=60", "container.outlet_diameter=5", NULL});
    gf_stress_field f;
    solve(&cfg, 30.0, &f);
    bool radial = f.radial;
    double mob = f.wall_mobilised, f_limit = f.mass_flow_angle;
    gf_stress_point axis;
    bool at = gf_stress_at(&f, 0.0, 0.5 * f.apex_z + 0.5 * 8.0 / tan(PI / 3), &axis);
    gf_radial rf;
    gf_status rs = gf_radial_solve(30, mob, 90 - 60, 1, &rf);
    gf_status none = gf_radial_solve(30, mob + 0.01, 90 - 60, 1, &rf);
    print_message("wall friction mobilised %.3f of 20 deg; axis f = (%.3g, %.3g)\n", mob, axis.f[0], axis.f[1]);
    gf_stress_free(&f);
    assert_true(radial && at);
    assert_true(mob > 1.0 && mob < 20.0);
    assert_int_equal(rs, GF_OK);
    assert_int_equal(none, GF_ERR_STATE);
    assert_true(axis.f[1] < 0.0);
    // stress.csv says so: the cone's 30 degrees exceed the limit.
    assert_true(f_limit > 29.0 && f_limit < 30.0);
}

// Arnold and McLean's fit (Powder Technol. 13, 255, 1976) to Jenike's chart
// for conical hoppers: the mass-flow limit, a half-angle from the vertical in
// degrees, for an effective internal friction angle d and wall friction w.
static double jenike_conical_limit(double d, double w)
{
    double sd = sin(d * PI / 180.0);
    return 90.0 - 0.5 * acos((1.0 - sd) / (2.0 * sd)) * 180.0 / PI -
           0.5 * (w + asin(sin(w * PI / 180.0) / sd) * 180.0 / PI);
}

// The radial field's existence bound is Jenike's mass-flow limit: within
// 1.5 degrees of the chart's fit (the fit's own accuracy) over the chart.
static void mass_flow_limit_is_jenikes_chart(void **state)
{
    (void)state;
    const double phis[] = {30, 40, 50}, phiws[] = {10, 15, 20, 25};
    double worst = 0.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++) {
            double tc = -1.0, ref = jenike_conical_limit(phis[i], phiws[j]);
            assert_int_equal(gf_radial_mass_flow_angle(phis[i], phiws[j], 1, &tc), GF_OK);
            print_message("phi %g phi_w %g: limit %.2f deg, chart %.2f\n", phis[i], phiws[j], tc, ref);
            worst = fmax(worst, fabs(tc - ref));
        }
    print_message("worst difference %.2f deg\n", worst);
    assert_true(worst < 1.5);
    // Smoother walls allow shallower hoppers, a rougher material too.
    double a, b, c;
    assert_int_equal(gf_radial_mass_flow_angle(30, 10, 1, &a), GF_OK);
    assert_int_equal(gf_radial_mass_flow_angle(30, 20, 1, &b), GF_OK);
    assert_int_equal(gf_radial_mass_flow_angle(40, 20, 1, &c), GF_OK);
    assert_true(a > b + 10.0);
    assert_true(b > c);
}

static void bad_input_is_refused(void **state)
{
    (void)state;
    gf_config c = gf_config_default();
    assert_int_equal(gf_config_set(&c, "stress.friction_angle=70", "--set"), GF_ERR_PARAM);
    assert_int_equal(gf_config_set(&c, "stress.wall_friction_angle=35", "--set"), GF_OK);
    assert_int_equal(gf_config_validate(&c), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "stress.wall_friction_angle"));
    c = gf_config_default();
    assert_int_equal(gf_config_set(&c, "spot.flow_rule=sfr", "--set"), GF_OK);
    assert_int_equal(gf_config_set(&c, "spot.bias_exponent=3", "--set"), GF_OK); // combines (the free surface)
    assert_int_equal(gf_config_validate(&c), GF_OK);
    assert_int_equal(gf_config_set(&c, "run.mode=fixed", "--set"), GF_OK);
    assert_int_equal(gf_config_set(&c, "run.order=spatial", "--set"), GF_OK);
    assert_int_equal(gf_config_validate(&c), GF_ERR_PARAM); // its blocks assume every step rises
    assert_non_null(strstr(gf_last_error(), "run.order"));
    c = gf_config_default();
    assert_int_equal(gf_config_validate(&c), GF_OK);
    gf_container box = gf_container_make(&c);
    gf_stress_def def = gf_config_stress_def(&c);
    gf_stress_field f;
    def.spacing = 0.0;
    assert_int_equal(gf_stress_solve(&def, &box, 50.0, &f), GF_ERR_PARAM);
    def = gf_config_stress_def(&c);
    assert_int_equal(gf_stress_solve(&def, &box, -1.0, &f), GF_ERR_PARAM);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(janssen_tall_box),
    cmocka_unit_test(janssen_tall_cylinder),
    cmocka_unit_test(radial_field_of_a_cone),
    cmocka_unit_test(radial_field_of_a_wedge),
    cmocka_unit_test(shallow_cone_has_no_radial_field),
    cmocka_unit_test(shallow_cone_mobilises_less_wall_friction),
    cmocka_unit_test(mass_flow_limit_is_jenikes_chart),
    cmocka_unit_test(bad_input_is_refused),
};

GF_TEST_MAIN("stress", tests)
