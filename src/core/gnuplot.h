// SPDX-License-Identifier: MIT
// Internal: running gnuplot on a script, for every command that draws plots
// (analysis, dem): a process runner with no model knowledge, so it is core.
#ifndef GF_CORE_GNUPLOT_H
#define GF_CORE_GNUPLOT_H

/// Runs `gnuplot SCRIPT` with `dir` as its working directory. 0 when it drew
/// the plot, 1 when gnuplot is not installed, -1 when it failed.
int gf_gnuplot_run(const char *dir, const char *script);

#endif
