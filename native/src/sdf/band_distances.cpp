// SPDX-License-Identifier: GPL-3.0-or-later
#include "sdf/band_distances.h"

#include <algorithm>
#include <cmath>

#include "sdf/point_triangle.h"

// Built twice on x86-64, for AVX2 and for the baseline, the one the processor runs chosen at
// load time: the row loops run four doubles wide instead of two.
// No FMA: both give the same bits.
#if defined(__x86_64__) && defined(__has_attribute)
#if __has_attribute(target_clones)
#define HYVOX_SDF_CLONES __attribute__((target_clones("avx2", "default")))
#endif
#endif
#ifndef HYVOX_SDF_CLONES
#define HYVOX_SDF_CLONES
#endif

namespace hyvox::sdf {
namespace {

constexpr int kSide = BlockLayout::kSide;

// One triangle against the rows of a block.
struct Sweep {
    const DistanceTriangle& t;
    double band;
    double reach2;          // (radius + band)²: rows farther from the centre in xy miss its sphere
    double hx, hy, hz, h0;  // the height above the plane: hx x + hy y + hz z + h0
    double inverse_hz;      // 1 / hz (0 for a plane parallel to z)

    Sweep(const DistanceTriangle& triangle, double band_voxels) : t(triangle), band(band_voxels) {
        reach2 = (t.radius + band) * (t.radius + band);
        const Vec3& n = t.h_axis;
        const Vec3& c = t.corner[0];
        hx = n[0], hy = n[1], hz = n[2];
        inverse_hz = hz != 0 ? 1 / hz : 0;
        h0 = -(n[0] * c[0] + n[1] * c[1] + n[2] * c[2]);
    }

    // Narrows [k_lo, k_hi] of row (x, y) to the voxels whose centres lie in the slab of
    // half-width band around the triangle's plane (a stretch of 2 band / |hz| along the row),
    // solved for rather than tested voxel by voxel; false when the row misses the slab or the
    // bounding sphere grown by the band.
    bool narrow(double x, double y, int& k_lo, int& k_hi) const {
        const double dx = x - t.centre[0], dy = y - t.centre[1];
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

}  // namespace

HYVOX_SDF_CLONES
std::uint64_t blockDistances(const ValidatedMesh& mesh, const GridSpec& grid, double band, const BandBins& bins,
                             std::size_t number, double* d2, std::uint64_t& evaluations) {
    std::fill(d2, d2 + kBlockVoxels, band * band);
    std::uint64_t touched = 0;
    const std::array<std::int32_t, 3> block = BlockLayout(grid).at(bins.blocks[number]);
    const int x0 = kSide * block[0], y0 = kSide * block[1], z0 = kSide * block[2];
    for (std::uint64_t p = bins.start[number]; p < bins.start[number + 1]; ++p) {
        const auto corners = voxelCorners(mesh, grid, bins.triangles[p]);
        std::array<std::int32_t, 3> lo, hi;
        if (!reachOf(corners, grid, band, lo, hi)) continue;
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::max(lo[a], kSide * block[a]);
            hi[a] = std::min(hi[a], kSide * block[a] + kSide - 1);
        }
        if (lo[0] > hi[0] || lo[1] > hi[1] || lo[2] > hi[2]) continue;
        const DistanceTriangle t(corners);
        const Sweep sweep(t, band);
        for (int i = lo[0]; i <= hi[0]; ++i)
            for (int j = lo[1]; j <= hi[1]; ++j) {
                const double x = i + 0.5, y = j + 0.5;
                int k_lo = lo[2], k_hi = hi[2];
                if (!sweep.narrow(x, y, k_lo, k_hi)) continue;
                // Whole quads of the block's row: the loop then runs whole vectors, never a
                // scalar remainder. The voxels it adds get their true distance to this triangle
                // too (a voxel's value is the least over any triangles that include its
                // nearest); those past the grid's end are left out of the leaves.
                k_lo = z0 + ((k_lo - z0) & ~3);
                k_hi = z0 + ((k_hi - z0) | 3);
                const int quads = (k_hi - k_lo + 1) / 4;  // 4 * quads: the compiler sees no remainder
                t.minDistance2Along(x, y, k_lo + 0.5, 4 * quads, d2 + blockOffset(i - x0, j - y0, k_lo - z0));
                evaluations += std::uint64_t(4 * quads);
                for (int bz = (k_lo - z0) >> 3; bz <= (k_hi - z0) >> 3; ++bz)
                    touched |= std::uint64_t(1) << brickBit((i - x0) >> 3, (j - y0) >> 3, bz);
            }
    }
    return touched;
}

}  // namespace hyvox::sdf
