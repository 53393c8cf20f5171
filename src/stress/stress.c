// SPDX-License-Identifier: MIT
// The limit-state Mohr-Coulomb stress field of a container (docs/stress.md):
// the equilibrium equations marched down from the free surface, depth h =
// ztop - z playing the role of time (the system is hyperbolic, its two
// characteristics the slip lines at psi -+ (pi/4 - phi/2), neither
// horizontal in an active field, so every level follows from the one above;
// Sokolovskii's method, here as finite volumes). The unknowns of a level are
// sigma_zz and sigma_uz in N cells across the section; sigma_uu is the
// active root of the yield condition (the material everywhere at incipient
// failure, major principal stress near vertical as in a filled silo); the
// walls fully mobilise their friction. The section [lo(h), hi(h)] may
// narrow with depth: the cells are mapped to xi in [0, 1]. Below the top of
// a converging section (a funnel) the field is Jenike's passive radial field
// instead (radial.c), when one exists.
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "stress/radial.h"
#include "stress/stress.h"

#define GF_PI 3.14159265358979323846

// The yield surface, active root: sigma_uu from sigma_zz = Z and sigma_uz = T
// when (sigma_uu - Z)^2 + 4 T^2 = sin^2(phi) (sigma_uu + Z)^2 and sigma_uu <= Z.
// *clamped is set when |T| exceeded Z tan(phi) (no real root; T pulled back).
typedef struct gf_yield {
    double s, s2;   // sin(phi), its square
    double tan_phi;
} gf_yield;

static double gf_yield_x(const gf_yield *y, double Z, double *T, bool *clamped)
{
    if (Z < 0.0) Z = 0.0;
    double tmax = Z * y->tan_phi;
    if (fabs(*T) > tmax) {
        *T = copysign(tmax, *T);
        if (clamped) *clamped = true;
    }
    double d = y->s2 * Z * Z - (1.0 - y->s2) * (*T) * (*T);
    d = d > 0.0 ? sqrt(d) : 0.0;
    return (Z * (1.0 + y->s2) - 2.0 * d) / (1.0 - y->s2);
}

// Largest |characteristic speed| du/dh of the state (Z, T): the roots of
// l^2 + X_T l - X_Z = 0, the Jacobian of the fluxes (-T, -X(Z, T)).
static double gf_yield_speed(const gf_yield *y, double Z, double T)
{
    if (Z <= 0.0) return sqrt((1.0 - y->s) / (1.0 + y->s));
    double d = y->s2 * Z * Z - (1.0 - y->s2) * T * T;
    d = fmax(d, 1e-6 * y->s2 * Z * Z); // the edge of the surface, where the root is singular
    d = sqrt(d);
    double xz = ((1.0 + y->s2) - 2.0 * y->s2 * Z / d) / (1.0 - y->s2), xt = 2.0 * T / d;
    double disc = xt * xt + 4.0 * xz;
    if (disc < 0.0) disc = 0.0;
    return 0.5 * (fabs(xt) + sqrt(disc));
}

// The wall's shear stress: with sigma_zz = Z from inside, the T that makes
// the wall friction fully mobilised, (t_up + mu_w n) . sigma n = 0, n the
// outward normal and t_up the upward tangent of the wall in (u, z).
static double gf_wall_g(const gf_yield *y, double Z, double T, const double n[2], const double a[2])
{
    double X = gf_yield_x(y, Z, &T, NULL);
    double sn[2] = {X * n[0] + T * n[1], T * n[0] + Z * n[1]};
    return a[0] * sn[0] + a[1] * sn[1];
}

