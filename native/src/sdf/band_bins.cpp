// SPDX-License-Identifier: GPL-3.0-or-later
#include "sdf/band_bins.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>

#include "hyvox/errors.h"
#include "sdf/point_triangle.h"

namespace hyvox::sdf {
namespace {

// Triangles reaching at most this many blocks are binned into all of them without a test.
constexpr std::uint64_t kTestedAbove = 8;

struct Pair {
    std::uint64_t block;
    std::uint32_t triangle;
};

std::string mib(std::uint64_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; }

// The pairs of `runs`, taken in order, sorted by block, stably (a block's triangles keep their
// order): a radix sort of 16 bits a pass, the first pass reading the runs (and freeing them),
// one pass in all while the grid has at most 65536 blocks: linear in the pairs, where the
// comparison sort it replaced was measurably slower on fine meshes (docs/why/sdf.md).
std::vector<Pair> sortedByBlock(std::vector<std::vector<Pair>>& runs, std::uint64_t pairs, std::uint64_t block_count) {
    constexpr int kDigitBits = 16;
    constexpr std::uint64_t kDigitMask = (std::uint64_t(1) << kDigitBits) - 1;
    std::vector<std::uint64_t> start((std::size_t(1) << kDigitBits) + 1);
    std::vector<Pair> sorted(pairs), spare;
    auto pass = [&](int shift, auto forEachSource, std::vector<Pair>& into) {
        std::fill(start.begin(), start.end(), 0);
        forEachSource([&](const Pair& pair) { ++start[((pair.block >> shift) & kDigitMask) + 1]; });
        for (std::size_t d = 1; d < start.size(); ++d) start[d] += start[d - 1];
        forEachSource([&](const Pair& pair) { into[start[(pair.block >> shift) & kDigitMask]++] = pair; });
    };
    pass(
        0,
        [&](auto visit) {
            for (const std::vector<Pair>& run : runs)
                for (const Pair& pair : run) visit(pair);
        },
        sorted);
    std::vector<std::vector<Pair>>().swap(runs);
    for (int shift = kDigitBits; block_count > 0 && (block_count - 1) >> shift; shift += kDigitBits) {
        spare.resize(pairs);
        pass(
            shift,
            [&](auto visit) {
                for (const Pair& pair : sorted) visit(pair);
            },
            spare);
        sorted.swap(spare);
    }
    return sorted;
}

// Calls visit(block index) for each block triangle t may lie within the band of.
template <typename Visit>
void forEachBlock(const ValidatedMesh& mesh, const GridSpec& grid, const BlockLayout& blocks, double band,
                  std::uint32_t t, Visit visit) {
    const auto corners = voxelCorners(mesh, grid, t);
    std::array<std::int32_t, 3> lo, hi;
    if (!reachOf(corners, grid, band, lo, hi)) return;
    constexpr int kLog2 = BlockLayout::kLog2, kSide = BlockLayout::kSide;
    std::array<std::int32_t, 3> b_lo, b_hi;
    std::uint64_t count = 1;
    for (int a = 0; a < 3; ++a) {
        b_lo[a] = lo[a] >> kLog2;
        b_hi[a] = hi[a] >> kLog2;
        count *= std::uint64_t(b_hi[a] - b_lo[a] + 1);
    }
    if (count <= kTestedAbove) {
        for (int bx = b_lo[0]; bx <= b_hi[0]; ++bx)
            for (int by = b_lo[1]; by <= b_hi[1]; ++by)
                for (int bz = b_lo[2]; bz <= b_hi[2]; ++bz) visit(blocks.index(bx, by, bz));
        return;
    }
    // A block whose reached centres all lie farther than the band from the triangle: its
    // middle is farther than the band plus half the diagonal of those centres' box.
    const DistanceTriangle triangle(corners);
    for (int bx = b_lo[0]; bx <= b_hi[0]; ++bx)
        for (int by = b_lo[1]; by <= b_hi[1]; ++by)
            for (int bz = b_lo[2]; bz <= b_hi[2]; ++bz) {
                const int b[3] = {bx, by, bz};
                Vec3 middle;
                double half_diagonal2 = 0;
                for (int a = 0; a < 3; ++a) {
                    const double first = std::max(kSide * b[a], lo[a]) + 0.5;
                    const double last = std::min(kSide * b[a] + kSide - 1, hi[a]) + 0.5;
                    middle[a] = 0.5 * (first + last);
                    half_diagonal2 += 0.25 * (last - first) * (last - first);
                }
                const double reach = band + std::sqrt(half_diagonal2) + 1e-9;
                if (triangle.distance2(middle) < reach * reach) visit(blocks.index(bx, by, bz));
            }
}

}  // namespace

std::array<std::array<double, 3>, 3> voxelCorners(const ValidatedMesh& mesh, const GridSpec& grid, std::uint32_t t) {
    return {grid.toVoxel(mesh.vertex(t, 0)), grid.toVoxel(mesh.vertex(t, 1)), grid.toVoxel(mesh.vertex(t, 2))};
}

bool reachOf(const std::array<std::array<double, 3>, 3>& corners, const GridSpec& grid, double band,
             std::array<std::int32_t, 3>& lo, std::array<std::int32_t, 3>& hi) {
    for (int a = 0; a < 3; ++a) {
        const double min = std::min({corners[0][a], corners[1][a], corners[2][a]});
        const double max = std::max({corners[0][a], corners[1][a], corners[2][a]});
        // Centre i + 0.5 within the band of [min, max]; clipped to the grid before the
        // conversion (a far vertex may lie billions of voxels away).
        const double first = std::ceil(min - band - 0.5), last = std::floor(max + band - 0.5);
        lo[a] = std::int32_t(std::clamp(first, 0.0, double(grid.dims[a])));
        hi[a] = std::int32_t(std::clamp(last, -1.0, double(grid.dims[a] - 1)));
        if (lo[a] > hi[a]) return false;
    }
    return true;
}

BandBins binBand(const ValidatedMesh& mesh, const GridSpec& grid, double band, std::uint64_t budget_bytes,
                 std::uint64_t budget_mib, Interrupter* interrupter) {
    const std::vector<std::uint32_t>& usable = mesh.usable;
    const BlockLayout blocks(grid);
    const std::size_t n = usable.size();
    constexpr std::size_t kGrain = 4096;
    auto checked = [&](std::size_t at) {
        if (at % kInterruptCheckTriangles < kGrain) throwIfInterrupted(interrupter);
    };
    // One pass over the triangles, each run of kGrain writing its own pairs (the mesh's order
    // when the runs are read in turn), the memory they take counted against the budget as
    // they are made: the runs (with their growth's slack), sorted into one vector, then lists.
    constexpr std::uint64_t kBytesPerPair = 3 * sizeof(Pair);
    std::vector<std::vector<Pair>> runs((n + kGrain - 1) / kGrain);
    std::atomic<std::uint64_t> made{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, runs.size(), 1), [&](const auto& range) {
        for (std::size_t r = range.begin(); r != range.end(); ++r) {
            checked(r * kGrain);
            std::vector<Pair>& run = runs[r];
            for (std::size_t u = r * kGrain; u < std::min(n, (r + 1) * kGrain); ++u)
                forEachBlock(mesh, grid, blocks, band, usable[u],
                             [&](std::uint64_t block) { run.push_back({block, usable[u]}); });
            const std::uint64_t so_far = made += run.size();
            if (so_far * kBytesPerPair > budget_bytes)
                throw ResourceError("the sdf's band needs more than " + mib(so_far * kBytesPerPair) +
                                    " for its (triangle, block) pairs (" + std::to_string(so_far) +
                                    " so far), beyond the memory budget of " + std::to_string(budget_mib) +
                                    " MiB; use a larger voxel size or a narrower sdf_band");
        }
    });
    throwIfInterrupted(interrupter);
    const std::uint64_t pairs = made;
    const std::vector<Pair> all = sortedByBlock(
        runs, pairs,
        std::uint64_t(blocks.counts[0]) * std::uint64_t(blocks.counts[1]) * std::uint64_t(blocks.counts[2]));
    throwIfInterrupted(interrupter);
    BandBins bins;
    bins.triangles.resize(pairs);
    for (std::uint64_t p = 0; p < pairs; ++p) {
        if (p == 0 || all[p].block != all[p - 1].block) {
            bins.blocks.push_back(all[p].block);
            bins.start.push_back(p);
        }
        bins.triangles[p] = all[p].triangle;
    }
    bins.start.push_back(pairs);
    return bins;
}

}  // namespace hyvox::sdf
