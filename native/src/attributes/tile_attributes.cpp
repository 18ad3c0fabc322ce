// SPDX-License-Identifier: GPL-3.0-or-later
#include "attributes/tile_attributes.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "attributes/clip_to_voxel.h"
#include "attributes/sweep_triangle.h"

namespace hyvox::attributes {
namespace {

using Corners = std::array<Point, 3>;
using LeafMask = std::array<std::uint64_t, BitGrid::kWordsPerBrick>;

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

bool bitSet(const std::uint64_t* words, int v) { return (words[v >> 6] >> (v & 63)) & 1u; }

// The tile's non-empty bricks, and (unless brute force) the triangles (positions in
// job.mesh.usable, ascending) whose candidate voxels reach each: brick s's are
// triangles[first[s] .. first[s + 1]), counted first and then filled (no list per brick).
struct TileBins {
    std::vector<std::size_t> occupied;  // tile brick indices
    std::vector<std::size_t> first;     // occupied.size() + 1 offsets into triangles
    std::vector<std::uint32_t> triangles;

    struct Span {
        const std::uint32_t* from;
        const std::uint32_t* to;
        const std::uint32_t* begin() const { return from; }
        const std::uint32_t* end() const { return to; }
    };
    Span of(std::size_t slot) const { return {triangles.data() + first[slot], triangles.data() + first[slot + 1]}; }
};

TileBins binTriangles(const BackendJob& job, const BitGrid& bits, bool brute_force) {
    const BrickLayout& bricks = bits.bricks();
    const std::array<int, 3> tile_lo{job.tile.offset[0], job.tile.offset[1], job.tile.offset[2]};
    const std::array<int, 3> tile_hi{job.tile.last(0), job.tile.last(1), job.tile.last(2)};
    TileBins bins;
    std::vector<std::int64_t> slot_of_brick(bricks.total(), -1);
    for (std::size_t b = 0; b < bricks.total(); ++b) {
        const std::uint64_t* words = bits.data() + b * BitGrid::kWordsPerBrick;
        if (std::any_of(words, words + BitGrid::kWordsPerBrick, [](std::uint64_t w) { return w != 0; })) {
            slot_of_brick[b] = std::int64_t(bins.occupied.size());
            bins.occupied.push_back(b);
        }
    }
    if (brute_force) return bins;
    // Pass 0 counts each occupied brick's triangles, pass 1 places them in mesh order.
    bins.first.assign(bins.occupied.size() + 1, 0);
    std::vector<std::size_t> next;
    const auto& usable = job.mesh.usable;
    // Each triangle's candidate voxels first, in parallel (the corners' divisions and the
    // vertex reads are most of the binning).
    std::vector<VoxelRange> ranges(usable.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, usable.size(), 4096), [&](const auto& range) {
        for (std::size_t n = range.begin(); n != range.end(); ++n)
            ranges[n] = candidates(triangleCorners(job, usable[n]), tile_lo, tile_hi);
    });
    for (int pass = 0; pass < 2; ++pass) {
        for (std::uint32_t n = 0; n < usable.size(); ++n) {
            const VoxelRange& r = ranges[n];
            if (r.empty()) continue;
            for (int bx = (r.lo[0] - tile_lo[0]) >> 3; bx <= (r.hi[0] - tile_lo[0]) >> 3; ++bx)
                for (int by = (r.lo[1] - tile_lo[1]) >> 3; by <= (r.hi[1] - tile_lo[1]) >> 3; ++by)
                    for (int bz = (r.lo[2] - tile_lo[2]) >> 3; bz <= (r.hi[2] - tile_lo[2]) >> 3; ++bz) {
                        const std::int64_t slot = slot_of_brick[bricks.index(bx, by, bz)];
                        if (slot < 0) continue;
                        if (pass == 0)
                            ++bins.first[std::size_t(slot) + 1];
                        else
                            bins.triangles[next[std::size_t(slot)]++] = n;
                    }
        }
        if (pass == 0) {
            for (std::size_t s = 0; s < bins.occupied.size(); ++s) bins.first[s + 1] += bins.first[s];
            bins.triangles.resize(bins.first.back());
            next.assign(bins.first.begin(), bins.first.end() - 1);
        }
    }
    return bins;
}

// One leaf's sums (channels, then the weight, per voxel in the leaf's bit order), filled
// from triangles one after the other.
class LeafAccumulator {
public:
    // `sums`: 512 * (channels + 1) zeros, the thread's, handed back zero (takeMeans() clears
    // the set voxels', the only ones written).
    LeafAccumulator(const BackendJob& job, const SurfaceValues& values, bool brute_force, std::vector<double>& sums)
        : job_(job), values_(values), brute_force_(brute_force), stride_(std::size_t(values.channels() + 1)),
          sums_(sums) {}

