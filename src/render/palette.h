// SPDX-License-Identifier: MIT
// Internal: the colours of the pictures (layers, packing fraction, walls, background).
#ifndef GF_RENDER_PALETTE_H
#define GF_RENDER_PALETTE_H

#include <stdint.h>

/// Inside the container, outside it, walls and base, text. sRGB in [0, 1].
extern const double gf_palette_inside[3];
extern const double gf_palette_outside[3];
extern const double gf_palette_wall[3];
extern const double gf_palette_text[3];
/// Particles whose packing fraction is unknown (NaN).
extern const double gf_palette_unknown[3];

/// Colour of initial layer `layer`: odd and even layers alternate between two
/// contrasting colours (2009 paper Fig. 3).
void gf_palette_layer(int32_t layer, double rgb[3]);

/// Colour of packing fraction phi on the scale [lo, hi] (reversed ColorBrewer
/// RdYlBu: loose = red, dense = blue), clamped above hi; below lo it fades
/// from the red of lo to white at phi = 0 (2009 paper Fig. 4 caption). NaN:
/// gf_palette_unknown.
void gf_palette_phi(double phi, double lo, double hi, double rgb[3]);

/// Number of stops of the phi scale, and stop k (k = 0 at lo ... n-1 at hi),
/// for drawing the colour bar as a gradient equal to gf_palette_phi.
int gf_palette_phi_stops(void);
void gf_palette_phi_stop(int k, double rgb[3]);

#endif
