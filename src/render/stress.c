// SPDX-License-Identifier: MIT
// The picture of a stress field (docs/stress.md): the slice y = 0 (or a
// meridian plane), shaded by the mean stress P, with the major principal
// direction as short bars and the two families of slip lines (alpha red,
// beta blue) traced through the field from points along the free surface.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/error.h"
#include "draw/canvas.h"
#include "render/palette.h"
#include "render/panel.h"
#include "render/stress.h"

#define GF_PI 3.14159265358979323846

typedef struct gf_stress_view {
    double scale, margin, zmax, xmin; // pixels per d, border px, picture top (d), left edge (d)
    int height;
} gf_stress_view;

static double gf_px(const gf_stress_view *v, double x) { return v->margin + (x - v->xmin) * v->scale; }
static double gf_py(const gf_stress_view *v, double z) { return v->margin + 36.0 + (v->zmax - z) * v->scale; }

// The field at a point of the picture: u = |x| about the axis (mirrored).
// The outline of the slice as a closed cairo path.
static void gf_outline_path(cairo_t *cr, const gf_stress_view *v, const gf_outline *o)
{
    for (int i = 0; i < o->n; i++) (i ? cairo_line_to : cairo_move_to)(cr, gf_px(v, o->p[i][0]), gf_py(v, o->p[i][1]));
    cairo_close_path(cr);
}

static bool gf_stress_pic_at(const gf_stress_field *f, double x, double z, gf_stress_point *p, double *sign)
{
    *sign = f->axisym && x < 0.0 ? -1.0 : 1.0;
    return gf_stress_at(f, f->axisym ? fabs(x) : x, z, p);
}

// One slip line from (x, z): steps of h along the family's direction (k = 0:
// alpha at psi - eps, 1: beta at psi + eps), downwards, until it leaves the field.
static void gf_trace(cairo_t *cr, const gf_stress_view *v, const gf_stress_field *f, double x, double z, int k)
{
    double h = 0.25 * f->du;
    cairo_move_to(cr, gf_px(v, x), gf_py(v, z));
    double prev[2] = {0.0, -1.0};
    for (int i = 0; i < 4000; i++) {
        gf_stress_point p;
        double sg;
        if (!gf_stress_pic_at(f, x, z, &p, &sg)) break;
        double psi = sg > 0 ? p.psi : GF_PI - p.psi; // mirrored on the left of the axis
        double a = k ? psi + f->eps : psi - f->eps, d[2] = {cos(a), sin(a)};
        if (d[0] * prev[0] + d[1] * prev[1] < 0.0) d[0] = -d[0], d[1] = -d[1]; // keep going the same way
        double nx = x + h * d[0], nz = z + h * d[1];
        if (!gf_stress_pic_at(f, nx, nz, &p, &sg)) break; // stop at the wall, not beyond it
        x = nx;
        z = nz;
        prev[0] = d[0];
        prev[1] = d[1];
        cairo_line_to(cr, gf_px(v, x), gf_py(v, z));
    }
    cairo_stroke(cr);
}

