// SPDX-License-Identifier: MIT
// Internal: the analysis options as a key table of config/keys.h (the tests
// walk it as they walk gf_config's).
#ifndef GF_ANALYSIS_OPTIONS_H
#define GF_ANALYSIS_OPTIONS_H

#include "config/keys.h"

/// Every analysis option, grouped by section, over gf_analysis_opts.
extern const gf_key_table gf_analysis_keys;

#endif
