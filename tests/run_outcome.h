// SPDX-License-Identifier: MIT
// Tests: the outcome of a run of a silo (final particles, exits, counters, the
// parallel engines' profile), and a check that two are the same to the last
// bit: the parallel engines' results must not depend on threads or ranks
// (support.c; test_parallel.c, test_domains.c).
#ifndef GF_TESTS_RUN_OUTCOME_H
#define GF_TESTS_RUN_OUTCOME_H

#include "granflow/granflow.h"

typedef struct gf_test_outcome {
    gf_packing pk;
    gf_exit *ex;
    size_t nex;
    gf_sim_stats st;
    uint64_t shared_phases; ///< phases with two or more blocks (sectors) side by side
    gf_par_profile prof;
} gf_test_outcome;

/// The outcome of a sim as it is now.
gf_test_outcome gf_test_outcome_of(const gf_sim *sim);
/// Packs c's silo (gf_test_generated_sim) and runs it to c.run_duration.
gf_test_outcome gf_test_run_outcome(gf_config c);
/// Particles, exits and counters equal bit for bit (the floating-point sums too).
void gf_test_same_outcome(const gf_test_outcome *a, const gf_test_outcome *b);
void gf_test_outcome_free(gf_test_outcome *o);

#endif
