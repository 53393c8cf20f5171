// SPDX-License-Identifier: MIT
#include "core/rng.h"

static uint64_t gf_splitmix64(uint64_t *x)
{
    uint64_t z = (*x += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

void gf_rng_seed(gf_rng *rng, uint64_t seed, uint64_t stream)
{
    uint64_t x = seed ^ (stream * 0xD1B54A32D192ED03ull);
    for (int i = 0; i < 4; i++) rng->s[i] = gf_splitmix64(&x);
}

uint64_t gf_rng_poisson(gf_rng *r, double mean)
{
    if (mean <= 0.0) return 0;
    if (mean > 500.0) {
        // Box-Muller normal approximation; the fixed-step driver never gets here
        // with the papers' rates (lambda/mu ~ 13).
        double u1 = gf_rng_uniform_pos(r), u2 = gf_rng_uniform(r);
        double z = sqrt(-2.0 * log(u1)) * cos(2.0 * 3.14159265358979323846 * u2);
        double k = floor(mean + sqrt(mean) * z + 0.5);
        if (!(k < 0x1p63)) return UINT64_C(1) << 63; // (a cast out of range is undefined)
        return k < 0 ? 0 : (uint64_t)k;
    }
    double limit = exp(-mean), p = gf_rng_uniform(r);
    uint64_t k = 0;
    double term = limit, cdf = limit;
    while (p > cdf) {
        k++;
        term *= mean / (double)k;
        cdf += term;
        if (term < 1e-300) break;
    }
    return k;
}
