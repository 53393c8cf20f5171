// SPDX-License-Identifier: MIT
// Internal: a run directory's config.ini, and for container.shape = mesh its
// own copy of the STL (docs/geometry.md, "Containers from STL").
#ifndef GF_RUN_MESH_COPY_H
#define GF_RUN_MESH_COPY_H

#include "granflow/config.h"

/// Saves `cfg` as `cfgpath` in run directory `dir`. A mesh container's STL
/// is first copied to dir/container.stl (atomically; nothing to do when it is
/// that file already, as on resume) and config.ini names it as
/// `mesh = container.stl`, read from config.ini's folder: the directory
/// resumes, analyses and renders wherever the original file went.
gf_status gf_run_save_config(const gf_config *cfg, const char *dir, const char *cfgpath);

#endif
