// SPDX-License-Identifier: MIT
// Pictures (cairo): hand-placed particles rendered and read back pixel by
// pixel (colour at disc centres, background, the y < 0 half not drawn, walls
// and orifice, depth order), the documented layout and sizes, SVG and PDF
// output, the contact sheet, and failures that leave no file behind.
#include "support.h"

#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "granflow/granflow.h"
#include "granflow/render.h"
#include "render/palette.h"

#if defined(__SANITIZE_ADDRESS__)
// fontconfig, reached through cairo's text, keeps a few hundred bytes of font
// patterns for the life of the process (freed only by FcFini); not our leak.
const char *__lsan_default_suppressions(void);
__attribute__((visibility("default"))) const char *__lsan_default_suppressions(void) { return "leak:libfontconfig.so\n"; }
#endif

// ---------------------------------------------------------------------------
// helpers

// A 10 x 4 container with a 3 d orifice: walls at x = +-5, base at z = 0.
static gf_config small_box(void)
{
    gf_config c = gf_config_default();
    c.container_width = 10;
    c.container_depth = 4;
    c.orifice_diameter = 3;
    c.exit_z = 0;
    return c;
}

static void push(gf_packing *pk, int64_t id, int32_t layer, double x, double y, double z)
{
    assert_int_equal(gf_packing_push(pk, id, layer, x, y, z, 0.5), GF_OK);
}

// Four visible particles and one behind the viewer (y < 0), one hidden
// behind another (same x, z, larger y, listed after it).
static void scene(gf_packing *pk)
{
    push(pk, 1, 1, -2.0, 0.5, 2.0);  // A: layer 1, in front of E
    push(pk, 2, 2, 2.0, 1.0, 2.0);   // B: layer 2
    push(pk, 3, 1, 0.0, -1.0, 5.0);  // C: y < 0, not drawn
    push(pk, 4, 3, 3.0, 0.5, 6.0);   // D: layer 3 (odd, like layer 1)
    push(pk, 5, 2, -2.0, 1.8, 2.0);  // E: behind A
    push(pk, 6, 4, -3.5, 0.2, 0.6);  // F: layer 4, near the base
}

// A path in the test's directory (static storage, eight in rotation).
static const char *tmp_path(const char *name)
{
    static char buf[8][1024];
    static int next;
    char *b = buf[next++ % 8];
    snprintf(b, sizeof buf[0], "%s/%s", gf_test_tmpdir(), name);
    return b;
}

// Whether `needle` occurs in the last `tail` bytes of data[0..len).
static int in_tail(const char *data, size_t len, const char *needle, size_t tail)
{
    size_t m = strlen(needle), from = len > tail ? len - tail : 0;
    for (size_t i = from; i + m <= len; i++)
        if (!memcmp(data + i, needle, m)) return 1;
    return 0;
}

static int exists(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0;
}

static void render_ok(gf_status st)
{
    if (st != GF_OK) print_error("render: %s: %s\n", gf_status_str(st), gf_last_error());
    assert_int_equal(st, GF_OK);
}

typedef struct image {
    cairo_surface_t *s;
    int w, h, stride;
    const unsigned char *data;
} image;

static image load_png(const char *path)
{
    image im = {0};
    im.s = cairo_image_surface_create_from_png(path);
    if (cairo_surface_status(im.s) != CAIRO_STATUS_SUCCESS)
        fail_msg("cannot read %s back: %s", path, cairo_status_to_string(cairo_surface_status(im.s)));
    cairo_surface_flush(im.s);
    im.w = cairo_image_surface_get_width(im.s);
    im.h = cairo_image_surface_get_height(im.s);
    im.stride = cairo_image_surface_get_stride(im.s);
    im.data = cairo_image_surface_get_data(im.s);
    return im;
}

static void free_image(image *im) { cairo_surface_destroy(im->s); }

