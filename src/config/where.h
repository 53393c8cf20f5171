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

/// True when keys `a` and `b` ("section.name") were set by the same origin
/// (one file, or both by "--set"); false when either is at its default.
bool gf_config_same_origin(const gf_config *cfg, const char *a, const char *b);

/// The parts of a message about one or two keys: `lead` is "WHERE: " of the
/// first key not at its default (else ""), `key[i]` is "section.name = value"
/// followed by " (WHERE)" unless that is the lead's place.
typedef struct gf_config_msg {
    char lead[GF_PATH_MAX + 32];
    char key[2][GF_PATH_MAX + 128];
} gf_config_msg;

/// Fills `m` for keys `a` and `b` ("section.name"; `b` may be NULL).
void gf_config_msg_make(gf_config_msg *m, const gf_config *cfg, const char *a, const char *b);

#endif
