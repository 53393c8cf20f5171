// SPDX-License-Identifier: MIT
// One particle leaving through the orifice: the record the engine produces
// (gf_sim_exits), a run writes (exits.csv) and the analysis reads. Its own
// header so that readers of exits need not include the engine's.
#ifndef GRANFLOW_EXIT_H
#define GRANFLOW_EXIT_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/// One particle that left: id, time (tau) and where it crossed (x, y); the
/// pass it ended (1 for the initial packing, + 1 at each re-insertion) and
/// where that pass began: time and distance from the axis x = y = 0 (at
/// t = 0 for the first pass, else where it was put back on the surface).
typedef struct gf_exit {
    int64_t id;
    double time, x, y;
    int64_t pass;
    double entry_time, entry_r;
} gf_exit;

#ifdef __cplusplus
}
#endif
#endif
