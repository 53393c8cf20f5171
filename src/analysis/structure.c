// SPDX-License-Identifier: MIT
// Window selection shared by the structure measurements.
#include "analysis/structure.h"

#include <math.h>

void gf_structure_window(const gf_series *s, const gf_analysis_opts *o, size_t *k0, size_t *k1)
{
    double t0, t1;
    gf_analysis_window(o, s, &t0, &t1);
    // Frame times come from text dumps: allow for their rounding.
    double eps = 1e-9 * fmax(1.0, fmax(fabs(t0), fabs(t1)));
    size_t a = 0;
    while (a < s->nframes && s->frames[a].time < t0 - eps) a++;
    size_t b = a;
    while (b < s->nframes && s->frames[b].time <= t1 + eps) b++;
    *k0 = a;
    *k1 = b;
}
