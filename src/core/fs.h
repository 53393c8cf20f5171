// SPDX-License-Identifier: MIT
// Internal: the file-system chores of run, analysis, render and DEM directories:
// mkdir -p, remove a file or a tree, clear a directory of the files a tool wrote
// (fs.c); open and read files that must be regular ones of bounded size (fs_read.c).
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

/// Opens `path` read-only if it is a regular file of at most `max_bytes`
/// bytes (0: any size), and gives its descriptor in *fd (close-on-exec, blocking).
/// A FIFO is opened without blocking (O_NONBLOCK) and refused like a device,
/// socket or directory: GF_ERR_IO "PATH: not a regular file (a FIFO)"; a larger
/// file: GF_ERR_FORMAT "PATH: N bytes, more than the M expected". For files a
/// run or an analysis wrote and a later command reads back: a link to
/// /dev/zero or a FIFO in their place must not make that command endless.
gf_status gf_fs_open_regular(const char *path, long long max_bytes, int *fd);

/// The whole of the regular file `path` (gf_fs_open_regular: at most
/// `max_bytes`, 0: any size) in a block of the core allocator, NUL-terminated:
/// *len bytes read, *cap allocated (free with gf_free(*data, *cap)). A file
/// that grows while it is read past its size at open is refused (GF_ERR_FORMAT);
/// out of memory is GF_ERR_NOMEM, a read error GF_ERR_IO, each naming the file.
gf_status gf_fs_read_all(const char *path, long long max_bytes, unsigned char **data, size_t *len, size_t *cap);

#endif