// The pixel (px, py) as 0-255 components.
static void pixel(const image *im, int px, int py, int rgb[3])
{
    assert_true(px >= 0 && px < im->w && py >= 0 && py < im->h);
    uint32_t v;
    memcpy(&v, im->data + (size_t)py * (size_t)im->stride + 4 * (size_t)px, 4);
    rgb[0] = (int)((v >> 16) & 255);
    rgb[1] = (int)((v >> 8) & 255);
    rgb[2] = (int)(v & 255);
}

// The documented layout (render.h): x from -W/2 - 2, z down from zmax + 1,
// below a label strip of gf_render_label_px pixels; (ox, oy) a panel's corner.
typedef struct layout {
    double s, xlo, ztop;
    int label, ox, oy;
} layout;

static layout layout_of(const gf_config *c, const gf_render_opts *o, double zmax)
{
    return (layout){o->px_per_d, -0.5 * c->container_width - 2.0, zmax + 1.0, gf_render_label_px(o), 0, 0};
}

// Pixel colour at the point (x, z) of the view, compared with `want` (sRGB
// in [0, 1]): 8-bit rounding by cairo and libpng gives at most 1 level, we
// allow 2.
static void expect_colour_at(const image *im, const layout *L, double x, double z, const double want[3],
                             const char *what)
{
    int px = L->ox + (int)floor((x - L->xlo) * L->s), py = L->oy + L->label + (int)floor((L->ztop - z) * L->s);
    int got[3];
    pixel(im, px, py, got);
    for (int k = 0; k < 3; k++)
        if (abs(got[k] - (int)lround(255.0 * want[k])) > 2)
            fail_msg("%s at (x %g, z %g) = pixel (%d, %d): got rgb(%d, %d, %d), want rgb(%ld, %ld, %ld)", what, x,
                     z, px, py, got[0], got[1], got[2], lround(255 * want[0]), lround(255 * want[1]),
                     lround(255 * want[2]));
}

static void layer_rgb(int32_t layer, double c[3]) { gf_palette_layer(layer, c); }

// ---------------------------------------------------------------------------

static void layer_colours_background_and_walls(void **state)
{
    (void)state;
    gf_config c = small_box();
    gf_packing pk = {0};
    scene(&pk);
    gf_render_opts o = gf_render_opts_default();
    o.zmax = 8.0;
    const char *path = tmp_path("layers.png");
    render_ok(gf_render_slice(&pk, 12.5, &c, NULL, &o, path));
    assert_false(exists(tmp_path("layers.png.tmp")));
    image im = load_png(path);
    layout L = layout_of(&c, &o, 8.0);
    double c1[3], c2[3];
    layer_rgb(1, c1);
    layer_rgb(2, c2);
    // the two layer colours must be clearly different (sum of |differences| > 0.5)
    assert_true(fabs(c1[0] - c2[0]) + fabs(c1[1] - c2[1]) + fabs(c1[2] - c2[2]) > 0.5);

    expect_colour_at(&im, &L, -2.0, 2.0, c1, "A (layer 1, in front of E of layer 2)");
    expect_colour_at(&im, &L, 2.0, 2.0, c2, "B (layer 2)");
    expect_colour_at(&im, &L, 3.0, 6.0, c1, "D (layer 3 = odd)");
    expect_colour_at(&im, &L, -3.5, 0.6, c2, "F (layer 4 = even)");
    expect_colour_at(&im, &L, 0.0, 5.0, gf_palette_inside, "C (y < 0: not drawn, background)");
    expect_colour_at(&im, &L, 0.0, 3.5, gf_palette_inside, "empty space in the container");
    expect_colour_at(&im, &L, 3.0, 6.0 + 0.7, gf_palette_inside, "just above D");
    expect_colour_at(&im, &L, -6.5, 4.0, gf_palette_outside, "outside the left wall");
    expect_colour_at(&im, &L, -5.25, 4.0, gf_palette_wall, "left wall");
    expect_colour_at(&im, &L, 5.25, 4.0, gf_palette_wall, "right wall");
    expect_colour_at(&im, &L, -4.0, -0.25, gf_palette_wall, "base");
    expect_colour_at(&im, &L, 0.0, -0.25, gf_palette_outside, "orifice (a gap in the base)");
    expect_colour_at(&im, &L, 0.0, -1.5, gf_palette_outside, "below the orifice");
    // the label strip holds dark text ("t = 12.5 tau") and nothing else is that dark there
    int dark = 0, rgb[3];
    for (int py = 0; py < L.label; py++)
        for (int px = 0; px < im.w; px++) {
            pixel(&im, px, py, rgb);
            dark += rgb[0] + rgb[1] + rgb[2] < 200;
        }
    assert_true(dark > 20);
    free_image(&im);
    gf_packing_free(&pk);
}

