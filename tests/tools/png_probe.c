// SPDX-License-Identifier: MIT
// png_probe: the pixels of a PNG, for the layout test of `granflow report`
// (tests/report_layout.sh), which measures where a browser drew each picture
// of the page from a screenshot: the test's pictures are solid colours, so a
// picture's box is the box of the pixels of its colour. Through cairo, which
// the library already uses; no image library for the test alone.
//
//   png_probe make OUT.png W H RRGGBB   a W x H picture of one colour
//   png_probe size IN.png               "W H"
//   png_probe box IN.png RRGGBB [TOL]   "X0 Y0 X1 Y1 N": the box (inclusive) of the N
//                                       pixels within TOL (default 8) of the colour
//                                       in each channel; "none" when there is none
//   png_probe pixel IN.png X Y          "RRGGBB" of that pixel
#include <cairo.h>

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int usage(void)
{
    fputs("usage: png_probe make OUT.png W H RRGGBB | size IN.png | box IN.png RRGGBB [TOL] | pixel IN.png X Y\n",
          stderr);
    return 2;
}

static int colour(const char *hex, unsigned rgb[3])
{
    unsigned v;
    if (strlen(hex) != 6 || sscanf(hex, "%6x", &v) != 1) return 0;
    rgb[0] = v >> 16 & 255;
    rgb[1] = v >> 8 & 255;
    rgb[2] = v & 255;
    return 1;
}

static cairo_surface_t *load(const char *path)
{
    cairo_surface_t *s = cairo_image_surface_create_from_png(path);
    if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
        fprintf(stderr, "png_probe: %s: %s\n", path, cairo_status_to_string(cairo_surface_status(s)));
        cairo_surface_destroy(s);
        return NULL;
    }
    cairo_surface_flush(s);
    return s;
}

// The pixel (x, y) as r, g, b (an opaque screenshot: no alpha to undo).
static void pixel(cairo_surface_t *s, int x, int y, unsigned rgb[3])
{
    const unsigned char *row = cairo_image_surface_get_data(s) + (size_t)y * (size_t)cairo_image_surface_get_stride(s);
    uint32_t p;
    memcpy(&p, row + 4 * (size_t)x, 4);
    rgb[0] = p >> 16 & 255;
    rgb[1] = p >> 8 & 255;
    rgb[2] = p & 255;
}

int main(int argc, char **argv)
{
    if (argc < 3) return usage();
    unsigned rgb[3];
    if (!strcmp(argv[1], "make")) {
        if (argc != 6 || !colour(argv[5], rgb)) return usage();
        int w = atoi(argv[3]), h = atoi(argv[4]);
        if (w < 1 || h < 1) return usage();
        cairo_surface_t *s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
        cairo_t *cr = cairo_create(s);
        cairo_set_source_rgb(cr, rgb[0] / 255.0, rgb[1] / 255.0, rgb[2] / 255.0);
        cairo_paint(cr);
        cairo_destroy(cr);
        cairo_status_t st = cairo_surface_write_to_png(s, argv[2]);
        cairo_surface_destroy(s);
        if (st != CAIRO_STATUS_SUCCESS) fprintf(stderr, "png_probe: %s: %s\n", argv[2], cairo_status_to_string(st));
        return st == CAIRO_STATUS_SUCCESS ? 0 : 1;
    }
    cairo_surface_t *s = load(argv[2]);
    if (!s) return 1;
    int w = cairo_image_surface_get_width(s), h = cairo_image_surface_get_height(s), rc = 0;
    if (!strcmp(argv[1], "size") && argc == 3) {
        printf("%d %d\n", w, h);
    } else if (!strcmp(argv[1], "box") && (argc == 4 || argc == 5) && colour(argv[3], rgb)) {
        int tol = argc == 5 ? atoi(argv[4]) : 8, x0 = w, y0 = h, x1 = -1, y1 = -1;
        long n = 0;
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                unsigned p[3];
                pixel(s, x, y, p);
                if (abs((int)p[0] - (int)rgb[0]) > tol || abs((int)p[1] - (int)rgb[1]) > tol ||
                    abs((int)p[2] - (int)rgb[2]) > tol)
                    continue;
                n++;
                if (x < x0) x0 = x;
                if (x > x1) x1 = x;
                if (y < y0) y0 = y;
                if (y > y1) y1 = y;
            }
        if (n) printf("%d %d %d %d %ld\n", x0, y0, x1, y1, n);
        else puts("none");
    } else if (!strcmp(argv[1], "pixel") && argc == 5) {
        int x = atoi(argv[3]), y = atoi(argv[4]);
        if (x < 0 || y < 0 || x >= w || y >= h) {
            fprintf(stderr, "png_probe: (%d, %d) is outside %d x %d\n", x, y, w, h);
            rc = 1;
        } else {
            unsigned p[3];
            pixel(s, x, y, p);
            printf("%02x%02x%02x\n", p[0], p[1], p[2]);
        }
    } else {
        rc = usage();
    }
    cairo_surface_destroy(s);
    return rc;
}