static double gf_wall_t(const gf_yield *y, double Z, const double n[2], const double t[2], double mu_w)
{
    double tmax = (Z > 0.0 ? Z : 0.0) * y->tan_phi * (1.0 - 1e-12);
    if (tmax <= 0.0) return 0.0;
    double a[2] = {t[0] + mu_w * n[0], t[1] + mu_w * n[1]};
    // g(T) has two roots on the yield surface; the wall's is the one nearest
    // T = 0 (the other sits at the surface's edge, where sigma_uu > sigma_zz).
    // Walk out from 0 both ways in small steps to the first sign change.
    const int steps = 256;
    double g0 = gf_wall_g(y, Z, 0.0, n, a), best = 0.0, bestg = fabs(g0);
    for (int k = 1; k <= steps; k++) {
        for (int sgn = -1; sgn <= 1; sgn += 2) {
            double lo = sgn * tmax * (k - 1) / steps, hi = sgn * tmax * k / steps;
            double glo = gf_wall_g(y, Z, lo, n, a), ghi = gf_wall_g(y, Z, hi, n, a);
            if (fabs(ghi) < bestg) {
                bestg = fabs(ghi);
                best = hi;
            }
            if (glo == 0.0) return lo;
            if ((glo < 0.0) == (ghi < 0.0)) continue;
            for (int it = 0; it < 60; it++) {
                double mid = 0.5 * (lo + hi), gm = gf_wall_g(y, Z, mid, n, a);
                if ((gm < 0.0) == (glo < 0.0)) {
                    lo = mid;
                    glo = gm;
                } else {
                    hi = mid;
                }
            }
            return 0.5 * (lo + hi);
        }
    }
    return best; // the friction cannot be reached: the nearest
}

// The section of the container at height z in the solution's plane: [lo, hi]
// from the outline (the slice y = 0); for an axisymmetric field lo = 0 and
// hi the largest |x|. False when the slice misses the inside.
static bool gf_section(const gf_outline *o, bool axisym, double z, double *lo, double *hi)
{
    double a = INFINITY, b = -INFINITY;
    for (int i = 0; i < o->n; i++) {
        const double *p = o->p[i], *q = o->p[(i + 1) % o->n];
        double zmin = fmin(p[1], q[1]), zmax = fmax(p[1], q[1]);
        if (z < zmin || z > zmax) continue;
        double xs[2];
        int nx = 0;
        if (zmax - zmin < 1e-12) {
            xs[nx++] = p[0];
            xs[nx++] = q[0];
        } else {
            xs[nx++] = p[0] + (q[0] - p[0]) * (z - p[1]) / (q[1] - p[1]);
        }
        for (int k = 0; k < nx; k++) {
            double x = axisym ? fabs(xs[k]) : xs[k];
            a = fmin(a, x);
            b = fmax(b, x);
        }
    }
    if (!(b > a) && !(axisym && b > 0.0)) return false;
    *lo = axisym ? 0.0 : a;
    *hi = b;
    return true;
}

// One level of the march: cells of the section, their state and the walls'.
typedef struct gf_march {
    const gf_stress_def *def;
    const gf_outline *o;
    bool axisym;
    int k;          // 1: axisymmetric (r-weighted), 0: plane strain
    int n;          // cells across
    double ztop;
    gf_yield y;
    double mu_w;
    double *Z, *T;  // per cell
    double *W0, *W1; // conserved X r^k (Z, T) per cell, 2 n
    double *G0, *G1; // face fluxes, 2 (n + 1)
    long clamped;
} gf_march;

typedef struct gf_level {
    double lo, hi, dlo, dhi; // section and its rate of change with depth (d/dh)
} gf_level;

static bool gf_level_at(const gf_march *m, double h, gf_level *L)
{
    double z = m->ztop - h, e = 1e-3;
    double lo0, hi0, lo1, hi1;
    if (!gf_section(m->o, m->axisym, z, &L->lo, &L->hi)) return false;
    // Slopes from a small centred difference (one-sided at the ends of the outline).
    bool a = gf_section(m->o, m->axisym, z + e, &lo0, &hi0), b = gf_section(m->o, m->axisym, z - e, &lo1, &hi1);
    if (a && b) {
        L->dlo = (lo1 - lo0) / (2 * e);
        L->dhi = (hi1 - hi0) / (2 * e);
    } else if (b) {
        L->dlo = (lo1 - L->lo) / e;
        L->dhi = (hi1 - L->hi) / e;
    } else if (a) {
        L->dlo = (L->lo - lo0) / e;
        L->dhi = (L->hi - hi0) / e;
    } else {
        L->dlo = L->dhi = 0.0;
    }
    return true;
}

static double gf_cell_r(const gf_march *m, const gf_level *L, int i)
{
    return L->lo + (i + 0.5) / m->n * (L->hi - L->lo);
}