static void size_follows_scale(void **state)
{
    (void)state;
    gf_config c = small_box();
    gf_packing pk = {0};
    scene(&pk);
    gf_render_opts o = gf_render_opts_default();
    o.zmax = 8.0;
    // view: x over W + 4 = 14 d, z from -2 to zmax + 1 = 9, i.e. 11 d; label max(4 s, 28) px
    const double scales[] = {4.0, 8.0, 12.0};
    const int want_w[] = {56, 112, 168}, want_h[] = {28 + 44, 32 + 88, 48 + 132};
    for (int k = 0; k < 3; k++) {
        o.px_per_d = scales[k];
        int w, h;
        render_ok(gf_render_slice_size(&pk, &c, &o, &w, &h));
        assert_int_equal(w, want_w[k]);
        assert_int_equal(h, want_h[k]);
        const char *path = tmp_path("scale.png");
        render_ok(gf_render_slice(&pk, 0.0, &c, NULL, &o, path));
        image im = load_png(path);
        assert_int_equal(im.w, want_w[k]);
        assert_int_equal(im.h, want_h[k]);
        free_image(&im);
    }
    // phi mode adds the colour bar strip: max(10 d, 84 px)
    o.colour = GF_RENDER_PHI;
    o.px_per_d = 12.0;
    int w, h;
    render_ok(gf_render_slice_size(&pk, &c, &o, &w, &h));
    assert_int_equal(w, 168 + 120);
    o.px_per_d = 4.0;
    render_ok(gf_render_slice_size(&pk, &c, &o, &w, &h));
    assert_int_equal(w, 56 + 84);
    // no label: no strip
    o.label = false;
    o.colour = GF_RENDER_LAYER;
    render_ok(gf_render_slice_size(&pk, &c, &o, &w, &h));
    assert_int_equal(h, 44);
    // zmax automatic: the highest particle top (D: 6.5), view top 7.5
    o.zmax = NAN;
    render_ok(gf_render_slice_size(&pk, &c, &o, &w, &h));
    assert_int_equal(h, (int)ceil((7.5 + 2.0) * 4.0));
    gf_packing_free(&pk);
}

