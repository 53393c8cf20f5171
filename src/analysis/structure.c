// SPDX-License-Identifier: MIT
// Window selection shared by the structure measurements.
#include "analysis/structure.h"

#include <math.h>

void gf_structure_window(const gf_series *s, const gf_analysis_opts *o, size_t *k0, size_t *k1)
{
    double t0, t1;
    gf_analysis_window(o, s, &t0, &t1);
    gf_window_frames(s, t0, t1, k0, k1);
}
