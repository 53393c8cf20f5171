// SPDX-License-Identifier: MIT
// The colours of the pictures.
#include "render/palette.h"

#include <math.h>

const double gf_palette_inside[3] = {0.965, 0.960, 0.945};  // warm off-white: the silo's interior
const double gf_palette_outside[3] = {1.0, 1.0, 1.0};
const double gf_palette_wall[3] = {0.20, 0.22, 0.25};       // dark slate
const double gf_palette_text[3] = {0.10, 0.10, 0.12};
const double gf_palette_unknown[3] = {0.62, 0.62, 0.62};

// Two colours far apart in hue and lightness, distinguishable with the common
// colour-vision deficiencies: burnt orange and a deep steel blue.
static const double gf_layer_rgb[2][3] = {
    {0.863, 0.408, 0.153}, // odd layers (the bottom one is layer 1)
    {0.176, 0.400, 0.659}, // even layers
};

void gf_palette_layer(int32_t layer, double rgb[3])
{
    int parity = (int)(((layer % 2) + 2) % 2);
    const double *c = gf_layer_rgb[parity == 1 ? 0 : 1];
    for (int k = 0; k < 3; k++) rgb[k] = c[k];
}

// ColorBrewer RdYlBu (11 classes), from red (loose) to blue (dense).
static const unsigned char gf_phi_hex[][3] = {
    {0xa5, 0x00, 0x26}, {0xd7, 0x30, 0x27}, {0xf4, 0x6d, 0x43}, {0xfd, 0xae, 0x61},
    {0xfe, 0xe0, 0x90}, {0xff, 0xff, 0xbf}, {0xe0, 0xf3, 0xf8}, {0xab, 0xd9, 0xe9},
    {0x74, 0xad, 0xd1}, {0x45, 0x75, 0xb4}, {0x31, 0x36, 0x95},
};
enum { GF_PHI_NSTOP = (int)(sizeof gf_phi_hex / sizeof gf_phi_hex[0]) };

int gf_palette_phi_stops(void) { return GF_PHI_NSTOP; }

void gf_palette_phi_stop(int k, double rgb[3])
{
    if (k < 0) k = 0;
    if (k >= GF_PHI_NSTOP) k = GF_PHI_NSTOP - 1;
    for (int c = 0; c < 3; c++) rgb[c] = gf_phi_hex[k][c] / 255.0;
}

void gf_palette_phi(double phi, double lo, double hi, double rgb[3])
{
    if (isnan(phi)) {
        for (int c = 0; c < 3; c++) rgb[c] = gf_palette_unknown[c];
        return;
    }
    if (phi < lo) { // white at 0, the scale's red at lo
        double t = phi > 0 && lo > 0 ? phi / lo : 0.0;
        double red[3];
        gf_palette_phi_stop(0, red);
        for (int c = 0; c < 3; c++) rgb[c] = 1.0 + t * (red[c] - 1.0);
        return;
    }
    double u = hi > lo ? (phi - lo) / (hi - lo) : 1.0;
    if (u > 1.0) u = 1.0;
    double pos = u * (GF_PHI_NSTOP - 1);
    int k = (int)floor(pos);
    if (k >= GF_PHI_NSTOP - 1) k = GF_PHI_NSTOP - 2;
    double f = pos - k, a[3], b[3];
    gf_palette_phi_stop(k, a);
    gf_palette_phi_stop(k + 1, b);
    for (int c = 0; c < 3; c++) rgb[c] = a[c] + f * (b[c] - a[c]);
}
