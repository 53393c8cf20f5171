// SPDX-License-Identifier: MIT
// Fuzz target: a packing file read as .csv (see fuzz_packing.h).
#include <stdio.h>

#include "fuzz_packing.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) { return gf_fuzz_packing(".csv", 0, data, size); }
