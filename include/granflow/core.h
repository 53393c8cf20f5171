// SPDX-License-Identifier: MIT
// granflow core: export macro, status codes, last-error text, allocation accounting.
#ifndef GRANFLOW_CORE_H
#define GRANFLOW_CORE_H

#include <stddef.h>
#include <stdint.h>

#include "granflow/version.h"

#if defined(GF_BUILDING)
#define GF_API __attribute__((visibility("default")))
#else
#define GF_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/// Result of every fallible granflow call. Details are in gf_last_error().
typedef enum gf_status {
    GF_OK = 0,          ///< success
    GF_ERR_PARAM,       ///< an argument or configuration value is invalid
    GF_ERR_IO,          ///< a file could not be opened, read, written or renamed
    GF_ERR_FORMAT,      ///< a data file is malformed or truncated
    GF_ERR_NOMEM,       ///< an allocation failed
    GF_ERR_STATE,       ///< the call does not fit the object's state (e.g. corrupt checkpoint)
    GF_ERR_INTERRUPTED, ///< a run stopped early on request (SIGINT/SIGTERM); state is saved
    GF_ERR_EXISTS,      ///< the output directory already holds a run or results (resume, force, or another one)
} gf_status;

/// Short fixed name of a status ("ok", "invalid parameter", ...). Never NULL.
GF_API const char *gf_status_str(gf_status status);

/// Human-readable message of the last failure in this thread (file, line, key
/// where known). Empty string when nothing failed. Valid until the next call.
GF_API const char *gf_last_error(void);

/// Bytes currently held through granflow's allocator (0 when everything was freed).
GF_API size_t gf_bytes_allocated(void);

/// mkdir -p: creates `path` and its missing parents. GF_ERR_IO (naming the
/// directory) when one cannot be created or exists as something else.
GF_API gf_status gf_fs_mkdirs(const char *path);

/// Processor cores this process may run on (its affinity mask on Linux; else online; at least 1).
GF_API int gf_cpu_count(void);

/// Library version string, e.g. "0.1.0" (GF_VERSION_STRING of the build).
GF_API const char *gf_version(void);

// ---- hooks for embedding (as Box2D's b2SetAllocator / b2SetAssertFcn) -------

/// Returns a block of `size` bytes aligned to `alignment` (a power of two,
/// at least 64), or NULL. granflow zeroes the block itself.
typedef void *gf_alloc_fn(size_t size, size_t alignment);
/// Releases a block from the matching gf_alloc_fn; `size` is its requested size.
typedef void gf_free_fn(void *block, size_t size);

/// Routes granflow's own allocator (particle arrays, spots, grids, tables) to
/// `alloc`/`free`; NULL, NULL restores aligned_alloc/free. Set it before the
/// first granflow call that allocates and keep it while any granflow object
/// lives (a block must be freed by the allocator that made it). Not thread-safe.
/// Not routed: Voro++'s `new` and jansson's parser (summary.json), whose
/// allocator hook is process-wide; both free all they take before returning.
GF_API void gf_set_allocator(gf_alloc_fn *alloc, gf_free_fn *free);

/// Called when an internal consistency check fails (a bug in granflow or a
/// misuse of its API, never bad input; compiled into every build).
/// Return non-zero to abort (the default does: prints the condition, aborts),
/// zero to continue.
typedef int gf_assert_fn(const char *condition, const char *file, int line);

/// Installs the assertion hook; NULL restores the default. Not thread-safe.
GF_API void gf_set_assert_fn(gf_assert_fn *fn);

/// Receives each warning the library raises (a measurement skipped, a tool
/// missing): the calling thread, the message without a trailing newline.
typedef void gf_warning_fn(void *ctx, const char *message);

/// Installs a process-wide warning callback (NULL: none). Whether or not one
/// is installed, warnings are also kept per thread for gf_warning(); the
/// library itself never prints them. Not thread-safe.
GF_API void gf_set_warning_fn(gf_warning_fn *fn, void *ctx);

/// Number of warnings kept in this thread since the last gf_warnings_clear():
/// at most GF_WARNINGS_KEPT, the newest (older ones are dropped).
GF_API size_t gf_warning_count(void);

/// Warning `i` (0 = oldest kept) of this thread, or NULL when out of range.
/// Valid until the next warning or gf_warnings_clear() in this thread.
GF_API const char *gf_warning(size_t i);

/// Forgets this thread's warnings.
GF_API void gf_warnings_clear(void);

/// How many warning messages each thread keeps.
#define GF_WARNINGS_KEPT 32

#ifdef __cplusplus
}
#endif
#endif