gf_status gf_render_stress(const gf_stress_field *f, const gf_container *c, const char *title, const char *path)
{
    double lo[3], hi[3];
    gf_container_bounds(c, f->ztop, lo, hi);
    gf_stress_view v = {.margin = 12.0, .zmax = f->ztop};
    v.xmin = lo[0];
    double w = hi[0] - lo[0], hgt = f->ztop - fmin(0.0, lo[2]);
    v.scale = fmin(10.0, 1200.0 / fmax(w, hgt));
    v.scale = fmax(v.scale, fmin(10.0, 300.0 / w)); // room for the legend
    int W = (int)ceil(2 * v.margin + w * v.scale), H = (int)ceil(2 * v.margin + 36.0 + hgt * v.scale);
    gf_canvas cv;
    gf_status st = gf_canvas_open(&cv, path, GF_RENDER_AUTO, W, H);
    if (st != GF_OK) return st;
    cairo_t *cr = cv.cr;
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    // P shaded from white (0) to a deep blue (the largest P).
    double pmax = 0.0;
    for (size_t k = 0; k < (size_t)f->nu * f->nz; k++)
        if (f->in[k]) pmax = fmax(pmax, f->pt[k].p);
    gf_outline o;
    gf_container_outline(c, f->ztop, &o);
    gf_outline_path(cr, &v, &o); // the shading clipped to the inside
    cairo_save(cr);
    cairo_clip(cr);
    double cell = fmax(f->du, f->dz) * 0.5;
    for (double z = f->z0; z <= f->ztop; z += cell)
        for (double x = lo[0]; x <= hi[0]; x += cell) {
            gf_stress_point p;
            double sg;
            if (!gf_stress_pic_at(f, x + 0.5 * cell, z + 0.5 * cell, &p, &sg)) continue;
            double t = pmax > 0 ? fmin(1.0, p.p / pmax) : 0.0;
            cairo_set_source_rgb(cr, 1.0 - 0.75 * t, 1.0 - 0.6 * t, 1.0 - 0.25 * t);
            cairo_rectangle(cr, gf_px(&v, x), gf_py(&v, z + cell), cell * v.scale + 0.5, cell * v.scale + 0.5);
            cairo_fill(cr);
        }
    cairo_restore(cr);
    // The walls.
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    cairo_set_line_width(cr, 2.0);
    gf_outline_path(cr, &v, &o);
    cairo_stroke(cr);
    // Slip lines from points along the surface, and from the walls' tops.
    int nseed = (int)fmax(6.0, w / 4.0);
    cairo_set_line_width(cr, 1.0);
    for (int k = 0; k < 2; k++) {
        if (k == 0)
            cairo_set_source_rgba(cr, 0.8, 0.1, 0.1, 0.8);
        else
            cairo_set_source_rgba(cr, 0.1, 0.2, 0.8, 0.8);
        for (int i = 0; i <= nseed; i++) {
            double x = lo[0] + (hi[0] - lo[0]) * (i + 0.5 * k) / (nseed + 0.5);
            gf_trace(cr, &v, f, x, f->ztop - 0.5 * f->dz, k);
        }
        // More from the walls, down their height, so the converging part has lines too.
        for (double z = f->ztop - 4.0; z > f->z0; z -= fmax(4.0, hgt / 12.0)) {
            gf_trace(cr, &v, f, lo[0] + 0.6 * f->du, z, k);
            gf_trace(cr, &v, f, hi[0] - 0.6 * f->du, z, k);
        }
    }
    // The major principal direction: a bar at every few nodes.
    double step = fmax(2.0, 4.0 * f->du), bar = 0.8 * step;
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_set_line_width(cr, 1.5);
    for (double z = f->z0 + 0.5 * step; z < f->ztop; z += step)
        for (double x = lo[0] + 0.5 * step; x < hi[0]; x += step) {
            gf_stress_point p;
            double sg;
            if (!gf_container_contains(c, x, 0.5 * (lo[1] + hi[1]), z, 0.25 * bar, 0.0) ||
                !gf_stress_pic_at(f, x, z, &p, &sg))
                continue;
            double psi = sg > 0 ? p.psi : GF_PI - p.psi, dx = 0.5 * bar * cos(psi), dz = 0.5 * bar * sin(psi);
            cairo_move_to(cr, gf_px(&v, x - dx), gf_py(&v, z - dz));
            cairo_line_to(cr, gf_px(&v, x + dx), gf_py(&v, z + dz));
            cairo_stroke(cr);
        }
    char line[256];
    snprintf(line, sizeof line, "%s: stress, phi = %g, phi_w = %g deg", title ? title : "", f->def.friction_angle,
             f->def.wall_friction_angle);
    gf_panel_text(cr, v.margin, v.margin + 10.0, 11.0, line);
    gf_panel_text(cr, v.margin, v.margin + 24.0, 9.0, "bars: major stress; red, blue: slip lines; shade: P");
    (void)gf_palette_text;
    return gf_canvas_commit(&cv);
}

gf_status gf_render_stress_of_run(const char *dir, const gf_config *cfg, const char *outdir, const char *ext,
                                  const char *title, const char **written)
{
    static char out[GF_PATH_MAX + 64];
    *written = NULL;
    char csv[GF_PATH_MAX + 32], line[1024];
    snprintf(csv, sizeof csv, "%s/stress.csv", dir);
    FILE *fp = fopen(csv, "r");
    if (!fp) return GF_OK;
    const char *key = "ztop = ";
    char *at = fgets(line, sizeof line, fp) ? strstr(line, key) : NULL;
    fclose(fp);
    double ztop = 0.0;
    if (!at || sscanf(at + strlen(key), "%lf", &ztop) != 1)
        return gf_error_set(GF_ERR_PARAM, "%s: no 'ztop = ' in its first line", csv);
    gf_container c = gf_container_make(cfg);
    gf_stress_def def = gf_config_stress_def(cfg);
    gf_stress_field f;
    gf_status st = gf_stress_solve(&def, &c, ztop, &f);
    if (st != GF_OK) return st;
    snprintf(out, sizeof out, "%s/stress.%s", outdir, ext);
    st = gf_render_stress(&f, &c, title, out);
    gf_stress_free(&f);
    if (st == GF_OK) *written = out;
    return st;
}
