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
    double reach2;                 // (radius + band)²: rows farther from the centre in xy miss its sphere
    double radius2, four_radius2;  // the bounding sphere's radius², 4 radius²
    double hx, hy, hz, h0;         // the height above the plane: hx x + hy y + hz z + h0

    Sweep(const DistanceTriangle& triangle, double band) : t(triangle) {
        reach2 = (t.radius + band) * (t.radius + band);
        radius2 = t.radius * t.radius;
        four_radius2 = 4 * radius2;
        const Vec3& n = t.h_axis;
        const Vec3& c = t.corner[0];
        hx = n[0], hy = n[1], hz = n[2];
        h0 = -(n[0] * c[0] + n[1] * c[1] + n[2] * c[2]);
    }

    // Narrows [k_lo, k_hi] of row (x, y), whose voxels' best squared distances so far are
    // row[k - z0], to the voxels the triangle may lower: those with its plane nearer than their
    // best (|height| < s, s² = best) and its bounding sphere too (|p - c| - r < s, tested
    // without a root: false exactly when a = |p - c|² - r² - s² >= 0 and a² >= 4 r² s²). The
    // sphere grown by the band bounds the whole row first. False when none is left.
    bool narrow(double x, double y, const double* row, int z0, int& k_lo, int& k_hi) const {
        const double dx = x - t.centre[0], dy = y - t.centre[1], dxy2 = dx * dx + dy * dy;
        if (dxy2 >= reach2) return false;
        const double height_xy = hx * x + hy * y + h0;
        double lower[kSide];
        const int count = k_hi - k_lo + 1;
        const double* best = row + (k_lo - z0);
        const double z_first = double(k_lo) + 0.5, dz_first = z_first - t.centre[2];
        for (int m = 0; m < count; ++m) {
            const double dz = dz_first + m, s2 = best[m];
            const double a = dxy2 + dz * dz - radius2 - s2;
            const double height = height_xy + hz * (z_first + m);
            const bool in_sphere = (a < 0) | (a * a < four_radius2 * s2);
            lower[m] = (in_sphere & (height * height < s2)) ? 1.0 : 0.0;
        }
        int from = 0, to = count - 1;
        while (from <= to && lower[from] == 0) ++from;
        while (to >= from && lower[to] == 0) --to;
        if (from > to) return false;
        k_hi = k_lo + to;
        k_lo += from;
        return true;
    }
};

}  // namespace

HYVOX_SDF_CLONES
void blockDistances(const ValidatedMesh& mesh, const GridSpec& grid, double band, const BandBins& bins,
                    std::size_t number, double* d2, std::uint64_t& evaluations) {
    std::fill(d2, d2 + kBlockVoxels, band * band);
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
                double* row = d2 + blockOffset(i - x0, j - y0, 0);
                if (!sweep.narrow(x, y, row, z0, k_lo, k_hi)) continue;
                t.minDistance2Along(x, y, k_lo + 0.5, k_hi - k_lo + 1, row + (k_lo - z0));
                evaluations += std::uint64_t(k_hi - k_lo + 1);
            }
    }
}

}  // namespace hyvox::sdf