// The wall state at the right (side 1) or left (side 0) wall of a plane
// section: Z from the adjacent cell, T from the wall friction.
static void gf_wall_state(const gf_march *m, const gf_level *L, int side, double *Z, double *T, double *X)
{
    int i = side ? m->n - 1 : 0;
    double slope = side ? L->dhi : L->dlo, norm = sqrt(1.0 + slope * slope);
    double n[2], t[2] = {-slope / norm, 1.0 / norm};
    if (side) {
        n[0] = 1.0 / norm;
        n[1] = slope / norm;
    } else {
        n[0] = -1.0 / norm;
        n[1] = -slope / norm;
    }
    *Z = m->Z[i];
    *T = gf_wall_t(&m->y, *Z, n, t, m->mu_w);
    *X = gf_yield_x(&m->y, *Z, T, NULL);
}

// The hoop stress (Haar-von Karman): the in-plane principal stress that is
// horizontal on the axis, so that sigma_rr = sigma_tt there: in the active
// state the minor one (radial.c has the passive state's).
static double gf_hoop(const gf_yield *y, double P) { return P * (1.0 - y->s); }

static void gf_fluxes(gf_march *m, const gf_level *L, double *G)
{
    int n = m->n;
    double X = L->hi - L->lo;
    for (int f = 0; f <= n; f++) {
        double xi = (double)f / n, r = L->lo + xi * X, rk = m->k ? r : 1.0;
        double vel = L->dlo + xi * (L->dhi - L->dlo); // du/dh of the face
        double g0, g1;
        if (f == 0 || f == n) {
            int side = f == n;
            if (m->k && !side) {
                g0 = g1 = 0.0; // the axis
            } else {
                double Z, T, Xw;
                gf_wall_state(m, L, side, &Z, &T, &Xw);
                g0 = rk * (-T) - vel * rk * Z;
                g1 = rk * (-Xw) - vel * rk * T;
            }
        } else {
            double ZL = m->Z[f - 1], TL = m->T[f - 1], ZR = m->Z[f], TR = m->T[f];
            double XL = gf_yield_x(&m->y, ZL, &TL, NULL), XR = gf_yield_x(&m->y, ZR, &TR, NULL);
            double aL = gf_yield_speed(&m->y, ZL, TL), aR = gf_yield_speed(&m->y, ZR, TR);
            double a = fmax(aL, aR) + fabs(vel); // Rusanov: the fastest wave at the face
            // G = r^k f(u) - vel r^k u; dissipation a (u_R - u_L) r^k.
            g0 = rk * (0.5 * (-TL - TR) - vel * 0.5 * (ZL + ZR)) - 0.5 * a * rk * (ZR - ZL);
            g1 = rk * (0.5 * (-XL - XR) - vel * 0.5 * (TL + TR)) - 0.5 * a * rk * (TR - TL);
        }
        G[2 * f] = g0;
        G[2 * f + 1] = g1;
    }
}

// The largest stable depth step: a wave crosses at most 0.45 of a cell.
static double gf_dh_max(const gf_march *m, const gf_level *L)
{
    double a = 0.0;
    for (int i = 0; i < m->n; i++) a = fmax(a, gf_yield_speed(&m->y, m->Z[i], m->T[i]));
    a += fmax(fabs(L->dlo), fabs(L->dhi));
    return 0.45 * (L->hi - L->lo) / m->n / fmax(a, 1e-6);
}

