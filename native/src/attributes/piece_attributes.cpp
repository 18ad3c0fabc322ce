// SPDX-License-Identifier: GPL-3.0-or-later
#include "attributes/piece_attributes.h"

#include <algorithm>
#include <atomic>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_arena.h>

#include "attributes/clip_to_voxel.h"
#include "hyvox/errors.h"

namespace hyvox::attributes {
namespace {

// A voxel's place in the tile's bit grid: brick, then bit (the order of the leaves' values).
std::uint64_t voxelKey(const BrickLayout& bricks, const std::array<std::int32_t, 3>& v) {
    const std::uint64_t bit = std::uint64_t(BitGrid::bitInBrick(v[0], v[1], v[2]));
    return std::uint64_t(bricks.index(v[0] >> 3, v[1] >> 3, v[2] >> 3)) * 512u + bit;
}

// The sort key beside the piece's position, so sorting moves 16 bytes and reads no piece.
struct KeyedPiece {
    std::uint64_t voxel;
    std::uint32_t triangle;
    std::uint32_t index;  // in pieces
    bool operator<(const KeyedPiece& other) const {
        return voxel != other.voxel ? voxel < other.voxel : triangle < other.triangle;
    }
};

}  // namespace

TileAttributeCounts computePieceAttributes(const BackendJob& job, const BitGrid& bits, const SurfaceValues& values,
                                           const std::vector<VoxelPiece>& pieces, std::vector<AttributeLeaf>& out) {
    const BrickLayout& tile_bricks = bits.bricks();
    const BrickLayout grid_bricks = job.grid.bricks();
    const std::array<std::int32_t, 3>& offset = job.tile.offset;
    const int threads = job.options.threads > 0 ? job.options.threads : tbb::task_arena::automatic;
    tbb::task_arena arena(threads);

    std::vector<KeyedPiece> sorted(pieces.size());
    if (pieces.size() > 0xffffffffu)
        throw ResourceError("more than 2^32 clipped pieces in one tile; use smaller tiles");
    for (std::size_t n = 0; n < pieces.size(); ++n)
        sorted[n] = {voxelKey(tile_bricks, pieces[n].voxel), pieces[n].triangle, std::uint32_t(n)};
    arena.execute([&] { tbb::parallel_sort(sorted.begin(), sorted.end()); });
    throwIfInterrupted(job.interrupter);

    std::vector<std::size_t> occupied;
    for (std::size_t b = 0; b < tile_bricks.total(); ++b) {
        const std::uint64_t* words = bits.data() + b * BitGrid::kWordsPerBrick;
        if (std::any_of(words, words + BitGrid::kWordsPerBrick, [](std::uint64_t w) { return w != 0; }))
            occupied.push_back(b);
    }
    const std::size_t first = out.size();
    out.resize(first + occupied.size());
    const std::size_t stride = std::size_t(values.channels() + 1);
    std::atomic<std::uint64_t> used{0}, unreached{0}, rounded{0};
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, occupied.size(), 4), [&](const auto& range) {
            throwIfInterrupted(job.interrupter);
            std::vector<double> sums(stride);
            std::uint64_t local_used = 0, local_unreached = 0, local_rounded = 0;
            for (std::size_t s = range.begin(); s != range.end(); ++s) {
                const std::size_t b = occupied[s];
                const std::uint64_t* words = bits.data() + b * BitGrid::kWordsPerBrick;
                auto next = std::lower_bound(sorted.begin(), sorted.end(), std::uint64_t(b) * 512u,
                                             [](const KeyedPiece& p, std::uint64_t key) { return p.voxel < key; });
                const std::array<std::int32_t, 3> at = tile_bricks.at(b);
                AttributeLeaf& result = out[first + s];
                result.brick =
                    grid_bricks.index((offset[0] >> 3) + at[0], (offset[1] >> 3) + at[1], (offset[2] >> 3) + at[2]);
                bool leaf_rounded = false;
                for (int v = 0; v < 512; ++v) {
                    if (!((words[v >> 6] >> (v & 63)) & 1u)) continue;
                    const std::uint64_t key = std::uint64_t(b) * 512u + std::uint64_t(v);
                    while (next != sorted.end() && next->voxel < key) ++next;  // pieces of unset voxels: none expected
                    auto end = next;
                    bool any_exact = false;
                    for (; end != sorted.end() && end->voxel == key; ++end) any_exact |= !pieces[end->index].margin;
                    // As the cpu method: pieces clipped with the touch margin only where no exact one reached.
                    leaf_rounded |= next != end && !any_exact;
                    std::fill(sums.begin(), sums.end(), 0.0);
                    for (; next != end; ++next) {
                        const VoxelPiece& piece = pieces[next->index];
                        if (piece.margin == any_exact) continue;
                        ++local_used;
                        const std::uint32_t triangle = job.mesh.usable[piece.triangle];
                        const TriangleFrame frame(triangleCorners(job, triangle));
                        Point centroid;
                        for (std::size_t a = 0; a < 3; ++a)
                            centroid[a] = double(offset[a] + piece.voxel[a]) + double(piece.centroid[a]);
                        double value[kMaxChannels];
                        values.evaluate(triangle, frame.barycentrics(centroid), frame.unitNormal(), value);
                        const double w = double(piece.area) + kAreaEpsilon;
                        for (std::size_t c = 0; c + 1 < stride; ++c) sums[c] += w * value[c];
                        sums[stride - 1] += w;
                    }
                    if (!(sums[stride - 1] > 0)) ++local_unreached;
                    float mean[kMaxChannels];
                    meanOfSums(values.layout(), sums.data(), sums[stride - 1], mean);
                    result.values.insert(result.values.end(), mean, mean + values.channels());
                }
                local_rounded += leaf_rounded;
            }
            used.fetch_add(local_used, std::memory_order_relaxed);
            unreached.fetch_add(local_unreached, std::memory_order_relaxed);
            rounded.fetch_add(local_rounded, std::memory_order_relaxed);
        });
    });
    return {used.load(), unreached.load(), rounded.load()};
}

}  // namespace hyvox::attributes