static void phi_colours(void **state)
{
    (void)state;
    gf_config c = small_box();
    gf_packing pk = {0};
    scene(&pk);
    double phi[6] = {0.55, 0.65, 0.60, 0.60, 0.60, NAN}; // A loose, B dense, F unknown
    gf_render_opts o = gf_render_opts_default();
    o.zmax = 8.0;
    o.colour = GF_RENDER_PHI;
    const char *path = tmp_path("phi.png");
    render_ok(gf_render_slice(&pk, 3.0, &c, phi, &o, path));
    image im = load_png(path);
    layout L = layout_of(&c, &o, 8.0);
    double lo[3], hi[3], mid[3];
    gf_palette_phi(0.55, 0.55, 0.65, lo);
    gf_palette_phi(0.65, 0.55, 0.65, hi);
    gf_palette_phi(0.60, 0.55, 0.65, mid);
    // the scale runs from red (loose) to blue (dense), through a light middle
    assert_true(lo[0] > lo[2] + 0.3);
    assert_true(hi[2] > hi[0] + 0.3);
    assert_true(mid[0] + mid[1] + mid[2] > 2.4);
    expect_colour_at(&im, &L, -2.0, 2.0, lo, "A (phi 0.55)");
    expect_colour_at(&im, &L, 2.0, 2.0, hi, "B (phi 0.65)");
    expect_colour_at(&im, &L, 3.0, 6.0, mid, "D (phi 0.60)");
    expect_colour_at(&im, &L, -3.5, 0.6, gf_palette_unknown, "F (phi NaN)");
    // values beyond the scale clamp at its dense end; below it they fade to white at 0
    double v[3];
    gf_palette_phi(0.9, 0.55, 0.65, v);
    for (int k = 0; k < 3; k++) gf_assert_near(v[k], hi[k], 1e-12);
    gf_palette_phi(0.0, 0.55, 0.65, v);
    for (int k = 0; k < 3; k++) gf_assert_near(v[k], 1.0, 1e-12);
    free_image(&im);
    // phi mode without phi values is an error, and writes nothing
    const char *none = tmp_path("phi_missing.png");
    assert_int_equal(gf_render_slice(&pk, 3.0, &c, NULL, &o, none), GF_ERR_PARAM);
    assert_false(exists(none));
    gf_packing_free(&pk);
}

static void svg_and_pdf(void **state)
{
    (void)state;
    gf_config c = small_box();
    gf_packing pk = {0};
    scene(&pk);
    gf_render_opts o = gf_render_opts_default();
    const struct {
        const char *name;
        gf_render_format fmt;
        const char *magic[2];
    } cases[] = {
        {"v.svg", GF_RENDER_AUTO, {"<?xml", "<svg"}},
        {"v.pdf", GF_RENDER_AUTO, {"%PDF", "%PDF"}},
        {"v.PDF", GF_RENDER_AUTO, {"%PDF", "%PDF"}},
        {"forced.png", GF_RENDER_SVG, {"<?xml", "<svg"}},
        {"forced.out", GF_RENDER_PDF, {"%PDF", "%PDF"}},
        {"plain.out", GF_RENDER_AUTO, {"\x89PNG", "\x89PNG"}},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        o.format = cases[k].fmt;
        const char *path = tmp_path(cases[k].name);
        render_ok(gf_render_slice(&pk, 1.0, &c, NULL, &o, path));
        char tmp[1100];
        snprintf(tmp, sizeof tmp, "%s.tmp", path);
        assert_false(exists(tmp));
        size_t len;
        char *text = gf_test_read_file(path, &len);
        assert_non_null(text);
        int ok = 0;
        for (int m = 0; m < 2; m++) ok |= len >= strlen(cases[k].magic[m]) && !memcmp(text, cases[k].magic[m], strlen(cases[k].magic[m]));
        if (!ok) fail_msg("%s does not start with %s", cases[k].name, cases[k].magic[0]);
        // complete files: the vector surfaces were finished before the rename
        if (!strcmp(cases[k].magic[1], "<svg")) assert_true(in_tail(text, len, "</svg>", 64));
        if (!strcmp(cases[k].magic[0], "%PDF")) assert_true(in_tail(text, len, "%%EOF", 64));
        free(text);
    }
    gf_packing_free(&pk);
}

