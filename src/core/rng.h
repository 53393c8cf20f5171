// SPDX-License-Identifier: MIT
// Internal: xoshiro256** random numbers, seeded through splitmix64. The state
// is four words so a checkpoint can store it and a run resumes exactly.
#ifndef GF_CORE_RNG_H
#define GF_CORE_RNG_H

#include <math.h>
#include <stdint.h>

typedef struct gf_rng {
    uint64_t s[4];
} gf_rng;

/// Seeds the generator; `stream` separates independent uses of one seed.
void gf_rng_seed(gf_rng *rng, uint64_t seed, uint64_t stream);

static inline uint64_t gf_rng_rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

/// Next 64 random bits.
static inline uint64_t gf_rng_next(gf_rng *r)
{
    uint64_t *s = r->s;
    uint64_t result = gf_rng_rotl(s[1] * 5, 7) * 9;
    uint64_t t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = gf_rng_rotl(s[3], 45);
    return result;
}

/// Uniform double in [0, 1) with 53 random bits.
static inline double gf_rng_uniform(gf_rng *r) { return (double)(gf_rng_next(r) >> 11) * 0x1.0p-53; }

/// Uniform double in (0, 1]: safe to take the log of.
static inline double gf_rng_uniform_pos(gf_rng *r) { return 1.0 - gf_rng_uniform(r); }

/// Uniform integer in [0, n), n > 0 (Lemire's multiply-shift, bias < 2^-64 n).
static inline uint64_t gf_rng_below(gf_rng *r, uint64_t n)
{
    __extension__ typedef unsigned __int128 gf_u128;
    return (uint64_t)(((gf_u128)gf_rng_next(r) * n) >> 64);
}

/// Exponential waiting time with the given rate (> 0).
static inline double gf_rng_exp(gf_rng *r, double rate) { return -log(gf_rng_uniform_pos(r)) / rate; }

/// Poisson-distributed count with mean `mean` (>= 0); inversion for small
/// means, normal approximation rounded above 500.
uint64_t gf_rng_poisson(gf_rng *r, double mean);

#endif