// One step of the march from h to h + dh (Heun's method over the
// finite-volume update of X r^k u).
static gf_status gf_march_step(gf_march *m, double h, double dh)
{
    gf_level L0, L1;
    if (!gf_level_at(m, h, &L0) || !gf_level_at(m, h + dh, &L1))
        return gf_error_set(GF_ERR_STATE, "the container has no cross-section at z = %g", m->ztop - h - dh);
    int n = m->n;
    double X0 = L0.hi - L0.lo, X1 = L1.hi - L1.lo, dxi = 1.0 / n;
    double *Zs = m->W1, *Ts = m->W1 + n; // scratch of the predictor
    gf_fluxes(m, &L0, m->G0);
    // Predictor.
    for (int i = 0; i < n; i++) {
        double r0 = gf_cell_r(m, &L0, i), r1 = gf_cell_r(m, &L1, i);
        double rk0 = m->k ? r0 : 1.0, rk1 = m->k ? r1 : 1.0;
        double T = m->T[i], Xs = gf_yield_x(&m->y, m->Z[i], &T, NULL);
        double ptt = gf_hoop(&m->y, 0.5 * (Xs + m->Z[i]));
        double w0 = X0 * rk0 * m->Z[i], w1 = X0 * rk0 * m->T[i];
        double d0 = -(m->G0[2 * (i + 1)] - m->G0[2 * i]) / dxi + X0 * rk0;
        double d1 = -(m->G0[2 * (i + 1) + 1] - m->G0[2 * i + 1]) / dxi - X0 * m->k * ptt;
        m->W0[2 * i] = d0;
        m->W0[2 * i + 1] = d1;
        Zs[i] = (w0 + dh * d0) / (X1 * rk1);
        Ts[i] = (w1 + dh * d1) / (X1 * rk1);
    }
    // Corrector: the fluxes of the predicted state at h + dh.
    double *Zk = gf_alloc(sizeof(double) * 2 * n);
    if (!Zk) return gf_error_set(GF_ERR_NOMEM, "out of memory for the stress field");
    double *Tk = Zk + n;
    memcpy(Zk, m->Z, sizeof(double) * n);
    memcpy(Tk, m->T, sizeof(double) * n);
    memcpy(m->Z, Zs, sizeof(double) * n);
    memcpy(m->T, Ts, sizeof(double) * n);
    gf_fluxes(m, &L1, m->G1);
    for (int i = 0; i < n; i++) {
        double r0 = gf_cell_r(m, &L0, i), r1 = gf_cell_r(m, &L1, i);
        double rk0 = m->k ? r0 : 1.0, rk1 = m->k ? r1 : 1.0;
        double T = m->T[i], Xs = gf_yield_x(&m->y, m->Z[i], &T, NULL);
        double ptt = gf_hoop(&m->y, 0.5 * (Xs + m->Z[i]));
        double d0 = -(m->G1[2 * (i + 1)] - m->G1[2 * i]) / dxi + X1 * rk1;
        double d1 = -(m->G1[2 * (i + 1) + 1] - m->G1[2 * i + 1]) / dxi - X1 * m->k * ptt;
        double w0 = X0 * rk0 * Zk[i] + 0.5 * dh * (m->W0[2 * i] + d0);
        double w1 = X0 * rk0 * Tk[i] + 0.5 * dh * (m->W0[2 * i + 1] + d1);
        double Z = w0 / (X1 * rk1), Tn = w1 / (X1 * rk1);
        if (Z < 0.0) Z = 0.0;
        bool cl = false;
        (void)gf_yield_x(&m->y, Z, &Tn, &cl);
        if (cl && Z > 1e-9) m->clamped++;
        m->Z[i] = Z;
        m->T[i] = Tn;
    }
    gf_free(Zk, sizeof(double) * 2 * n);
    return GF_OK;
}

// The state of a level at u (its section L), linear between cell centres,
// the walls' state beyond the first and last centre.
static void gf_level_sample(const gf_march *m, const gf_level *L, double u, double *Z, double *T)
{
    int n = m->n;
    double xi = (u - L->lo) / (L->hi - L->lo) * n - 0.5;
    if (xi <= 0.0) {
        if (m->k) {
            *Z = m->Z[0];
            *T = m->T[0] * fmax(u, 0.0) / gf_cell_r(m, L, 0); // sigma_rz vanishes on the axis
            return;
        }
        double Zw, Tw, Xw;
        gf_wall_state(m, L, 0, &Zw, &Tw, &Xw);
        double t = fmax(0.0, xi + 0.5) / 0.5;
        *Z = Zw + t * (m->Z[0] - Zw);
        *T = Tw + t * (m->T[0] - Tw);
        return;
    }
    if (xi >= n - 1) {
        double Zw, Tw, Xw;
        gf_wall_state(m, L, 1, &Zw, &Tw, &Xw);
        double t = fmin(1.0, (xi - (n - 1)) / 0.5);
        *Z = m->Z[n - 1] + t * (Zw - m->Z[n - 1]);
        *T = m->T[n - 1] + t * (Tw - m->T[n - 1]);
        return;
    }
    int i = (int)xi;
    double t = xi - i;
    *Z = m->Z[i] + t * (m->Z[i + 1] - m->Z[i]);
    *T = m->T[i] + t * (m->T[i + 1] - m->T[i]);
}

