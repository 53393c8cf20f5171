// SPDX-License-Identifier: MIT
// The stress field's grid: lookup by bilinear interpolation, the slip-line
// directions, freeing, and the CSV the run directory holds (docs/stress.md).
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "stress/stress.h"

void gf_stress_free(gf_stress_field *f)
{
    size_t nn = (size_t)f->nu * (size_t)f->nz;
    if (f->pt) gf_free(f->pt, sizeof(gf_stress_point) * nn);
    if (f->in) gf_free(f->in, nn);
    memset(f, 0, sizeof *f);
}

bool gf_stress_at(const gf_stress_field *f, double u, double z, gf_stress_point *out)
{
    if (!f->pt || f->nu < 2 || f->nz < 2) return false;
    double a = (u - f->u0) / f->du, b = (z - f->z0) / f->dz;
    if (!(a >= -0.5 && b >= -0.5 && a <= f->nu - 0.5 && b <= f->nz - 0.5)) return false;
    int i = (int)floor(a), j = (int)floor(b);
    if (i < 0) i = 0;
    if (j < 0) j = 0;
    if (i > f->nu - 2) i = f->nu - 2;
    if (j > f->nz - 2) j = f->nz - 2;
    double ta = fmin(fmax(a - i, 0.0), 1.0), tb = fmin(fmax(b - j, 0.0), 1.0);
    // Bilinear over the corners inside the material, the weights renormalised.
    double w[4] = {(1 - ta) * (1 - tb), ta * (1 - tb), (1 - ta) * tb, ta * tb}, ws = 0.0;
    size_t k[4] = {(size_t)j * f->nu + i, (size_t)j * f->nu + i + 1, (size_t)(j + 1) * f->nu + i,
                   (size_t)(j + 1) * f->nu + i + 1};
    gf_stress_point s = {0};
    double c2 = 0.0, s2 = 0.0; // psi is averaged as the direction 2 psi (it is defined modulo pi)
    for (int q = 0; q < 4; q++) {
        if (!f->in[k[q]] || w[q] <= 0.0) continue;
        const gf_stress_point *p = &f->pt[k[q]];
        ws += w[q];
        s.suu += w[q] * p->suu;
        s.szz += w[q] * p->szz;
        s.suz += w[q] * p->suz;
        s.stt += w[q] * p->stt;
        s.p += w[q] * p->p;
        s.f[0] += w[q] * p->f[0];
        s.f[1] += w[q] * p->f[1];
        c2 += w[q] * cos(2.0 * p->psi);
        s2 += w[q] * sin(2.0 * p->psi);
    }
    if (ws <= 0.0) return false;
    s.suu /= ws;
    s.szz /= ws;
    s.suz /= ws;
    s.stt /= ws;
    s.p /= ws;
    s.f[0] /= ws;
    s.f[1] /= ws;
    s.psi = 0.5 * atan2(s2, c2);
    if (s.psi < 0.0) s.psi += 3.14159265358979323846;
    *out = s;
    return true;
}

void gf_stress_slip_dirs(const gf_stress_field *f, double psi, double alpha[2], double beta[2])
{
    alpha[0] = cos(psi - f->eps);
    alpha[1] = sin(psi - f->eps);
    beta[0] = cos(psi + f->eps);
    beta[1] = sin(psi + f->eps);
}

gf_status gf_stress_write_csv(const gf_stress_field *f, const char *path)
{
    FILE *fp = fopen(path, "w");
    if (!fp) return gf_error_set(GF_ERR_IO, "%s: cannot write", path);
    const char *u = f->axisym ? "r" : "x";
    fprintf(fp, "# limit-state Mohr-Coulomb stress (docs/stress.md): ztop = %.17g, phi = %g deg, phi_w = %g deg, %s; "
                "stresses in rho_b g d, compressive positive; psi: major principal direction from the %s axis, "
                "degrees; f: out-of-balance force div(P R(psi)); clamped states: %ld%s",
            f->ztop, f->def.friction_angle, f->def.wall_friction_angle,
            f->axisym ? "axisymmetric (r, z), Haar-von Karman hoop stress" : "plane strain (x, z)", u, f->clamped,
            f->radial ? "; below the top of the funnel: the radial field" : "");
    if (f->radial && f->wall_mobilised < f->def.wall_friction_angle)
        fprintf(fp, " (with the wall friction partly mobilised, %.4g of phi_w = %g deg: too shallow for mass flow)",
                f->wall_mobilised, f->def.wall_friction_angle);
    if (isfinite(f->mass_flow_angle)) {
        double thd = f->theta_w * 180.0 / 3.14159265358979323846;
        fprintf(fp, "; Jenike's mass-flow limit for a cone at these angles: a half-angle of %.1f deg, this one's %.1f "
                    "deg: %s flow",
                f->mass_flow_angle, thd, thd <= f->mass_flow_angle ? "mass" : "funnel");
    }
    fputc('\n', fp);
    fprintf(fp, "%s,z,s_%s%s,s_zz,s_%sz,s_%s,p,psi_deg,f_%s,f_z\n", u, u, u, u, f->axisym ? "tt" : "yy", u);
    for (int j = 0; j < f->nz; j++)
        for (int i = 0; i < f->nu; i++) {
            size_t k = (size_t)j * f->nu + i;
            if (!f->in[k]) continue;
            const gf_stress_point *p = &f->pt[k];
            fprintf(fp, "%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.4f,%.6g,%.6g\n", f->u0 + i * f->du, f->z0 + j * f->dz,
                    p->suu, p->szz, p->suz, p->stt, p->p, p->psi * 180.0 / 3.14159265358979323846, p->f[0], p->f[1]);
        }
    if (ferror(fp) | (fclose(fp) != 0)) return gf_error_set(GF_ERR_IO, "%s: write failed", path);
    return GF_OK;
}
