// SPDX-License-Identifier: GPL-3.0-or-later
#include "tessellation/patch_plan.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>

#include "hyvox/errors.h"
#include "tessellation/tess_factors.h"

namespace hyvox::tessellation {

PatchPlan planPatches(const ValidatedMesh& mesh, const GridSpec& grid, const std::array<std::int32_t, 3>& tile_offset,
                      const std::array<std::int32_t, 3>& tile_dims, double gamma, int max_level, bool estimate_bricks,
                      double reach, double pn_reach) {
    const BrickLayout bricks = BrickLayout::over(tile_dims);
    std::vector<std::uint8_t> reached(estimate_bricks ? bricks.total() : 0, 0);
    std::atomic<std::uint64_t> large_estimate{0};
    std::atomic<std::uint64_t> points_estimate{0};
    std::vector<std::uint32_t> pieces(mesh.usable.size());  // 0 = whole, 1 = one patch, n = n² patches

    // Per triangle, in parallel: its split count and the bricks its points can reach.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.usable.size(), 4096), [&](const auto& range) {
        for (std::size_t u = range.begin(); u != range.end(); ++u) {
            Vec3f p[3];
            std::array<double, 3> d[3];
            for (int c = 0; c < 3; ++c) {
                d[c] = grid.toVoxel(mesh.vertex(mesh.usable[u], c));
                for (int a = 0; a < 3; ++a) p[c][a] = float(d[c][a]);
            }
            const PatchFactors factors = patchFactors(p[0], p[1], p[2], gamma);
            pieces[u] = factors.largest() <= 1.0 ? 0u : std::uint32_t(presplitPieces(factors, max_level));
            // A patch at level L makes about L² micro-triangles (pre-split or not).
            const double level = std::max(1.0, factors.largest());
            points_estimate.fetch_add(std::uint64_t(std::min(level * level, 1.0e15)), std::memory_order_relaxed);
            if (!estimate_bricks) continue;
            const double grow = reach + pn_reach * factors.largest() / gamma;
            std::array<int, 3> lo{}, hi{};
            std::uint64_t box = 1;
            for (int a = 0; a < 3; ++a) {
                const double mn = std::min({d[0][a], d[1][a], d[2][a]}) - grow - tile_offset[a];
                const double mx = std::max({d[0][a], d[1][a], d[2][a]}) + grow - tile_offset[a];
                const double last = double(bricks.counts[a] - 1);
                lo[a] = int(std::clamp(std::floor(mn / BrickLayout::kSide), 0.0, last));
                hi[a] = int(std::clamp(std::floor(mx / BrickLayout::kSide), 0.0, last));
                box *= std::uint64_t(hi[a] - lo[a] + 1);
            }
            if (box <= 27) {
                for (int x = lo[0]; x <= hi[0]; ++x)
                    for (int y = lo[1]; y <= hi[1]; ++y)
                        for (int z = lo[2]; z <= hi[2]; ++z)
                            __atomic_store_n(&reached[bricks.index(x, y, z)], 1, __ATOMIC_RELAXED);
            } else {
                // A plane crosses a brick over at least ~64 voxel units²: 3× that covers
                // obliques and the bricks the triangle only grazes along its boundary.
                const double e1[3] = {d[1][0] - d[0][0], d[1][1] - d[0][1], d[1][2] - d[0][2]};
                const double e2[3] = {d[2][0] - d[0][0], d[2][1] - d[0][1], d[2][2] - d[0][2]};
                const double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2],
                             cz = e1[0] * e2[1] - e1[1] * e2[0];
                const double area = 0.5 * std::sqrt(cx * cx + cy * cy + cz * cz);
                large_estimate += std::uint64_t(3.0 * (area + grow * std::sqrt(area)) / 64.0) + 27;
            }
        }
    });

    PatchPlan plan;
    plan.points_estimate = points_estimate.load();
    // The points are counted in 32-bit GPU counters, and a run of billions of points takes
    // hours on a software device: refused before any work, with the reason.
    if (plan.points_estimate > kMaxPoints)
        throw ResourceError("the tessellation would make about " + std::to_string(plan.points_estimate) +
                            " points, more than the " + std::to_string(kMaxPoints) +
                            " its counters hold; lower tess_gamma or the resolution");
    plan.brick_estimate = large_estimate + std::uint64_t(std::count(reached.begin(), reached.end(), 1));
    const std::size_t whole = std::size_t(std::count(pieces.begin(), pieces.end(), 0u));
    plan.whole.reserve(whole);
    plan.direct.reserve(mesh.usable.size() - whole);
    for (std::size_t u = 0; u < pieces.size(); ++u) {
        const std::uint64_t n = pieces[u];
        if (n == 0) {
            plan.whole.push_back(std::uint32_t(u));
            continue;
        }
        if (n == 1) {
            plan.direct.push_back(std::uint32_t(u));
            continue;
        }
        if (plan.split_patches + n * n > (1ull << 31))
            throw ResourceError(
                "the tessellation pre-split would need more than 2^31 patches; lower gamma or the resolution");
        plan.splits.insert(plan.splits.end(),
                           {std::uint32_t(u), std::uint32_t(n), std::uint32_t(plan.split_patches), 0u});
        plan.split_patches += n * n;
        plan.largest_split = std::max(plan.largest_split, std::uint32_t(n));
    }
    return plan;
}

}  // namespace hyvox::tessellation