static void failures_leave_no_file(void **state)
{
    (void)state;
    gf_config c = small_box();
    gf_packing pk = {0};
    scene(&pk);
    gf_render_opts o = gf_render_opts_default();
    // a directory that does not exist
    const char *missing = tmp_path("no_such_dir/x.png");
    gf_status st = gf_render_slice(&pk, 0.0, &c, NULL, &o, missing);
    assert_int_equal(st, GF_ERR_IO);
    assert_non_null(strstr(gf_last_error(), "no_such_dir"));
    assert_false(exists(missing));
    // the target is a directory: the picture is drawn to PATH.tmp, the rename
    // fails, and PATH.tmp is removed
    const char *dir = tmp_path("a_directory.png");
    assert_int_equal(mkdir(dir, 0777), 0);
    st = gf_render_slice(&pk, 0.0, &c, NULL, &o, dir);
    assert_int_equal(st, GF_ERR_IO);
    assert_false(exists(tmp_path("a_directory.png.tmp")));
    o.format = GF_RENDER_PDF;
    assert_int_equal(gf_render_slice(&pk, 0.0, &c, NULL, &o, dir), GF_ERR_IO);
    assert_false(exists(tmp_path("a_directory.png.tmp")));
    o.format = GF_RENDER_AUTO;
    // bad options: an earlier picture at the path stays as it was
    const char *keep = tmp_path("keep.png");
    render_ok(gf_render_slice(&pk, 0.0, &c, NULL, &o, keep));
    size_t len0, len1;
    char *before = gf_test_read_file(keep, &len0);
    o.px_per_d = 0.0;
    assert_int_equal(gf_render_slice(&pk, 0.0, &c, NULL, &o, keep), GF_ERR_PARAM);
    o.px_per_d = 200.0; // 14 d x 200 = 2800 px wide is fine, but zmax 1000 d is too tall
    o.zmax = 1000.0;
    assert_int_equal(gf_render_slice(&pk, 0.0, &c, NULL, &o, keep), GF_ERR_PARAM);
    o = gf_render_opts_default();
    o.phi_lo = 0.7;
    o.phi_hi = 0.6;
    assert_int_equal(gf_render_slice(&pk, 0.0, &c, NULL, &o, keep), GF_ERR_PARAM);
    char *after = gf_test_read_file(keep, &len1);
    assert_true(len0 == len1 && memcmp(before, after, len0) == 0);
    free(before);
    free(after);
    gf_config bad = c;
    bad.container_width = -1;
    o = gf_render_opts_default();
    assert_int_equal(gf_render_slice(&pk, 0.0, &bad, NULL, &o, tmp_path("bad.png")), GF_ERR_PARAM);
    assert_false(exists(tmp_path("bad.png")));
    assert_int_equal(gf_render_sheet(NULL, 0, &c, NULL, &o, tmp_path("bad.png")), GF_ERR_PARAM);
    gf_packing_free(&pk);
}