    void start(const std::uint64_t* words, const std::array<int, 3>& lo, const std::array<int, 3>& hi) {
        words_ = words;
        leaf_voxels_.reset(words);
        lo_ = lo;
        hi_ = hi;
    }

    // Every triangle's exact pieces; then, for set voxels none reached (a touch the method's
    // test found and the clip lost to rounding), the pieces within kTouchMargin. True when
    // that fallback ran.
    template <typename Triangles>
    bool accumulate(const Triangles& triangles) {
        for (std::uint32_t n : triangles) addTriangle(n, words_, 0.0);
        LeafMask lost{};
        bool any_lost = false;
        for (int v = 0; v < 512; ++v)
            if (bitSet(words_, v) && !(weight(v) > 0)) {
                lost[std::size_t(v >> 6)] |= std::uint64_t(1) << (v & 63);
                any_lost = true;
            }
        if (any_lost)
            for (std::uint32_t n : triangles) addTriangle(n, lost.data(), kTouchMargin);
        return any_lost;
    }

    // The means of the set voxels in bit order, normals renormalised, and the sums cleared
    // for the next leaf; counts voxels still unreached.
    void takeMeans(std::vector<float>& out, std::uint64_t& unreached) {
        const std::size_t channels = std::size_t(values_.channels());
        std::size_t count = 0;
        for (int word = 0; word < BitGrid::kWordsPerBrick; ++word) count += std::size_t(__builtin_popcountll(words_[word]));
        out.resize(count * channels);
        float* mean = out.data();
        for (int word = 0; word < BitGrid::kWordsPerBrick; ++word)
            for (std::uint64_t bits = words_[word]; bits; bits &= bits - 1) {
                const int v = 64 * word + __builtin_ctzll(bits);
                double* sums = &sums_[std::size_t(v) * stride_];
                const double w = sums[stride_ - 1];
                if (!(w > 0)) ++unreached;
                meanOfSums(values_.layout(), sums, w, mean);
                mean += channels;
                std::fill(sums, sums + stride_, 0.0);
            }
    }

    std::uint64_t pieces() const { return pieces_; }

private:
    double weight(int v) const { return sums_[std::size_t(v) * stride_ + stride_ - 1]; }

    // Inlined into each of the sweep's visits (it runs once per piece).
    [[gnu::always_inline]] void add(const TriangleFrame& frame, int i, int j, int k, const ClippedPiece& piece) {
        ++pieces_;
        const double w = piece.area + kAreaEpsilon;
        double* voxel = &sums_[std::size_t(((i & 7) << 6) | ((j & 7) << 3) | (k & 7)) * stride_];
        values_.addWeighted(corner_values_, frame.barycentrics(piece.centroid), w, voxel);
        voxel[stride_ - 1] += w;
    }

    // The triangle's pieces in the voxels of `mask`, clipped to their boxes grown by `margin`.
    // cpu sweeps the triangle (sweep_triangle.h) past the slabs and columns whose voxels are
    // all unset; the reference, and the margin fallback of both, clip box by box.
    void addTriangle(std::uint32_t n, const std::uint64_t* mask, double margin) {
        const std::uint32_t triangle = job_.mesh.usable[n];
        const Corners corners = triangleCorners(job_, triangle);
        const VoxelRange r = candidates(corners, lo_, hi_);
        if (r.empty()) return;
        const TriangleFrame frame(corners);
        values_.prepare(triangle, frame.unitNormal(), corner_values_);
        ClippedPiece piece;
        if (brute_force_ || margin > 0) {
            for (int i = r.lo[0]; i <= r.hi[0]; ++i)
                for (int j = r.lo[1]; j <= r.hi[1]; ++j)
                    for (int k = r.lo[2]; k <= r.hi[2]; ++k)
                        if (bitSet(mask, ((i & 7) << 6) | ((j & 7) << 3) | (k & 7)) &&
                            clipTriangleToVoxel(corners, {i, j, k}, frame, piece, margin))
                            add(frame, i, j, k, piece);
            return;
        }
        sweepTriangle(corners, frame, r.lo, r.hi, leaf_voxels_, [&](const Voxel& v, const ClippedPiece& cut) {
            add(frame, v[0], v[1], v[2], cut);
        });
    }

