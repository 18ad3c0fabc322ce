// SPDX-License-Identifier: GPL-3.0-or-later
#include "tile_plan.h"

#include <algorithm>
#include <cmath>

#include "core/clamp_coord.h"
#include "hyvox/region.h"

namespace hyvox::tiling {
namespace {

constexpr std::uint64_t kMaxAutoTileBytes = 256ull << 20;

std::int32_t roundUpToBrick(std::int64_t voxels) {
    const std::int64_t side = BrickLayout::kSide;
    return std::int32_t(std::max<std::int64_t>(side, (voxels + side - 1) / side * side));
}

std::uint64_t denseBytes(const std::array<std::int32_t, 3>& dims) {
    return std::uint64_t(BrickLayout::over(dims).total()) * BitGrid::kWordsPerBrick * sizeof(std::uint64_t);
}

}  // namespace

Tile TilePlan::tile(std::size_t index) const {
    const std::size_t tz = index % std::size_t(counts[2]);
    const std::size_t ty = (index / std::size_t(counts[2])) % std::size_t(counts[1]);
    const std::size_t tx = index / (std::size_t(counts[2]) * std::size_t(counts[1]));
    const std::size_t at[3] = {tx, ty, tz};
    Tile tile;
    for (int a = 0; a < 3; ++a) {
        tile.offset[a] = lo[a] + std::int32_t(at[a]) * side[a];
        tile.dims[a] = std::min(side[a], hi[a] - tile.offset[a]);
    }
    return tile;
}

std::uint64_t TilePlan::tileBytes() const { return denseBytes(side); }

TilePlan planTiles(const GridSpec& grid, const VoxelizeOptions& options, std::uint64_t device_limit) {
    TilePlan plan;
    const RegionBox box = regionBox(grid, options.region);
    plan.lo = box.lo;
    plan.hi = box.hi;
    plan.region = !options.region.whole();
    const std::array<std::int32_t, 3> dims = plan.boxDims();
    std::int32_t side = 0;
    {
        if (options.tile_size > 0) {
            side = roundUpToBrick(options.tile_size);
        } else {
            std::uint64_t limit = std::min(kMaxAutoTileBytes, options.memoryBudgetBytes() / 4);
            if (device_limit > 0) limit = std::min(limit, device_limit);
            if (denseBytes(dims) > limit) {
                // The largest cube of whole bricks whose bits fit the limit (side³ / 8 bytes).
                const double voxels = std::cbrt(double(limit) * 8.0);
                side = std::max<std::int32_t>(BrickLayout::kSide,
                                              std::int32_t(voxels) / BrickLayout::kSide * BrickLayout::kSide);
            }
        }
    }
    for (int a = 0; a < 3; ++a) {
        plan.side[a] = side > 0 && side < dims[a] ? side : dims[a];
        plan.counts[a] = (dims[a] + plan.side[a] - 1) / plan.side[a];
    }
    return plan;
}

PointReach pointReach(const GridSpec& grid, const VoxelizeOptions& options) {
    PointReach reach;
    if (options.method != Method::Tessellation) return reach;
    const TessellationOptions& tess = options.tessellation;
    // PN-triangle patches bulge well under half their size (the patch planner's bound).
    if (tess.pn_triangles) reach.relative = 0.5;
    double height = 0;  // the largest |height - midlevel| the map holds (a file was read into its pixels)
    if (!tess.displacement_pixels.empty()) {
        const auto [low, high] =
            std::minmax_element(tess.displacement_pixels.values.begin(), tess.displacement_pixels.values.end());
        height = std::max(std::fabs(*low - tess.displacement_midlevel), std::fabs(*high - tess.displacement_midlevel));
    }
    if (height > 0) reach.fixed = height * std::fabs(tess.displacement_strength) / grid.voxel_size + 1.0;
    return reach;
}

std::vector<std::vector<std::uint32_t>> binTriangles(const ValidatedMesh& mesh, const GridSpec& grid,
                                                     const TilePlan& plan, const PointReach& reach,
                                                     Interrupter* interrupter) {
    std::vector<std::vector<std::uint32_t>> bins(plan.total());
    for (std::size_t n = 0; n < mesh.usable.size(); ++n) {
        if (n % kInterruptCheckTriangles == 0) throwIfInterrupted(interrupter);
        const std::uint32_t t = mesh.usable[n];
        std::array<int, 3> first{}, last{};
        const std::array<std::array<double, 3>, 3> corners{
            grid.toVoxel(mesh.vertex(t, 0)), grid.toVoxel(mesh.vertex(t, 1)), grid.toVoxel(mesh.vertex(t, 2))};
        std::array<double, 3> lows{}, highs{};
        double extent = 0;
        for (int a = 0; a < 3; ++a) {
            lows[a] = clampCoord(std::min({corners[0][a], corners[1][a], corners[2][a]}));
            highs[a] = clampCoord(std::max({corners[0][a], corners[1][a], corners[2][a]}));
            extent = std::max(extent, highs[a] - lows[a]);
        }
        const double grow = std::min(reach.fixed + reach.relative * extent, 1.0e9);
        bool outside = false;
        for (int a = 0; a < 3; ++a) {
            const double lo = lows[a] - grow, hi = highs[a] + grow;
            const double v0 = std::max(double(plan.lo[a]), std::ceil(lo) - 1);
            const double v1 = std::min(double(plan.hi[a] - 1), std::floor(hi));
            if (v0 > v1) {
                outside = true;
                break;
            }
            first[a] = (int(v0) - plan.lo[a]) / plan.side[a];
            last[a] = (int(v1) - plan.lo[a]) / plan.side[a];
        }
        if (outside) continue;
        for (int x = first[0]; x <= last[0]; ++x)
            for (int y = first[1]; y <= last[1]; ++y)
                for (int z = first[2]; z <= last[2]; ++z)
                    bins[(std::size_t(x) * std::size_t(plan.counts[1]) + std::size_t(y)) * std::size_t(plan.counts[2]) +
                         std::size_t(z)]
                        .push_back(t);
    }
    return bins;
}

}  // namespace hyvox::tiling