static void gf_point_make(const gf_march *m, double Z, double T, gf_stress_point *p)
{
    double X = gf_yield_x(&m->y, Z, &T, NULL);
    p->suu = X;
    p->szz = Z;
    p->suz = T;
    p->p = 0.5 * (X + Z);
    p->stt = m->k ? gf_hoop(&m->y, p->p) : p->p; // plane strain: sigma_yy = P (no strain along y)
    double psi = 0.5 * atan2(2.0 * T, X - Z);     // major principal direction from the u axis
    if (psi < 0.0) psi += GF_PI;
    p->psi = psi;
    p->f[0] = p->f[1] = 0.0;
}

// A node of the converging section from the radial field.
static void gf_radial_point(const gf_stress_field *f, const gf_radial *rf, double u, double z, gf_stress_point *p)
{
    double du = u - f->apex_u, dz = z - f->apex_z, r = hypot(du, dz), th = atan2(du, dz), sg[4], psi;
    gf_radial_at(rf, r, th, sg, &psi);
    p->suu = sg[0];
    p->szz = sg[1];
    p->suz = sg[2];
    p->p = 0.5 * (sg[0] + sg[1]);
    p->stt = f->axisym ? sg[3] : p->p;
    p->psi = psi;
    p->f[0] = p->f[1] = 0.0;
}

