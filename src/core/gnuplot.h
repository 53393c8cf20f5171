// SPDX-License-Identifier: MIT
// Internal: running gnuplot on a script, for every command that draws plots
// (analysis, dem): a process runner with no model knowledge, so it is core.
#ifndef GF_CORE_GNUPLOT_H
#define GF_CORE_GNUPLOT_H

#include <stddef.h>

/// Runs `gnuplot SCRIPT` with `dir` as its working directory. 0 when it drew
/// the plot, 1 when gnuplot is not installed, -1 when it failed. gnuplot's
/// output is kept, never printed: on failure `msg` (may be NULL) gets its
/// line naming what went wrong.
int gf_gnuplot_run(const char *dir, const char *script, char *msg, size_t msgsize);

#endif
