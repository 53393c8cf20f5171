// SPDX-License-Identifier: MIT
// Internal: the record in a gf_config of where each key got its value (a file
// and line, an origin such as "--set", or the default), and the wording of
// validation messages that quote it.
#ifndef GF_CONFIG_WHERE_H
#define GF_CONFIG_WHERE_H

#include <stddef.h>

#include "config/keys.h"
#include "granflow/config.h"

/// Records that key `k` of gf_config_keys was set by `origin` (a file's path
/// or "--set"), at `line` of it (0: no line).
void gf_config_mark(gf_config *cfg, const gf_key *k, const char *origin, int line);

/// Where key `k` got its value: "FILE:LINE", "--set", "default".
void gf_config_where_of(const gf_config *cfg, const gf_key *k, char *buf, size_t n);

// gf_config_same_origin and gf_config_msg_make are public (granflow/config.h):
// the shapes (geom/) word their own checks' messages with them.

#endif