gf_status gf_stress_solve(const gf_stress_def *def, const gf_container *c, double ztop, gf_stress_field *out)
{
    memset(out, 0, sizeof *out);
    if (!(def->friction_angle > 0.0 && def->friction_angle < 60.0))
        return gf_error_set(GF_ERR_PARAM, "stress.friction_angle = %g must be in (0, 60) degrees", def->friction_angle);
    if (!(def->wall_friction_angle >= 0.0 && def->wall_friction_angle <= def->friction_angle))
        return gf_error_set(GF_ERR_PARAM, "stress.wall_friction_angle = %g must be in [0, stress.friction_angle = %g]",
                            def->wall_friction_angle, def->friction_angle);
    if (!(def->spacing > 0.0 && def->spacing <= 100.0))
        return gf_error_set(GF_ERR_PARAM, "stress.spacing = %g must be in (0, 100] d", def->spacing);
    if (!(ztop > 0.0)) return gf_error_set(GF_ERR_PARAM, "the free surface z = %g is not above the base", ztop);
    if (gf_container_inner_radius(c) > 0.0)
        return gf_error_set(GF_ERR_STATE, "the stress field has no solution with a central column");
    gf_outline o;
    gf_container_outline(c, ztop + 1.0, &o);
    gf_march m = {.def = def, .o = &o, .axisym = gf_container_profile_radial(c), .ztop = ztop};
    m.k = m.axisym ? 1 : 0;
    double phi = def->friction_angle * GF_PI / 180.0;
    m.y = (gf_yield){.s = sin(phi), .s2 = sin(phi) * sin(phi), .tan_phi = tan(phi)};
    m.mu_w = tan(def->wall_friction_angle * GF_PI / 180.0);
    const double zstop = 0.0, zcol = c->z_col;
    gf_level L;
    if (!gf_level_at(&m, 0.0, &L)) return gf_error_set(GF_ERR_STATE, "the container has no cross-section at z = %g", ztop);
    // Cells across: the spacing at the top, at least 16 (a narrowing section keeps its count).
    m.n = (int)ceil((L.hi - L.lo) / def->spacing);
    if (m.n < 16) m.n = 16;
    if (m.n > 4096) m.n = 4096;
    // The output grid: nodes every `spacing` over the bounding section, levels from ztop to zstop.
    double ulo = L.lo, uhi = L.hi;
    for (double z = zstop; z <= ztop; z += 0.25 * def->spacing) {
        gf_level Lz;
        if (gf_level_at(&m, ztop - z, &Lz)) {
            ulo = fmin(ulo, Lz.lo);
            uhi = fmax(uhi, Lz.hi);
        }
    }
    out->def = *def;
    out->axisym = m.axisym;
    out->nu = (int)ceil((uhi - ulo) / def->spacing) + 1;
    out->nz = (int)ceil((ztop - zstop) / def->spacing) + 1;
    if ((double)out->nu * out->nz > 5e7)
        return gf_error_set(GF_ERR_PARAM, "stress.spacing = %g makes a grid of %d x %d nodes: too many", def->spacing,
                            out->nu, out->nz);
    out->u0 = ulo;
    out->du = out->nu > 1 ? (uhi - ulo) / (out->nu - 1) : 1.0;
    out->z0 = zstop;
    out->dz = (ztop - zstop) / (out->nz - 1);
    out->ztop = ztop;
    out->zstop = zstop;
    out->sin_phi = m.y.s;
    out->eps = 0.25 * GF_PI - 0.5 * phi;
    // A converging section (below the top of the funnel, zcol > 0) flows in
    // the passive state: Jenike's radial stress field about the apex where
    // its walls meet (radial.c), when one exists for these angles (mass flow).
    gf_radial rf;
    out->mass_flow_angle = NAN; // unchanged when there is no limit
    if (zcol > 0.0 && m.axisym &&
        gf_radial_mass_flow_angle(def->friction_angle, def->wall_friction_angle, 1, &out->mass_flow_angle) != GF_OK)
        gf_error_clear();
    if (zcol > 0.0) {
        gf_level Lc;
        double zp = 0.5 * fmin(zcol, ztop);
        if (gf_level_at(&m, ztop - zp, &Lc) && Lc.dhi < 0.0 && (m.axisym || Lc.dlo > 0.0)) {
            double hp = ztop - zp, span = Lc.hi - Lc.lo, rate = (m.axisym ? 0.0 : Lc.dlo) - Lc.dhi;
            double dapex = m.axisym ? Lc.hi / -Lc.dhi : span / rate; // depth below zp of the apex
            out->apex_u = m.axisym ? 0.0 : Lc.lo + Lc.dlo * dapex;
            out->apex_z = ztop - (hp + dapex);
            double thw = m.axisym ? atan(-Lc.dhi) : 0.5 * (atan(Lc.dlo) + atan(-Lc.dhi));
            out->theta_w = thw;
            double thd = thw * 180.0 / GF_PI, pw = def->wall_friction_angle;
            out->radial = gf_radial_solve(def->friction_angle, pw, thd, m.axisym, &rf) == GF_OK;
            out->wall_mobilised = pw;
            if (!out->radial) {
                // Too shallow for mass flow at phi_w (Jenike): the walls cannot
                // hold the passive field with their friction fully mobilised.
                // Take the field with the most wall friction that has one
                // (partly mobilised friction, as at the edge of funnel flow).
                double lo = -1.0, hi = pw;
                for (double t = floor(pw - 1e-9); t >= 1.0 && lo < 0.0; t -= 1.0) { // whole degrees down to 1
                    if (gf_radial_solve(def->friction_angle, t, thd, m.axisym, &rf) == GF_OK)
                        lo = t;
                    else
                        hi = t;
                }
                if (lo >= 0.0) {
                    lo = gf_radial_edge(def->friction_angle, pw, thd, m.axisym, GF_RADIAL_WALL_FRICTION, lo, hi, 20);
                    out->radial = gf_radial_solve(def->friction_angle, lo, thd, m.axisym, &rf) == GF_OK;
                    out->wall_mobilised = lo;
                }
            }
            gf_error_clear();
        }
    }
    size_t nn = (size_t)out->nu * out->nz;
    out->pt = gf_alloc(sizeof(gf_stress_point) * nn);
    out->in = gf_alloc(nn);
    size_t nm = (size_t)m.n;
    m.Z = gf_alloc(sizeof(double) * nm);
    m.T = gf_alloc(sizeof(double) * nm);
    m.W0 = gf_alloc(sizeof(double) * 2 * nm);
    m.W1 = gf_alloc(sizeof(double) * 2 * nm);
    m.G0 = gf_alloc(sizeof(double) * 2 * (nm + 1));
    m.G1 = gf_alloc(sizeof(double) * 2 * (nm + 1));
    gf_status st = GF_OK;
    if (!out->pt || !out->in || !m.Z || !m.T || !m.W0 || !m.W1 || !m.G0 || !m.G1) {
        st = gf_error_set(GF_ERR_NOMEM, "out of memory for the stress field");
        goto done;
    }
    memset(out->pt, 0, sizeof(gf_stress_point) * nn);
    memset(out->in, 0, nn);
    for (size_t i = 0; i < nm; i++) m.Z[i] = m.T[i] = 0.0;
    double h = 0.0;
    for (int j = out->nz - 1; j >= 0; j--) {
        double hj = ztop - (out->z0 + j * out->dz);
        if (j == 0) hj = ztop - zstop - 1e-9; // the last level just above the base
        while (h < hj - 1e-12) {
            gf_level Lh;
            if (!gf_level_at(&m, h, &Lh)) {
                st = gf_error_set(GF_ERR_STATE, "the container has no cross-section at z = %g", ztop - h);
                goto done;
            }
            double dh = fmin(gf_dh_max(&m, &Lh), hj - h);
            if ((st = gf_march_step(&m, h, dh)) != GF_OK) goto done;
            h += dh;
        }
        gf_level Lj;
        if (!gf_level_at(&m, h, &Lj)) continue;
        bool radial = out->radial && out->z0 + j * out->dz < zcol - 1e-9;
        for (int i = 0; i < out->nu; i++) {
            double u = out->u0 + i * out->du;
            if (u < Lj.lo - 1e-9 || u > Lj.hi + 1e-9) continue;
            size_t k = (size_t)j * out->nu + i;
            out->in[k] = 1;
            if (radial) {
                gf_radial_point(out, &rf, u, out->z0 + j * out->dz, &out->pt[k]);
                continue;
            }
            double Z, T;
            gf_level_sample(&m, &Lj, u, &Z, &T);
            gf_point_make(&m, Z, T, &out->pt[k]);
        }
    }
    out->clamped = m.clamped;
    // The out-of-balance force div(P R(psi)) at each node, P R = (sigma - P I) / sin(phi)
    // (docs/stress.md: the force on the grains of a spot when sin(phi) drops).
    for (int j = 0; j < out->nz; j++)
        for (int i = 0; i < out->nu; i++) {
            size_t k = (size_t)j * out->nu + i;
            if (!out->in[k]) continue;
            double s = out->sin_phi;
#define GF_AUU(q) ((out->pt[q].suu - out->pt[q].szz) / (2.0 * s))
#define GF_AUZ(q) (out->pt[q].suz / s)
            // One-sided where a neighbour is outside.
            size_t kl = i > 0 && out->in[k - 1] ? k - 1 : k, kr = i + 1 < out->nu && out->in[k + 1] ? k + 1 : k;
            size_t kd = j > 0 && out->in[k - out->nu] ? k - out->nu : k;
            size_t ku = j + 1 < out->nz && out->in[k + out->nu] ? k + out->nu : k;
            double du = (double)(kr - kl) * out->du, dz = (double)((ku - kd) / out->nu) * out->dz;
            double dAuu = du > 0 ? (GF_AUU(kr) - GF_AUU(kl)) / du : 0.0;
            double dAuz_u = du > 0 ? (GF_AUZ(kr) - GF_AUZ(kl)) / du : 0.0;
            double dAuz_z = dz > 0 ? (GF_AUZ(ku) - GF_AUZ(kd)) / dz : 0.0;
            double dAzz_z = dz > 0 ? -(GF_AUU(ku) - GF_AUU(kd)) / dz : 0.0;
            double fu = dAuu + dAuz_z, fz = dAuz_u + dAzz_z;
            double u = out->u0 + i * out->du;
            if (m.k && u > 0.5 * out->du) {
                double att = (out->pt[k].stt - out->pt[k].p) / s; // (sigma_tt - P) / sin(phi)
                fu += (GF_AUU(k) - att) / u;
                fz += GF_AUZ(k) / u;
            }
#undef GF_AUU
#undef GF_AUZ
            if (m.k && u < 0.5 * out->du) fu = 0.0; // on the axis, by symmetry
            out->pt[k].f[0] = fu;
            out->pt[k].f[1] = fz;
        }
done:
    gf_free(m.Z, sizeof(double) * nm);
    gf_free(m.T, sizeof(double) * nm);
    gf_free(m.W0, sizeof(double) * 2 * nm);
    gf_free(m.W1, sizeof(double) * 2 * nm);
    gf_free(m.G0, sizeof(double) * 2 * (nm + 1));
    gf_free(m.G1, sizeof(double) * 2 * (nm + 1));
    if (st != GF_OK) gf_stress_free(out);
    return st;
}
