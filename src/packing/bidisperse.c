// SPDX-License-Identifier: MIT
// Two particle sizes in a generated packing (issue 14: a pebble bed with
// pebbles of another size). The generator builds a dense packing of equal
// spheres of radius 0.5 (docs/packing.md); a random packing.fraction2 of
// them is then given the radius packing.radius2 <= 0.5. No pair can overlap
// (every centre is >= 0.99 from the others), and the centres keep the
// generator's density, so the grid and the neighbour lists hold them; the
// small ones sit loosely in their cages until the flow moves them. A second
// species larger than the first is imported instead (a `radius` or
// `diameter` column, docs/packing.md): growing spheres inside a dense packing
// needs a pour, which is the DEM's job (granflow dem).
#include "packing/bidisperse.h"

#include "core/error.h"
#include "core/rng.h"
#include "granflow/defs.h"

gf_status gf_packing_bidisperse(const gf_config *cfg, gf_packing *p)
{
    gf_packing_defs pd;
    gf_config_packing_defs(cfg, &pd);
    const double f = pd.fraction2, r2 = pd.radius2;
    if (!(f > 0.0)) return GF_OK;
    if (!(r2 > 0.0 && r2 <= 0.5))
        return gf_error_set(GF_ERR_PARAM, "packing.radius2 = %g: a generated second species must be no larger "
                                          "than the first (0.5); import a larger one", r2);
    gf_rng rng;
    gf_rng_seed(&rng, pd.seed, 0x4232u /* "B2": the second size */);
    for (size_t i = 0; i < p->n; i++)
        if (gf_rng_uniform(&rng) < f) p->r[i] = r2;
    return GF_OK;
}