static void contact_sheet(void **state)
{
    (void)state;
    gf_config c = small_box();
    gf_frame fr[3] = {0};
    for (int k = 0; k < 3; k++) {
        fr[k].time = 2.0 * k;
        // one particle a frame, falling: z = 6, 4, 2, layer k + 1
        push(&fr[k].pk, 1, k + 1, 1.0, 0.5, 6.0 - 2.0 * k);
    }
    gf_render_opts o = gf_render_opts_default();
    o.px_per_d = 6.0;
    const char *path = tmp_path("sheet.png");
    render_ok(gf_render_sheet(fr, 3, &c, NULL, &o, path));
    image im = load_png(path);
    // one row of three panels of 14 d each, all up to the highest top (6.5 d)
    layout L = layout_of(&c, &o, 6.5);
    int pw = (int)ceil(14.0 * o.px_per_d);
    assert_int_equal(im.w, 3 * pw);
    assert_int_equal(im.h, L.label + (int)ceil((7.5 + 2.0) * o.px_per_d));
    for (int k = 0; k < 3; k++) {
        double col[3];
        layer_rgb(k + 1, col);
        L.ox = k * pw;
        expect_colour_at(&im, &L, 1.0, 6.0 - 2.0 * k, col, "the particle of this panel");
        for (int j = 0; j < 3; j++)
            if (j != k) expect_colour_at(&im, &L, 1.0, 6.0 - 2.0 * j, gf_palette_inside, "where another panel's particle is");
        expect_colour_at(&im, &L, 5.25, 3.0, gf_palette_wall, "right wall of this panel");
    }
    free_image(&im);
    // phi mode: a colour bar on the right; the phi arrays are required
    o.colour = GF_RENDER_PHI;
    double p0[1] = {0.55}, p1[1] = {0.6}, p2[1] = {0.65};
    const double *phi[3] = {p0, p1, p2};
    render_ok(gf_render_sheet(fr, 3, &c, phi, &o, path));
    im = load_png(path);
    assert_int_equal(im.w, 3 * pw + 84);
    double hi[3];
    gf_palette_phi(0.65, o.phi_lo, o.phi_hi, hi);
    L.ox = 2 * pw;
    expect_colour_at(&im, &L, 1.0, 2.0, hi, "the dense particle of the last panel");
    free_image(&im);
    assert_int_equal(gf_render_sheet(fr, 3, &c, NULL, &o, tmp_path("sheet_nophi.png")), GF_ERR_PARAM);
    // a title adds a strip on top; SVG works for sheets too
    o.colour = GF_RENDER_LAYER;
    o.title = "a run";
    render_ok(gf_render_sheet(fr, 3, &c, NULL, &o, path));
    im = load_png(path);
    assert_int_equal(im.h, 2 * L.label + (int)ceil((7.5 + 2.0) * o.px_per_d));
    free_image(&im);
    render_ok(gf_render_sheet(fr, 3, &c, NULL, &o, tmp_path("sheet.svg")));
    for (int k = 0; k < 3; k++) gf_packing_free(&fr[k].pk);
}

static void empty_packing_draws_the_container(void **state)
{
    (void)state;
    gf_config c = small_box();
    c.exit_z = -1.0; // the exit line is drawn below the orifice; the view reaches z = -3
    gf_packing pk = {0};
    gf_render_opts o = gf_render_opts_default();
    const char *path = tmp_path("empty.png");
    render_ok(gf_render_slice(&pk, 0.0, &c, NULL, &o, path));
    image im = load_png(path);
    // zmax: at least the orifice diameter (3), so the view is z in [-3, 4]
    assert_int_equal(im.h, gf_render_label_px(&o) + 70);
    layout L = layout_of(&c, &o, 3.0);
    expect_colour_at(&im, &L, 0.0, 1.0, gf_palette_inside, "inside");
    expect_colour_at(&im, &L, -5.25, 1.0, gf_palette_wall, "left wall");
    expect_colour_at(&im, &L, 0.0, -0.5, gf_palette_outside, "orifice");
    free_image(&im);
}

// ---------------------------------------------------------------------------
// gf_render_dir: the pictures of a series

typedef struct written_list {
    char names[16][64];
    size_t n;
} written_list;

static void note_written(void *ctx, const char *path)
{
    written_list *w = ctx;
    assert_true(w->n < 16);
    const char *slash = strrchr(path, '/');
    snprintf(w->names[w->n++], sizeof w->names[0], "%s", slash ? slash + 1 : path);
    struct stat sb;
    assert_int_equal(stat(path, &sb), 0);
}

/// A multi-frame dump of three frames at t = 0, 2 and 4 in a 10 x 4 box.
static const char *three_frames(void)
{
    static char path[1200];
    char dir[1100];
    snprintf(dir, sizeof dir, "%s/renderdir", gf_test_tmpdir());
    mkdir(dir, 0777);
    const char *frame = "ITEM: TIME\n%d\nITEM: TIMESTEP\n%d\nITEM: NUMBER OF ATOMS\n3\nITEM: BOX BOUNDS ff ff ff\n"
                        "-5 5\n-2 2\n0 9\nITEM: ATOMS id type x y z\n1 1 -1 0.5 %g\n2 1 0 0.5 1.5\n3 2 1 0.5 3.5\n";
    char text[2048];
    size_t len = 0;
    for (int k = 0; k < 3; k++) len += (size_t)snprintf(text + len, sizeof text - len, frame, 2 * k, 20 * k, 0.5 + k);
    snprintf(path, sizeof path, "%s", gf_test_write_file(dir, "run.dump", text));
    return path;
}

