// SPDX-License-Identifier: GPL-3.0-or-later
#include "sdf/band_distances.h"

#include <algorithm>
#include <cmath>

#include "sdf/point_triangle.h"

namespace hyvox::sdf {
namespace {

constexpr int kSide = BlockLayout::kSide;

// One triangle against the rows of a block.
struct Sweep {
    const DistanceTriangle& t;
    double band;
    Vec3 centre;            // of a sphere holding the triangle: its centroid
    double reach2;          // (radius + band)²: rows farther from the centre in xy miss its sphere
    double hx, hy, hz, h0;  // the height above the plane: hx x + hy y + hz z + h0
    double inverse_hz;      // 1 / hz (0 for a plane parallel to z)

    Sweep(const DistanceTriangle& triangle, double band_voxels) : t(triangle), band(band_voxels) {
        // The sphere's radius: the farthest corner, a rounding more (it still holds the corners).
        centre = centroidOf(t.corner);
        double radius2 = 0;
        for (const Vec3& c : t.corner) radius2 = std::max(radius2, dot(minus(c, centre), minus(c, centre)));
        const double radius = std::sqrt(radius2) * (1.0 + 1e-12);
        reach2 = (radius + band) * (radius + band);
        const Vec3& n = t.h_axis;
        const Vec3& c = t.corner[0];
        hx = n[0], hy = n[1], hz = n[2];
        inverse_hz = hz != 0 ? 1 / hz : 0;
        h0 = -(n[0] * c[0] + n[1] * c[1] + n[2] * c[2]);
    }

    // Narrows [k_lo, k_hi] of row (x, y) to the voxels whose centres lie in the slab of
    // half-width band around the triangle's plane (a stretch of 2 band / |hz| along the row),
    // solved for rather than tested voxel by voxel; false when the row misses the slab or the
    // bounding sphere grown by the band. (Cutting the row further was slower: to the chord
    // through that sphere, as its square root costs more than the voxels it saves; to the
    // triangle's span along its longest edge and across it, as the cut costs more than the few
    // distances it spares: docs/why/sdf.md.)
    bool narrow(double x, double y, int& k_lo, int& k_hi) const {
        const double dx = x - centre[0], dy = y - centre[1];
        if (dx * dx + dy * dy >= reach2) return false;
        const double height_xy = hx * x + hy * y + h0;
        if (hz == 0) return std::fabs(height_xy) < band;
        const double a = (-band - height_xy) * inverse_hz, b = (band - height_xy) * inverse_hz;
        // Centres k + 0.5 in [min(a, b), max(a, b)], a rounding's width more on each side.
        constexpr double kSlack = 1e-9;
        const double first = std::ceil(std::min(a, b) - 0.5 - kSlack);
        const double last = std::floor(std::max(a, b) - 0.5 + kSlack);
        if (first > double(k_lo)) k_lo = first > double(k_hi) ? k_hi + 1 : int(first);
        if (last < double(k_hi)) k_hi = last < double(k_lo) ? k_lo - 1 : int(last);
        return k_lo <= k_hi;
    }
};

// Sweeps triangle `corners` over the rows of block `block` (in blocks) within its band.
HYVOX_AVX2_CLONES_GCC
std::uint64_t sweep(const std::array<Vec3, 3>& corners, const GridSpec& grid, double band,
                    const std::array<std::int32_t, 3>& block, double* d2, std::uint64_t& evaluations) {
    const int x0 = kSide * block[0], y0 = kSide * block[1], z0 = kSide * block[2];
    std::array<std::int32_t, 3> lo, hi;
    if (!reachOf(corners, grid, band, lo, hi)) return 0;
    for (int a = 0; a < 3; ++a) {
        lo[a] = std::max(lo[a], kSide * block[a]);
        hi[a] = std::min(hi[a], kSide * block[a] + kSide - 1);
    }
    if (lo[0] > hi[0] || lo[1] > hi[1] || lo[2] > hi[2]) return 0;
    const DistanceTriangle t(corners);
    const Sweep row_sweep(t, band);
    std::uint64_t touched = 0;
    for (int i = lo[0]; i <= hi[0]; ++i)
        for (int j = lo[1]; j <= hi[1]; ++j) {
            const double x = i + 0.5, y = j + 0.5;
            int k_lo = lo[2], k_hi = hi[2];
            if (!row_sweep.narrow(x, y, k_lo, k_hi)) continue;
            // Whole quads from the stretch's start (moved back where they would leave the
            // block's row): the loop then runs whole vectors, never a scalar remainder. The
            // voxels it adds get their true distance to this triangle too (a voxel's value is
            // the least over any triangles that include its nearest); those past the grid's end
            // are left out of the leaves.
            const int quads = (k_hi - k_lo + 4) / 4;        // 4 * quads: the compiler sees no remainder
            k_lo = std::min(k_lo, z0 + kSide - 4 * quads);  // kept within the block's row
            k_hi = k_lo + 4 * quads - 1;
            t.minDistance2Along(x, y, k_lo + 0.5, 4 * quads, d2 + blockOffset(i - x0, j - y0, k_lo - z0));
            evaluations += std::uint64_t(4 * quads);
            for (int bz = (k_lo - z0) >> 3; bz <= (k_hi - z0) >> 3; ++bz)
                touched |= std::uint64_t(1) << brickBit((i - x0) >> 3, (j - y0) >> 3, bz);
        }
    return touched;
}

}  // namespace

std::uint64_t blockDistances(const ValidatedMesh& mesh, const GridSpec& grid, double band, const BandBins& bins,
                             std::size_t number, double* d2, std::uint64_t& evaluations, BlockQueries* queries,
                             double queried_from) {
    std::fill(d2, d2 + kBlockVoxels, band * band);
    const std::array<std::int32_t, 3> block = BlockLayout(grid).at(bins.blocks[number]);
    const std::uint64_t first = bins.start[number], end = bins.start[number + 1];
    std::uint64_t touched = 0;
    if (queries && BlockQueries::fits(band)) {
        const std::array<std::int32_t, 3> origin{kSide * block[0], kSide * block[1], kSide * block[2]};
        queries->begin(origin, band);
        for (std::uint64_t p = first; p < end; ++p) queries->add(voxelCorners(mesh, grid, bins.triangles[p]));
        const bool queried = queries->placedTriangles() > 0 &&
            double(queries->placedTriangles()) >= queried_from * double(queries->occupiedCells());
        for (std::size_t n = 0; n < queries->triangles(); ++n)
            if (!queried || !queries->take(n))
                touched |= sweep(queries->corners(n), grid, band, block, d2, evaluations);
        if (!queried) return touched;
        queries->markReached({grid.dims[0] - origin[0], grid.dims[1] - origin[1]});
        return touched | queries->lower(d2, evaluations);
    }
    for (std::uint64_t p = first; p < end; ++p)
        touched |= sweep(voxelCorners(mesh, grid, bins.triangles[p]), grid, band, block, d2, evaluations);
    return touched;
}

}  // namespace hyvox::sdf
