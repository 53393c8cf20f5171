// SPDX-License-Identifier: MIT
// granflow core: export macro, status codes, last-error text, allocation accounting.
#ifndef GRANFLOW_CORE_H
#define GRANFLOW_CORE_H

#include <stddef.h>
#include <stdint.h>

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
} gf_status;

/// Short fixed name of a status ("ok", "invalid parameter", ...). Never NULL.
GF_API const char *gf_status_str(gf_status status);

/// Human-readable message of the last failure in this thread (file, line, key
/// where known). Empty string when nothing failed. Valid until the next call.
GF_API const char *gf_last_error(void);

/// Bytes currently held through granflow's allocator (0 when everything was freed).
GF_API size_t gf_bytes_allocated(void);

/// Library version string, e.g. "0.1.0".
GF_API const char *gf_version(void);

#ifdef __cplusplus
}
#endif
#endif