static void render_dir_default_set(void **state)
{
    (void)state;
    const char *dump = three_frames();
    written_list w = {0};
    gf_render_dir_opts o = gf_render_dir_opts_default();
    assert_string_equal(o.format, "png");
    assert_true(o.scale == 10 && o.panels == 8 && o.colour == GF_RENDER_LAYER && !o.outdir);
    o.scale = 3;
    o.written = note_written;
    o.ctx = &w;
    if (gf_render_dir(dump, &o) != GF_OK) fail_msg("gf_render_dir: %s", gf_last_error());
    // first, middle and last by layer, the last by packing fraction, the sheet; in render/ beside the dump
    const char *want[] = {"slice_000000.png", "slice_000001.png", "slice_000002.png", "slice_000002_phi.png",
                          "sheet.png"};
    assert_int_equal(w.n, 5);
    for (size_t k = 0; k < 5; k++) assert_string_equal(w.names[k], want[k]);
    char path[1300];
    snprintf(path, sizeof path, "%s/renderdir/render/sheet.png", gf_test_tmpdir());
    struct stat sb;
    assert_int_equal(stat(path, &sb), 0);

    // The snapshot nearest a time, with a warning when none is at it; phi-raw names.
    w.n = 0;
    double times[] = {2.9};
    o.times = times;
    o.ntimes = 1;
    o.colour = GF_RENDER_PHI;
    o.raw = true;
    snprintf(path, sizeof path, "%s/renderdir/out", gf_test_tmpdir());
    o.outdir = path;
    gf_warnings_clear();
    if (gf_render_dir(dump, &o) != GF_OK) fail_msg("gf_render_dir: %s", gf_last_error());
    assert_int_equal(w.n, 1);
    assert_string_equal(w.names[0], "slice_000001_phi_raw.png");
    assert_int_equal(gf_warning_count(), 1);
    assert_non_null(strstr(gf_warning(0), "no snapshot at t = 2.9"));
    gf_warnings_clear();
}

static void render_dir_refuses_bad_options(void **state)
{
    (void)state;
    const char *dump = three_frames();
    gf_render_dir_opts o = gf_render_dir_opts_default();
    o.format = "gif";
    assert_int_equal(gf_render_dir(dump, &o), GF_ERR_PARAM);
    assert_non_null(strstr(gf_last_error(), "gif"));
    o = gf_render_dir_opts_default();
    o.scale = 0.5;
    assert_int_equal(gf_render_dir(dump, &o), GF_ERR_PARAM);
    o = gf_render_dir_opts_default();
    o.panels = 0;
    assert_int_equal(gf_render_dir(dump, &o), GF_ERR_PARAM);
    o = gf_render_dir_opts_default();
    double t = 1;
    o.times = &t;
    o.ntimes = 1;
    o.all = true;
    assert_int_equal(gf_render_dir(dump, &o), GF_ERR_PARAM);
    o = gf_render_dir_opts_default();
    char empty[1100];
    snprintf(empty, sizeof empty, "%s/renderdir/empty", gf_test_tmpdir());
    mkdir(empty, 0777);
    assert_int_not_equal(gf_render_dir(empty, &o), GF_OK);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(layer_colours_background_and_walls),
    cmocka_unit_test(size_follows_scale),
    cmocka_unit_test(phi_colours),
    cmocka_unit_test(svg_and_pdf),
    cmocka_unit_test(failures_leave_no_file),
    cmocka_unit_test(contact_sheet),
    cmocka_unit_test(empty_packing_draws_the_container),
    cmocka_unit_test(render_dir_default_set),
    cmocka_unit_test(render_dir_refuses_bad_options),
};

GF_TEST_MAIN("render", tests)
