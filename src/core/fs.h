// SPDX-License-Identifier: MIT
// Internal: the file-system chores of run, analysis, render and DEM directories:
// mkdir -p, remove a file or a tree, clear a directory of the files a tool wrote.
#ifndef GF_CORE_FS_H
#define GF_CORE_FS_H

#include <stddef.h>

#include "granflow/core.h"

// gf_fs_mkdirs (mkdir -p) is public: see granflow/core.h.

/// Removes a file; a missing one is not an error.
gf_status gf_fs_remove(const char *path);

/// rm -r of a directory the tools wrote (analysis/, render/); symbolic links
/// are removed, never followed. A missing path is not an error.
gf_status gf_fs_remove_tree(const char *path);

/// Removes the files of `dir` whose name starts with `prefix` and ends with
/// one of the `nsuffix` suffixes (each name longer than prefix and suffix
/// together). A missing dir is not an error.
gf_status gf_fs_clear(const char *dir, const char *prefix, const char *const *suffixes, size_t nsuffix);

#endif
