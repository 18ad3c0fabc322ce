// SPDX-License-Identifier: GPL-3.0-or-later
#include "attributes/tile_attributes.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "attributes/clip_to_voxel.h"

namespace hyvox::attributes {
namespace {

using Corners = std::array<Point, 3>;

struct VoxelRange {
    std::array<int, 3> lo, hi;  // inclusive
    bool empty() const { return lo[0] > hi[0] || lo[1] > hi[1] || lo[2] > hi[2]; }
};

// The voxels whose closed box may meet the triangle: a coordinate exactly on a voxel
// plane touches the voxels on both sides.
VoxelRange candidates(const Corners& c, const std::array<int, 3>& clip_lo, const std::array<int, 3>& clip_hi) {
    VoxelRange r;
    for (std::size_t a = 0; a < 3; ++a) {
        const double lo = std::min({c[0][a], c[1][a], c[2][a]}), hi = std::max({c[0][a], c[1][a], c[2][a]});
        // Clamped before the conversion so far-away geometry cannot overflow an int.
        const double lo_voxel = std::ceil(std::clamp(lo, -2.0, double(clip_hi[a]) + 2)) - 1;
        const double hi_voxel = std::floor(std::clamp(hi, -2.0, double(clip_hi[a]) + 2));
        r.lo[a] = std::max(int(lo_voxel), clip_lo[a]);
        r.hi[a] = std::min(int(hi_voxel), clip_hi[a]);
    }
    return r;
}

Corners voxelCorners(const BackendJob& job, std::uint32_t triangle) {
    return {job.grid.toVoxel(job.mesh.vertex(triangle, 0)), job.grid.toVoxel(job.mesh.vertex(triangle, 1)),
            job.grid.toVoxel(job.mesh.vertex(triangle, 2))};
}

}  // namespace

TileAttributeCounts computeTileAttributes(const BackendJob& job, const BitGrid& bits, const SurfaceValues& values,
                                          bool brute_force, std::vector<AttributeLeaf>& out) {
    const Tile& tile = job.tile;
    const BrickLayout& tile_bricks = bits.bricks();
    const BrickLayout grid_bricks = job.grid.bricks();
    const std::array<int, 3> tile_lo{tile.offset[0], tile.offset[1], tile.offset[2]};
    const std::array<int, 3> tile_hi{tile.last(0), tile.last(1), tile.last(2)};
    const auto& usable = job.mesh.usable;

    // The tile's non-empty bricks, and (unless brute force) the triangles that may reach each.
    std::vector<std::size_t> occupied;
    std::vector<std::int64_t> slot_of_brick(tile_bricks.total(), -1);
    for (std::size_t b = 0; b < tile_bricks.total(); ++b) {
        const std::uint64_t* words = bits.data() + b * BitGrid::kWordsPerBrick;
        if (std::any_of(words, words + BitGrid::kWordsPerBrick, [](std::uint64_t w) { return w != 0; })) {
            slot_of_brick[b] = std::int64_t(occupied.size());
            occupied.push_back(b);
        }
    }
    std::vector<std::vector<std::uint32_t>> binned(brute_force ? 0 : occupied.size());
    if (!brute_force)
        for (std::uint32_t n = 0; n < usable.size(); ++n) {
            const VoxelRange r = candidates(voxelCorners(job, usable[n]), tile_lo, tile_hi);
            if (r.empty()) continue;
            for (int bx = (r.lo[0] - tile_lo[0]) >> 3; bx <= (r.hi[0] - tile_lo[0]) >> 3; ++bx)
                for (int by = (r.lo[1] - tile_lo[1]) >> 3; by <= (r.hi[1] - tile_lo[1]) >> 3; ++by)
                    for (int bz = (r.lo[2] - tile_lo[2]) >> 3; bz <= (r.hi[2] - tile_lo[2]) >> 3; ++bz) {
                        const std::int64_t slot = slot_of_brick[tile_bricks.index(bx, by, bz)];
                        if (slot >= 0) binned[std::size_t(slot)].push_back(n);
                    }
        }

    const int channels = values.channels();
    const std::size_t first = out.size();
    out.resize(first + occupied.size());
    std::atomic<std::uint64_t> pieces{0}, unreached{0}, rounded{0};
    const int threads = job.options.threads > 0 ? job.options.threads : tbb::task_arena::automatic;
    tbb::task_arena arena(threads);
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, occupied.size(), 4), [&](const auto& range) {
            throwIfInterrupted(job.interrupter);
            // Per voxel of the leaf: channels sums, then the weight.
            std::vector<double> sums(512 * std::size_t(channels + 1));
            double value[kMaxChannels];
            std::uint64_t local_pieces = 0;
            for (std::size_t s = range.begin(); s != range.end(); ++s) {
                const std::size_t b = occupied[s];
                const std::uint64_t* words = bits.data() + b * BitGrid::kWordsPerBrick;
                const std::array<std::int32_t, 3> at = tile_bricks.at(b);
                const std::array<int, 3> leaf_lo{tile_lo[0] + 8 * at[0], tile_lo[1] + 8 * at[1], tile_lo[2] + 8 * at[2]};
                const std::array<int, 3> leaf_hi{std::min(leaf_lo[0] + 7, tile_hi[0]), std::min(leaf_lo[1] + 7, tile_hi[1]),
                                                 std::min(leaf_lo[2] + 7, tile_hi[2])};
                std::fill(sums.begin(), sums.end(), 0.0);
                auto add = [&](std::uint32_t triangle, const Corners& corners, int i, int j, int k,
                               const ClippedPiece& piece) {
                    ++local_pieces;
                    values.evaluate(triangle, barycentrics(corners, piece.centroid), corners, value);
                    const double weight = piece.area + kAreaEpsilon;
                    double* voxel = &sums[std::size_t(((i & 7) << 6) | ((j & 7) << 3) | (k & 7)) * std::size_t(channels + 1)];
                    for (int c = 0; c < channels; ++c) voxel[c] += weight * value[c];
                    voxel[channels] += weight;
                };
                // Adds the triangle's pieces in the voxels of `mask` (8 words, the leaf's layout),
                // clipped to their boxes grown by `margin`. The reference clips box by box; cpu
                // clips slab by slab (x, then y, then z), sharing the first clips among a row's
                // voxels: the same planes in the same order, so the same pieces.
                auto visit = [&](std::uint32_t n, const std::uint64_t* mask, double margin) {
                    const std::uint32_t triangle = usable[n];
                    const Corners corners = voxelCorners(job, triangle);
                    const VoxelRange r = candidates(corners, leaf_lo, leaf_hi);
                    ClippedPiece piece;
                    if (brute_force) {
                        for (int i = r.lo[0]; i <= r.hi[0]; ++i)
                            for (int j = r.lo[1]; j <= r.hi[1]; ++j)
                                for (int k = r.lo[2]; k <= r.hi[2]; ++k)
                                    if (((mask[i & 7] >> (((j & 7) << 3) | (k & 7))) & 1u) &&
                                        clipTriangleToVoxel(corners, {i, j, k}, piece, margin))
                                        add(triangle, corners, i, j, k, piece);
                        return;
                    }
                    Polygon whole, x_slab, xy_column, box;
                    whole.n = 3;
                    std::copy(corners.begin(), corners.end(), whole.p.begin());
                    for (int i = r.lo[0]; i <= r.hi[0]; ++i) {
                        const std::uint64_t word = mask[i & 7];
                        if (!word) continue;
                        clipSlab(whole, x_slab, 0, i - margin, i + 1 + margin);
                        if (x_slab.n == 0) continue;
                        for (int j = r.lo[1]; j <= r.hi[1]; ++j) {
                            const std::uint64_t row = (word >> ((j & 7) << 3)) & 0xffu;
                            if (!row) continue;
                            clipSlab(x_slab, xy_column, 1, j - margin, j + 1 + margin);
                            if (xy_column.n == 0) continue;
                            for (int k = r.lo[2]; k <= r.hi[2]; ++k) {
                                if (!((row >> (k & 7)) & 1u)) continue;
                                clipSlab(xy_column, box, 2, k - margin, k + 1 + margin);
                                if (box.n == 0) continue;
                                measurePiece(box, piece);
                                add(triangle, corners, i, j, k, piece);
                            }
                        }
                    }
                };
                auto visitAll = [&](const std::uint64_t* mask, double margin) {
                    if (brute_force)
                        for (std::uint32_t n = 0; n < usable.size(); ++n) visit(n, mask, margin);
                    else
                        for (std::uint32_t n : binned[s]) visit(n, mask, margin);
                };
                visitAll(words, 0.0);
                // Set voxels no exact piece reached: the method's test found a touch that the
                // clip lost to rounding; the touches within kTouchMargin stand in for it.
                std::uint64_t lost[BitGrid::kWordsPerBrick] = {};
                bool any_lost = false;
                for (int v = 0; v < 512; ++v)
                    if (((words[v >> 6] >> (v & 63)) & 1u) && !(sums[std::size_t(v) * std::size_t(channels + 1) + std::size_t(channels)] > 0)) {
                        lost[v >> 6] |= std::uint64_t(1) << (v & 63);
                        any_lost = true;
                    }
                if (any_lost) {
                    rounded.fetch_add(1, std::memory_order_relaxed);
                    visitAll(lost, kTouchMargin);
                }

                AttributeLeaf& leaf = out[first + s];
                leaf.brick = grid_bricks.index((tile_lo[0] >> 3) + at[0], (tile_lo[1] >> 3) + at[1], (tile_lo[2] >> 3) + at[2]);
                const AttributeGrid& layout = values.layout();
                for (int v = 0; v < 512; ++v) {
                    if (!((words[v >> 6] >> (v & 63)) & 1u)) continue;
                    const double* voxel = &sums[std::size_t(v) * std::size_t(channels + 1)];
                    const double weight = voxel[channels];
                    if (!(weight > 0)) unreached.fetch_add(1, std::memory_order_relaxed);
                    float mean[kMaxChannels];
                    for (int c = 0; c < channels; ++c) mean[c] = weight > 0 ? float(voxel[c] / weight) : 0.0f;
                    if (layout.normal) {
                        float* n = mean + layout.normalOffset();
                        const double length = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
                        if (length > 0) {
                            // From the double sums, not the rounded floats.
                            const double* sum = voxel + layout.normalOffset();
                            const double exact = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
                            for (int a = 0; a < 3; ++a) n[a] = float(sum[a] / exact);
                        }
                    }
                    leaf.values.insert(leaf.values.end(), mean, mean + channels);
                }
            }
            pieces.fetch_add(local_pieces, std::memory_order_relaxed);
        });
    });
    return {pieces.load(), unreached.load(), rounded.load()};
}

void assembleAttributes(std::vector<AttributeLeaf>& leaves, AttributeGrid& grid) {
    std::sort(leaves.begin(), leaves.end(), [](const AttributeLeaf& a, const AttributeLeaf& b) { return a.brick < b.brick; });
    std::size_t total = 0;
    for (const AttributeLeaf& leaf : leaves) total += leaf.values.size();
    grid.values.clear();
    grid.values.reserve(total);
    for (AttributeLeaf& leaf : leaves) {
        grid.values.insert(grid.values.end(), leaf.values.begin(), leaf.values.end());
        std::vector<float>().swap(leaf.values);
    }
}

}  // namespace hyvox::attributes
