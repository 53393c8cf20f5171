// SPDX-License-Identifier: MIT
// Stops that stop (issue 26, item 5): the packing generator looks at the
// stop flag inside its passes over the particles, not only between
// relaxation sweeps (50,000,000 spheres took 43 s and 6.2 GB before their
// first sweep, and so before the first look), and refuses up front a count
// whose generation cannot fit in the memory the process may have.
#include "support.h"

#include <signal.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "core/alloc.h"
#include "granflow/granflow.h"

// An allocator hook that counts and, at the first block of `trigger_size`
// bytes, sets the stop flag as a signal would.
static volatile sig_atomic_t hook_stop;
static size_t hook_trigger_size, hook_calls_after;
static int hook_triggered;

static void *stop_alloc(size_t size, size_t alignment)
{
    if (hook_triggered) hook_calls_after++;
    if (!hook_triggered && size >= hook_trigger_size) {
        hook_triggered = 1;
        hook_stop = 1;
    }
    size_t rounded = (size + alignment - 1) & ~(alignment - 1);
    return aligned_alloc(alignment, rounded);
}

static void stop_free(void *block, size_t size)
{
    (void)size;
    free(block);
}

static gf_status generate_with_hook(size_t n, size_t trigger_size)
{
    gf_config c = gf_test_silo_config(20, (int64_t)n, 3);
    gf_packing pk = {0};
    hook_stop = 0;
    hook_trigger_size = trigger_size;
    hook_calls_after = 0;
    hook_triggered = 0;
    gf_set_allocator(stop_alloc, stop_free);
    gf_status st = gf_packing_generate(&c, &(gf_packing_opts){.stop = &hook_stop}, &pk);
    gf_set_allocator(NULL, NULL);
    assert_int_equal(pk.n, 0);
    return st;
}

// A flag already set: nothing is allocated at all (the generator used to
// allocate, place and sort every sphere before its first look).
static void generator_stopped_before_it_begins(void **state)
{
    (void)state;
    const size_t bytes0 = gf_bytes_allocated();
    gf_config c = gf_test_silo_config(20, 20000, 3);
    gf_packing pk = {0};
    hook_stop = 1;
    hook_trigger_size = 0;
    hook_calls_after = 0;
    hook_triggered = 1;
    gf_set_allocator(stop_alloc, stop_free);
    gf_status st = gf_packing_generate(&c, &(gf_packing_opts){.stop = &hook_stop}, &pk);
    gf_set_allocator(NULL, NULL);
    assert_int_equal(st, GF_ERR_INTERRUPTED);
    assert_non_null(strstr(gf_last_error(), "packing: interrupted before it began"));
    assert_int_equal(hook_calls_after, 0);
    assert_int_equal(gf_bytes_allocated(), bytes0);
}

// The flag set while the generator's arrays are allocated (the neighbour
// list, 8 slots of 4 bytes per sphere, is the last and largest of them):
// it stops while placing the spheres, before the cell grid and the
// neighbour list are built, and allocates nothing more.
static void generator_looks_at_the_flag_inside_its_first_pass(void **state)
{
    (void)state;
    const size_t n = 20000, bytes0 = gf_bytes_allocated();
    assert_int_equal(generate_with_hook(n, 8 * n * sizeof(uint32_t)), GF_ERR_INTERRUPTED);
    assert_non_null(strstr(gf_last_error(), "packing: interrupted before the first relaxation sweep"));
    assert_int_equal(hook_calls_after, 0);
    assert_int_equal(gf_bytes_allocated(), bytes0);
}

// More spheres than the memory the process may have: refused before any
// allocation, with what it needs and what it has.
static void generator_refuses_what_cannot_fit(void **state)
{
    (void)state;
    gf_config c = gf_test_silo_config(12, 200, 3);
    c.container_width = c.container_depth = 2000; // at the generator's footprint limit
    c.packing_particles = 90000000;                // 9e7 spheres: ~18 GB
    gf_packing pk = {0};
    struct rlimit old;
    assert_int_equal(getrlimit(RLIMIT_DATA, &old), 0);
    struct rlimit small = {(rlim_t)1 << 30, old.rlim_max}; // 1 GB of data
    if (old.rlim_max != RLIM_INFINITY && old.rlim_max < small.rlim_cur) small.rlim_cur = old.rlim_max;
    assert_int_equal(setrlimit(RLIMIT_DATA, &small), 0);
    const size_t bytes0 = gf_bytes_allocated();
    gf_status st = gf_packing_generate(&c, NULL, &pk);
    assert_int_equal(setrlimit(RLIMIT_DATA, &old), 0);
    assert_int_equal(st, GF_ERR_NOMEM);
    assert_non_null(strstr(gf_last_error(), "packing: 90000000 particles need about 18.0 GB to generate"));
    assert_non_null(strstr(gf_last_error(), "(ulimit -d)"));
    assert_int_equal(gf_bytes_allocated(), bytes0);
}

// setrlimit(RLIMIT_DATA) would starve the sanitizers' own mappings.
// ctest: nosan-case generator_refuses_what_cannot_fit
static const struct CMUnitTest tests[] = {
    cmocka_unit_test(generator_stopped_before_it_begins),
    cmocka_unit_test(generator_looks_at_the_flag_inside_its_first_pass),
    cmocka_unit_test(generator_refuses_what_cannot_fit),
};

GF_TEST_MAIN("stops", tests)
