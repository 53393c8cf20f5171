// SPDX-License-Identifier: MIT
// Thin wrapper over Voro++ (Rycroft 2009, the library the papers used): cell volumes in a walled box.
#include "analysis/voronoi_cells.h"

#include <climits>
#include <cmath>
#include <new>
#include <voro++.hh>

extern "C" {
#include "core/error.h"
}

namespace {

// Points per block of Voro++'s grid. Its own guess (guess_optimal) is 5.6;
// 3 measured ~9% faster on the papers' 55,000-sphere packing (0.56 s vs 0.61 s).
constexpr double gf_voro_per_block = 3.0;
// Cap on blocks per axis, so a sparse box does not allocate a huge grid.
constexpr int gf_voro_max_blocks = 512;

bool gf_voro_inside(double v, double lo, double hi)
{
    // Voro++ drops points with v >= hi (block index == count); NaN fails both.
    return v >= lo && v < hi;
}

int gf_voro_blocks(double span, double inv_scale)
{
    double b = std::floor(span * inv_scale + 1.0);
    if (!(b >= 1.0)) return 1;
    return b > gf_voro_max_blocks ? gf_voro_max_blocks : static_cast<int>(b);
}

gf_status gf_voro_run(size_t n, const double *x, const double *y, const double *z, const double lo[3],
                      const double hi[3], double *vol, double *rad2)
{
    size_t inside = 0;
    for (size_t i = 0; i < n; i++) {
        vol[i] = NAN;
        if (rad2) rad2[i] = NAN;
        if (gf_voro_inside(x[i], lo[0], hi[0]) && gf_voro_inside(y[i], lo[1], hi[1]) &&
            gf_voro_inside(z[i], lo[2], hi[2]))
            inside++;
    }
    if (inside == 0) return GF_OK;
    const double sx = hi[0] - lo[0], sy = hi[1] - lo[1], sz = hi[2] - lo[2];
    double inv_scale = std::cbrt(static_cast<double>(inside) / (gf_voro_per_block * sx * sy * sz));
    voro::container con(lo[0], hi[0], lo[1], hi[1], lo[2], hi[2], gf_voro_blocks(sx, inv_scale),
                        gf_voro_blocks(sy, inv_scale), gf_voro_blocks(sz, inv_scale), false, false, false, 8);
    for (size_t i = 0; i < n; i++)
        if (gf_voro_inside(x[i], lo[0], hi[0]) && gf_voro_inside(y[i], lo[1], hi[1]) &&
            gf_voro_inside(z[i], lo[2], hi[2]))
            con.put(static_cast<int>(i), x[i], y[i], z[i]);
    voro::c_loop_all loop(con);
    voro::voronoicell cell;
    if (loop.start()) do {
            if (!con.compute_cell(cell, loop)) continue;
            size_t i = static_cast<size_t>(loop.pid());
            vol[i] = cell.volume();
            // Voro++ keeps cell vertices at twice their positions.
            if (rad2) rad2[i] = 0.25 * cell.max_radius_squared();
        } while (loop.inc());
    return GF_OK;
}

} // namespace

extern "C" gf_status gf_voro_cells(size_t n, const double *x, const double *y, const double *z, const double lo[3],
                                   const double hi[3], double *vol, double *rad2)
{
    for (int k = 0; k < 3; k++)
        if (!(hi[k] > lo[k]) || !std::isfinite(lo[k]) || !std::isfinite(hi[k]))
            return gf_error_set(GF_ERR_PARAM, "voronoi: degenerate box on axis %d: [%g, %g]", k, lo[k], hi[k]);
    if (n > static_cast<size_t>(INT_MAX))
        return gf_error_set(GF_ERR_PARAM, "voronoi: %zu points is more than Voro++'s int ids allow", n);
    try {
        return gf_voro_run(n, x, y, z, lo, hi, vol, rad2);
    } catch (const std::bad_alloc &) {
        return gf_error_set(GF_ERR_NOMEM, "voronoi: out of memory for %zu cells", n);
    } catch (...) {
        return gf_error_set(GF_ERR_STATE, "voronoi: Voro++ failed on %zu points", n);
    }
}