    const BackendJob& job_;
    const SurfaceValues& values_;
    const bool brute_force_;
    const std::size_t stride_;
    std::vector<double>& sums_;
    const std::uint64_t* words_ = nullptr;
    LeafVoxels leaf_voxels_;  // words_, asked along each sweep order
    std::array<int, 3> lo_{}, hi_{};
    std::uint64_t pieces_ = 0;
    CornerValues corner_values_;
};

// 0, 1, ..., count - 1: the brute force's triangle list.
struct AllTriangles {
    struct Iterator {
        std::uint32_t n;
        std::uint32_t operator*() const { return n; }
        Iterator& operator++() {
            ++n;
            return *this;
        }
        bool operator!=(const Iterator& other) const { return n != other.n; }
    };
    std::uint32_t count;
    Iterator begin() const { return {0}; }
    Iterator end() const { return {count}; }
};

}  // namespace

std::array<Point, 3> triangleCorners(const BackendJob& job, std::uint32_t triangle) {
    return {job.grid.toVoxel(job.mesh.vertex(triangle, 0)), job.grid.toVoxel(job.mesh.vertex(triangle, 1)),
            job.grid.toVoxel(job.mesh.vertex(triangle, 2))};
}

TileAttributeCounts computeTileAttributes(const BackendJob& job, const BitGrid& bits, const SurfaceValues& values,
                                          bool brute_force, std::vector<AttributeLeaf>& out) {
    const int threads = job.options.threads > 0 ? job.options.threads : tbb::task_arena::automatic;
    tbb::task_arena arena(threads);
    const TileBins bins = arena.execute([&] { return binTriangles(job, bits, brute_force); });
    const BrickLayout& tile_bricks = bits.bricks();
    const BrickLayout grid_bricks = job.grid.bricks();
    const std::array<std::int32_t, 3>& offset = job.tile.offset;
    const std::size_t first = out.size();
    out.resize(first + bins.occupied.size());
    std::atomic<std::uint64_t> pieces{0}, unreached{0}, rounded{0};
    tbb::enumerable_thread_specific<std::vector<double>> sums_of_thread(512 * std::size_t(values.channels() + 1), 0.0);
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, bins.occupied.size(), 4), [&](const auto& range) {
            throwIfInterrupted(job.interrupter);
            LeafAccumulator leaf(job, values, brute_force, sums_of_thread.local());
            std::uint64_t local_unreached = 0, local_rounded = 0;
            for (std::size_t s = range.begin(); s != range.end(); ++s) {
                const std::size_t b = bins.occupied[s];
                const std::array<std::int32_t, 3> at = tile_bricks.at(b);
                std::array<int, 3> lo, hi;
                for (std::size_t a = 0; a < 3; ++a) {
                    lo[a] = offset[a] + 8 * at[a];
                    hi[a] = std::min(lo[a] + 7, job.tile.last(int(a)));
                }
                leaf.start(bits.data() + b * BitGrid::kWordsPerBrick, lo, hi);
                const bool fell_back = brute_force ? leaf.accumulate(AllTriangles{std::uint32_t(job.mesh.usable.size())})
                                                   : leaf.accumulate(bins.of(s));
                local_rounded += fell_back;
                AttributeLeaf& result = out[first + s];
                result.brick = grid_bricks.index((offset[0] >> 3) + at[0], (offset[1] >> 3) + at[1], (offset[2] >> 3) + at[2]);
                leaf.takeMeans(result.values, local_unreached);
            }
            pieces.fetch_add(leaf.pieces(), std::memory_order_relaxed);
            unreached.fetch_add(local_unreached, std::memory_order_relaxed);
            rounded.fetch_add(local_rounded, std::memory_order_relaxed);
        });
    });
    return {pieces.load(), unreached.load(), rounded.load()};
}

void assembleAttributes(std::vector<AttributeLeaf>& leaves, AttributeGrid& grid, int threads) {
    std::sort(leaves.begin(), leaves.end(), [](const AttributeLeaf& a, const AttributeLeaf& b) { return a.brick < b.brick; });
    // Each leaf's place in the result, then the copies (and frees) in parallel: the values of
    // a large grid are tens of MB.
    std::vector<std::size_t> start(leaves.size() + 1, 0);
    for (std::size_t n = 0; n < leaves.size(); ++n) start[n + 1] = start[n] + leaves[n].values.size();
    grid.values.clear();
    grid.values.resize(start.back());
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.size(), 64), [&](const auto& range) {
            for (std::size_t n = range.begin(); n != range.end(); ++n) {
                std::copy(leaves[n].values.begin(), leaves[n].values.end(), grid.values.begin() + std::ptrdiff_t(start[n]));
                std::vector<float>().swap(leaves[n].values);
            }
        });
    });
}

}  // namespace hyvox::attributes
