// SPDX-License-Identifier: GPL-3.0-or-later
#include "sdf/level_set.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "hyvox/errors.h"
#include "sdf/band_bins.h"
#include "sdf/band_distances.h"

namespace hyvox::sdf {
namespace {

using Leaf = LevelSetGrid::Leaf;
constexpr int kWords = BitGrid::kWordsPerBrick;

std::string mib(std::uint64_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; }

// The voxels of `brick` whose centre is inside.
void insideWords(const InsideCentres& centres, std::uint64_t brick, std::uint64_t out[kWords]) {
    std::uint64_t surface[kWords], on_surface[kWords], off_surface[kWords];
    centres.surface.brickWords(brick, surface);
    centres.surface_inside.brickWords(brick, on_surface);
    centres.inside.brickWords(brick, off_surface);
    for (int w = 0; w < kWords; ++w) out[w] = (surface[w] & on_surface[w]) | (~surface[w] & off_surface[w]);
}

std::size_t countOf(const std::uint64_t words[kWords]) {
    std::size_t n = 0;
    for (int w = 0; w < kWords; ++w) n += std::size_t(__builtin_popcountll(words[w]));
    return n;
}

// The leaves of one block of the band (bricks with band voxels), measured by one task.
struct Chunk {
    std::vector<Leaf> leaves;  // `first` into this chunk's values
    std::vector<float> values;
    std::uint64_t evaluations = 0;
};

// The bricks of block `block` that hold band voxels, as leaves, from the block's distances
// (`touched`: the bricks where a distance may lie below the band, as blockDistances gives them).
void leavesOf(const std::array<std::int32_t, 3>& block, const double* d2, std::uint64_t touched, double band2,
              const GridSpec& grid, const InsideCentres& centres, Chunk& chunk) {
    const BrickLayout bricks = grid.bricks();
    for (; touched; touched &= touched - 1) {
        const int bit = __builtin_ctzll(touched);
        const int bx = bit / (kBlockBricks * kBlockBricks), by = (bit / kBlockBricks) % kBlockBricks,
                  bz = bit % kBlockBricks;
        const std::array<std::int32_t, 3> b{block[0] * kBlockBricks + bx, block[1] * kBlockBricks + by,
                                            block[2] * kBlockBricks + bz};
        if (8 * b[0] >= grid.dims[0] || 8 * b[1] >= grid.dims[1] || 8 * b[2] >= grid.dims[2]) continue;
        // Voxel (x, y, z) of the brick: its row of 8 along z is contiguous in the block.
        auto row = [&](int x, int y) { return d2 + blockOffset(8 * bx + x, 8 * by + y, 8 * bz); };
        // The distances may reach past the grid's end along z (blockDistances).
        const int nz = std::min(8, grid.dims[2] - 8 * b[2]);
        Leaf leaf{};
        std::uint64_t any = 0;
        for (int x = 0; x < 8; ++x) {
            std::uint64_t word = 0;
            for (int y = 0; y < 8; ++y) {
                const double* r = row(x, y);
                for (int z = 0; z < 8; ++z) word |= std::uint64_t(r[z] < band2 && z < nz) << (8 * y + z);
            }
            leaf.active[x] = word;
            any |= word;
        }
        if (!any) continue;  // its inside, if any, is the inside pass's (below)
        leaf.brick = bricks.index(b[0], b[1], b[2]);
        leaf.first = chunk.values.size();
        insideWords(centres, leaf.brick, leaf.inside);
        for (int x = 0; x < 8; ++x)
            for (std::uint64_t bits = leaf.active[x]; bits; bits &= bits - 1) {
                const int v = __builtin_ctzll(bits);
                const float distance = float(std::sqrt(row(x, v >> 3)[v & 7]) * grid.voxel_size);
                chunk.values.push_back((leaf.inside[x] >> v) & 1 ? -distance : distance);
            }
        chunk.leaves.push_back(leaf);
    }
}

// Sorted runs, adjacent ones joined.
std::vector<SparseGrid::TileRun> joined(std::vector<SparseGrid::TileRun> runs) {
    std::sort(runs.begin(), runs.end(), [](const auto& a, const auto& b) { return a.begin < b.begin; });
    std::vector<SparseGrid::TileRun> out;
    for (const SparseGrid::TileRun& run : runs) {
        if (!out.empty() && out.back().end == run.begin)
            out.back().end = run.end;
        else
            out.push_back(run);
    }
    return out;
}

}  // namespace

LevelSetGrid makeLevelSet(const ValidatedMesh& mesh, const GridSpec& grid, const InsideCentres& centres,
                          const VoxelizeOptions& options, std::uint64_t held_bytes, Interrupter* interrupter,
                          SdfStats& stats) {
    const double band = double(options.sdf.band);
    const std::uint64_t budget = options.memoryBudgetBytes();
    const std::uint64_t left = budget > held_bytes ? budget - held_bytes : 0;
    tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
    const BandBins bins =
        arena.execute([&] { return binBand(mesh, grid, band, left, options.memoryBudgetMib(), interrupter); });
    // Every brick of a reached block a leaf of 512 floats: an upper bound of the grid as OpenVDB
    // (and Blender) will hold it.
    const std::uint64_t reached_bricks = std::uint64_t(bins.blocks.size()) * kBlockBricks * kBlockBricks * kBlockBricks;
    // Each thread's queries hold up to its block's triangles (the most any block has).
    std::uint64_t most_in_a_block = 0;
    for (std::size_t n = 0; n < bins.blocks.size(); ++n)
        most_in_a_block = std::max(most_in_a_block, bins.start[n + 1] - bins.start[n]);
    const std::uint64_t threads = std::min<std::uint64_t>(std::uint64_t(arena.max_concurrency()), bins.blocks.size());
    const std::uint64_t queries_bytes = threads * BlockQueries::bytesAtMost(band, most_in_a_block);
    const std::uint64_t need = reached_bricks * (sizeof(Leaf) + 512 * sizeof(float)) + bins.byteSize() + queries_bytes;
    if (need > left)
        throw ResourceError("the sdf's band needs about " + mib(need) + " beside " + mib(held_bytes) +
                            " held, more than the memory budget of " + std::to_string(options.memoryBudgetMib()) +
                            " MiB; use a larger voxel size or a narrower sdf_band");

    const BlockLayout blocks(grid);
    std::vector<Chunk> chunks(bins.blocks.size());
    struct Scratch {
        std::vector<double> d2 = std::vector<double>(kBlockVoxels);
        BlockQueries queries;
    };
    tbb::enumerable_thread_specific<Scratch> scratch;
    // The blocks with the most triangles first, one a task: a few crowded blocks can take
    // much of the band's time, and started last they would leave the other threads idle.
    std::vector<std::uint32_t> by_work(chunks.size());
    for (std::size_t n = 0; n < by_work.size(); ++n) by_work[n] = std::uint32_t(n);
    std::stable_sort(by_work.begin(), by_work.end(), [&](std::uint32_t a, std::uint32_t b) {
        return bins.start[a + 1] - bins.start[a] > bins.start[b + 1] - bins.start[b];
    });
    arena.execute([&] {
        tbb::parallel_for(
            tbb::blocked_range<std::size_t>(0, by_work.size(), 1),
            [&](const auto& range) {
                for (std::size_t at = range.begin(); at != range.end(); ++at) {
                    const std::size_t number = by_work[at];
                    throwIfInterrupted(interrupter);
                    Scratch& mine = scratch.local();
                    double* d2 = mine.d2.data();
                    const std::uint64_t touched =
                        blockDistances(mesh, grid, band, bins, number, d2, chunks[number].evaluations, &mine.queries);
                    leavesOf(blocks.at(bins.blocks[number]), d2, touched, band * band, grid, centres, chunks[number]);
                }
            },
            tbb::simple_partitioner());
    });
    throwIfInterrupted(interrupter);

    // The band's leaves in brick order (blocks hold bricks of several rows), values with them.
    struct Found {
        std::uint64_t brick;
        std::uint32_t chunk, leaf;
    };
    std::vector<Found> order;
    std::size_t values = 0;
    for (std::size_t c = 0; c < chunks.size(); ++c) {
        for (std::size_t l = 0; l < chunks[c].leaves.size(); ++l)
            order.push_back({chunks[c].leaves[l].brick, std::uint32_t(c), std::uint32_t(l)});
        values += chunks[c].values.size();
        stats.distance_evaluations += chunks[c].evaluations;
    }
    std::sort(order.begin(), order.end(), [](const Found& a, const Found& b) { return a.brick < b.brick; });
    LevelSetGrid out;
    out.background = float(band * grid.voxel_size);
    out.values.reserve(values);
    std::vector<Leaf> band_leaves;
    band_leaves.reserve(order.size());
    std::vector<std::uint64_t> band_bricks;
    band_bricks.reserve(order.size());
    for (const Found& found : order) {
        const Chunk& chunk = chunks[found.chunk];
        Leaf leaf = chunk.leaves[found.leaf];
        const auto from = chunk.values.begin() + long(leaf.first);
        leaf.first = out.values.size();
        out.values.insert(out.values.end(), from, from + long(countOf(leaf.active)));
        band_leaves.push_back(leaf);
        band_bricks.push_back(found.brick);
    }
    std::vector<Chunk>().swap(chunks);

    // The inside beyond the band: the inside pass's leaves off the band's bricks become leaves
    // of inactive voxels, its tiles off them inside tiles. (Every surface voxel lies in the band:
    // a voxel the surface touches has its centre within √3/2 voxel of it.)
    auto inBand = [&](std::uint64_t brick) {
        return std::binary_search(band_bricks.begin(), band_bricks.end(), brick);
    };
    std::vector<Leaf> beyond;
    for (const SparseGrid::Leaf& from : centres.inside.leaves()) {
        if (inBand(from.brick)) continue;
        Leaf leaf{};
        leaf.brick = from.brick;
        std::copy(from.words, from.words + kWords, leaf.inside);
        beyond.push_back(leaf);
    }
    out.leaves.reserve(band_leaves.size() + beyond.size());
    std::merge(band_leaves.begin(), band_leaves.end(), beyond.begin(), beyond.end(), std::back_inserter(out.leaves),
               [](const Leaf& a, const Leaf& b) { return a.brick < b.brick; });
    // A leaf without values points where the next leaf's values begin.
    for (std::size_t n = out.leaves.size(), next = out.values.size(); n-- > 0;) {
        if (countOf(out.leaves[n].active) == 0) out.leaves[n].first = next;
        next = out.leaves[n].first;
    }
    std::vector<SparseGrid::TileRun> tiles;
    for (const SparseGrid::TileRun& run : centres.inside.tileRuns()) {
        std::uint64_t from = run.begin;
        for (auto it = std::lower_bound(band_bricks.begin(), band_bricks.end(), run.begin);
             it != band_bricks.end() && *it < run.end; ++it) {
            if (from < *it) tiles.push_back({from, *it});
            from = *it + 1;
        }
        if (from < run.end) tiles.push_back({from, run.end});
    }
    out.inside_runs = joined(std::move(tiles));

    stats.background = out.background;
    stats.active_voxels = out.activeCount();
    stats.leaves = out.leaves.size();
    for (const SparseGrid::TileRun& run : out.inside_runs) stats.inside_tile_bricks += run.end - run.begin;
    stats.triangle_blocks = bins.triangles.size();
    return out;
}

}  // namespace hyvox::sdf
