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

// Leaves are taken in regions of 4³ (32³ voxels), one region per task: a triangle is set up
// and swept once per region it reaches rather than once per leaf, and its sweep cuts fewer
// leaf boundaries (docs/why/attributes.md).
constexpr int kRegionLog2 = 2;
constexpr int kRegionSide = 1 << kRegionLog2;  // leaves per region side
constexpr int kRegionLeaves = kRegionSide * kRegionSide * kRegionSide;
constexpr int kRegionVoxels = kRegionSide * 8;  // voxels per region side

// Leaf number within its region of tile brick `at`.
int leafInRegion(const std::array<std::int32_t, 3>& at) {
    constexpr int mask = kRegionSide - 1;
    return ((at[0] & mask) << (2 * kRegionLog2)) | ((at[1] & mask) << kRegionLog2) | (at[2] & mask);
}

// The tile's non-empty bricks (the results' slots, ascending), the regions that hold them
// (each with its bricks), and (unless brute force) the triangles (positions in
// job.mesh.usable, ascending) whose candidate voxels reach each region: region r's are
// triangles[first[r] .. first[r + 1]), counted first and then filled (no list per region).
struct TileBins {
    struct Leaf {
        std::size_t slot;  // in occupied
        int number;        // leafInRegion
    };
    std::vector<std::size_t> occupied;                 // tile brick indices
    std::vector<std::array<std::int32_t, 3>> regions;  // region coordinates in the tile
    std::vector<std::size_t> leaves_first;             // regions.size() + 1 offsets into leaves
    std::vector<Leaf> leaves;
    std::vector<std::size_t> first;  // regions.size() + 1 offsets into triangles
    std::vector<std::uint32_t> triangles;

    struct Span {
        const std::uint32_t* from;
        const std::uint32_t* to;
        const std::uint32_t* begin() const { return from; }
        const std::uint32_t* end() const { return to; }
    };
    Span of(std::size_t region) const {
        return {triangles.data() + first[region], triangles.data() + first[region + 1]};
    }
};

TileBins binTriangles(const BackendJob& job, const BitGrid& bits, bool brute_force) {
    const BrickLayout& bricks = bits.bricks();
    const std::array<int, 3> tile_lo{job.tile.offset[0], job.tile.offset[1], job.tile.offset[2]};
    const std::array<int, 3> tile_hi{job.tile.last(0), job.tile.last(1), job.tile.last(2)};
    BrickLayout region_layout;
    for (std::size_t a = 0; a < 3; ++a) region_layout.counts[a] = (bricks.counts[a] + kRegionSide - 1) >> kRegionLog2;
    TileBins bins;
    std::vector<std::int64_t> slot_of_region(region_layout.total(), -1);
    std::vector<std::vector<TileBins::Leaf>> leaves_of_region;
    for (std::size_t b = 0; b < bricks.total(); ++b) {
        const std::uint64_t* words = bits.data() + b * BitGrid::kWordsPerBrick;
        if (std::none_of(words, words + BitGrid::kWordsPerBrick, [](std::uint64_t w) { return w != 0; })) continue;
        const std::array<std::int32_t, 3> at = bricks.at(b);
        const std::size_t region =
            region_layout.index(at[0] >> kRegionLog2, at[1] >> kRegionLog2, at[2] >> kRegionLog2);
        if (slot_of_region[region] < 0) {
            slot_of_region[region] = std::int64_t(bins.regions.size());
            bins.regions.push_back({at[0] >> kRegionLog2, at[1] >> kRegionLog2, at[2] >> kRegionLog2});
            leaves_of_region.emplace_back();
        }
        leaves_of_region[std::size_t(slot_of_region[region])].push_back({bins.occupied.size(), leafInRegion(at)});
        bins.occupied.push_back(b);
    }
    bins.leaves_first.assign(1, 0);
    for (const auto& leaves : leaves_of_region) {
        bins.leaves.insert(bins.leaves.end(), leaves.begin(), leaves.end());
        bins.leaves_first.push_back(bins.leaves.size());
    }
    if (brute_force) return bins;
    // Pass 0 counts each region's triangles, pass 1 places them in mesh order.
    bins.first.assign(bins.regions.size() + 1, 0);
    std::vector<std::size_t> next;
    const auto& usable = job.mesh.usable;
    // Each triangle's candidate voxels first, in parallel (the corners' divisions and the
    // vertex reads are most of the binning).
    std::vector<VoxelRange> ranges(usable.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, usable.size(), 4096), [&](const auto& range) {
        for (std::size_t n = range.begin(); n != range.end(); ++n)
            ranges[n] = candidates(triangleCorners(job, usable[n]), tile_lo, tile_hi);
    });
    constexpr int kShift = 3 + kRegionLog2;
    for (int pass = 0; pass < 2; ++pass) {
        for (std::uint32_t n = 0; n < usable.size(); ++n) {
            const VoxelRange& r = ranges[n];
            if (r.empty()) continue;
            for (int rx = (r.lo[0] - tile_lo[0]) >> kShift; rx <= (r.hi[0] - tile_lo[0]) >> kShift; ++rx)
                for (int ry = (r.lo[1] - tile_lo[1]) >> kShift; ry <= (r.hi[1] - tile_lo[1]) >> kShift; ++ry)
                    for (int rz = (r.lo[2] - tile_lo[2]) >> kShift; rz <= (r.hi[2] - tile_lo[2]) >> kShift; ++rz) {
                        const std::int64_t slot = slot_of_region[region_layout.index(rx, ry, rz)];
                        if (slot < 0) continue;
                        if (pass == 0)
                            ++bins.first[std::size_t(slot) + 1];
                        else
                            bins.triangles[next[std::size_t(slot)]++] = n;
                    }
        }
        if (pass == 0) {
            for (std::size_t s = 0; s < bins.regions.size(); ++s) bins.first[s + 1] += bins.first[s];
            bins.triangles.resize(bins.first.back());
            next.assign(bins.first.begin(), bins.first.end() - 1);
        }
    }
    return bins;
}

// Per sweep order d (the axes a, b after d), the columns (a, b) of an 8³ leaf (bits x << 6 |
// y << 3 | z, as BitGrid's bricks) that hold a set voxel: bit (a << 3 | b).
std::array<std::uint64_t, 3> columnsOfLeaf(const std::uint64_t* words) {
    std::array<std::uint64_t, 3> columns{0, 0, 0};
    for (int x = 0; x < 8; ++x) {
        const std::uint64_t word = words[x];
        columns[0] |= word;       // (a, b) = (y, z): the word's own bits, any x
        std::uint64_t zs = word;  // the z bits set in any y of this x, in its low byte
        zs |= zs >> 32;
        zs |= zs >> 16;
        zs |= zs >> 8;
        for (int y = 0; y < 8; ++y)  // (a, b) = (x, y): byte y of word x
            if ((word >> (8 * y)) & 0xffu) columns[2] |= std::uint64_t(1) << (x << 3 | y);
        for (int z = 0; z < 8; ++z)  // (a, b) = (z, x)
            if ((zs >> z) & 1u) columns[1] |= std::uint64_t(1) << (z << 3 | x);
    }
    return columns;
}

// The voxels of one region that the sweep wants (EveryVoxel's questions, sweep_triangle.h):
// its leaves' bits, and per sweep order d the columns (a, b) and slabs a holding any.
class RegionVoxels {
public:
    // `base`: the region's first voxel; `words` of each leaf number (null: empty).
    void reset(const std::array<int, 3>& base, const std::array<const std::uint64_t*, kRegionLeaves>& words) {
        base_ = base;
        words_ = words;
        for (auto& columns : columns_) columns.fill(0);
        slabs_.fill(0);
        for (int leaf = 0; leaf < kRegionLeaves; ++leaf) {
            const std::uint64_t* w = words[std::size_t(leaf)];
            if (!w) continue;
            const std::array<int, 3> corner{8 * (leaf >> (2 * kRegionLog2)),
                                            8 * ((leaf >> kRegionLog2) & (kRegionSide - 1)),
                                            8 * (leaf & (kRegionSide - 1))};
            const std::array<std::uint64_t, 3> leaf_columns = columnsOfLeaf(w);
            for (int d = 0; d < 3; ++d) {
                const int a0 = corner[std::size_t((d + 1) % 3)], b0 = corner[std::size_t((d + 2) % 3)];
                for (std::uint64_t set = leaf_columns[std::size_t(d)]; set; set &= set - 1) {
                    const int bit = __builtin_ctzll(set);
                    const int at = (a0 + (bit >> 3)) * kRegionVoxels + b0 + (bit & 7);
                    columns_[std::size_t(d)][std::size_t(at) >> 6] |= std::uint64_t(1) << (at & 63);
                    slabs_[std::size_t(d)] |= std::uint32_t(1) << (a0 + (bit >> 3));
                }
            }
        }
    }
    bool slab(int d, int a) const { return (slabs_[std::size_t(d)] >> (a - base_[std::size_t((d + 1) % 3)])) & 1u; }
    bool column(int d, int a, int b) const {
        const int at = (a - base_[std::size_t((d + 1) % 3)]) * kRegionVoxels + (b - base_[std::size_t((d + 2) % 3)]);
        return (columns_[std::size_t(d)][std::size_t(at) >> 6] >> (at & 63)) & 1u;
    }
    bool voxel(const Voxel& v) const {
        const std::uint64_t* w = words_[std::size_t(leafOf(v))];
        const int bit = BitGrid::bitInBrick(v[0], v[1], v[2]);
        return w && ((w[bit >> 6] >> (bit & 63)) & 1u);
    }
    // The leaf number and the place in its sums of a voxel of the region.
    int leafOf(const Voxel& v) const {
        return (((v[0] - base_[0]) >> 3) << (2 * kRegionLog2)) | (((v[1] - base_[1]) >> 3) << kRegionLog2) |
            ((v[2] - base_[2]) >> 3);
    }

private:
    std::array<int, 3> base_{};
    std::array<const std::uint64_t*, kRegionLeaves> words_{};
    std::array<std::array<std::uint64_t, kRegionVoxels * kRegionVoxels / 64>, 3> columns_{};
    std::array<std::uint32_t, 3> slabs_{};
};

// One region's sums (channels, then the weight, per voxel: leaf number * 512 + the leaf's bit
// order), filled from triangles one after the other.
class RegionAccumulator {
public:
    // `sums`: kRegionLeaves * 512 * (channels + 1) zeros, the thread's, handed back zero
    // (takeMeans() clears the set voxels', the only ones written).
    RegionAccumulator(const BackendJob& job, const SurfaceValues& values, bool brute_force, std::vector<double>& sums)
        : job_(job),
          values_(values),
          brute_force_(brute_force),
          stride_(std::size_t(values.channels() + 1)),
          sums_(sums) {}

    void start(const std::array<int, 3>& lo, const std::array<int, 3>& hi,
               const std::array<const std::uint64_t*, kRegionLeaves>& words) {
        lo_ = lo;
        hi_ = hi;
        words_ = words;
        voxels_.reset(lo, words);
    }

    // Every triangle's exact pieces; then, for set voxels none reached (a touch the method's
    // test found and the clip lost to rounding), the pieces within kTouchMargin. Returns the
    // number of leaves where that fallback ran.
    template <typename Triangles>
    std::uint64_t accumulate(const Triangles& triangles) {
        for (std::uint32_t n : triangles) addTriangle(n, voxels_, 0.0);
        std::array<std::array<std::uint64_t, BitGrid::kWordsPerBrick>, kRegionLeaves> lost{};
        std::array<const std::uint64_t*, kRegionLeaves> lost_words{};
        std::uint64_t leaves_lost = 0;
        for (int leaf = 0; leaf < kRegionLeaves; ++leaf) {
            const std::uint64_t* words = words_[std::size_t(leaf)];
            if (!words) continue;
            bool any = false;
            for (int word = 0; word < BitGrid::kWordsPerBrick; ++word)
                for (std::uint64_t bits = words[word]; bits; bits &= bits - 1) {
                    const int v = 64 * word + __builtin_ctzll(bits);
                    if (weight(leaf, v) > 0) continue;
                    lost[std::size_t(leaf)][std::size_t(word)] |= std::uint64_t(1) << (v & 63);
                    any = true;
                }
            if (any) {
                lost_words[std::size_t(leaf)] = lost[std::size_t(leaf)].data();
                ++leaves_lost;
            }
        }
        if (leaves_lost > 0) {
            RegionVoxels lost_voxels;
            lost_voxels.reset(lo_, lost_words);
            for (std::uint32_t n : triangles) addTriangle(n, lost_voxels, kTouchMargin);
        }
        return leaves_lost;
    }

    // The means of leaf `leaf`'s set voxels (`words`) in bit order into `mean`, normals
    // renormalised, and their sums cleared for the next region; counts voxels still unreached.
    void takeMeans(int leaf, const std::uint64_t* words, float* mean, std::uint64_t& unreached) {
        const std::size_t channels = std::size_t(values_.channels());
        for (int word = 0; word < BitGrid::kWordsPerBrick; ++word)
            for (std::uint64_t bits = words[word]; bits; bits &= bits - 1) {
                const int v = 64 * word + __builtin_ctzll(bits);
                double* sums = voxelSums(leaf, v);
                const double w = sums[stride_ - 1];
                if (!(w > 0)) ++unreached;
                meanOfSums(values_.layout(), sums, w, mean);
                mean += channels;
                std::fill(sums, sums + stride_, 0.0);
            }
    }

    std::uint64_t pieces() const { return pieces_; }

private:
    double* voxelSums(int leaf, int bit) { return &sums_[(std::size_t(leaf) * 512 + std::size_t(bit)) * stride_]; }
    double weight(int leaf, int bit) { return voxelSums(leaf, bit)[stride_ - 1]; }

    // Inlined into each of the sweep's visits (it runs once per piece).
    [[gnu::always_inline]] void add(const TriangleFrame& frame, const Voxel& v, const ClippedPiece& piece) {
        ++pieces_;
        const double w = piece.area + kAreaEpsilon;
        double* voxel = voxelSums(voxels_.leafOf(v), BitGrid::bitInBrick(v[0], v[1], v[2]));
        values_.addWeighted(corner_values_, frame.barycentrics(piece.centroid), w, voxel);
        voxel[stride_ - 1] += w;
    }

    // The triangle's pieces in the voxels `wanted` holds, clipped to their boxes grown by
    // `margin`. cpu sweeps the triangle (sweep_triangle.h) past the slabs and columns whose
    // voxels are all unset; the reference, and the margin fallback of both, clip box by box.
    void addTriangle(std::uint32_t n, const RegionVoxels& wanted, double margin) {
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
                        if (wanted.voxel({i, j, k}) && clipTriangleToVoxel(corners, {i, j, k}, frame, piece, margin))
                            add(frame, {i, j, k}, piece);
            return;
        }
        sweepTriangle(corners, frame, r.lo, r.hi, wanted,
                      [&](const Voxel& v, const ClippedPiece& cut) { add(frame, v, cut); });
    }

    const BackendJob& job_;
    const SurfaceValues& values_;
    const bool brute_force_;
    const std::size_t stride_;
    std::vector<double>& sums_;
    std::array<int, 3> lo_{}, hi_{};
    std::array<const std::uint64_t*, kRegionLeaves> words_{};
    RegionVoxels voxels_;
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
    // The tile's means go into one block, each leaf's at its place in brick order.
    const std::size_t first = out.size();
    out.resize(first + bins.occupied.size());
    const std::size_t channels = std::size_t(values.channels());
    std::size_t floats = 0;
    for (std::size_t s = 0; s < bins.occupied.size(); ++s) {
        const std::uint64_t* words = bits.data() + bins.occupied[s] * BitGrid::kWordsPerBrick;
        std::size_t count = 0;
        for (int word = 0; word < BitGrid::kWordsPerBrick; ++word)
            count += std::size_t(__builtin_popcountll(words[word]));
        const std::array<std::int32_t, 3> at = tile_bricks.at(bins.occupied[s]);
        AttributeLeaf& leaf = out[first + s];
        leaf.brick = grid_bricks.index((offset[0] >> 3) + at[0], (offset[1] >> 3) + at[1], (offset[2] >> 3) + at[2]);
        leaf.offset = floats;
        leaf.count = count * channels;
        floats += leaf.count;
    }
    const auto block = std::make_shared<std::vector<float>>(floats);
    for (std::size_t s = 0; s < bins.occupied.size(); ++s) out[first + s].block = block;
    std::atomic<std::uint64_t> pieces{0}, unreached{0}, rounded{0};
    tbb::enumerable_thread_specific<std::vector<double>> sums_of_thread(
        std::size_t(kRegionLeaves) * 512 * std::size_t(values.channels() + 1), 0.0);
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, bins.regions.size(), 1), [&](const auto& range) {
            throwIfInterrupted(job.interrupter);
            RegionAccumulator region(job, values, brute_force, sums_of_thread.local());
            std::uint64_t local_unreached = 0, local_rounded = 0;
            for (std::size_t r = range.begin(); r != range.end(); ++r) {
                std::array<int, 3> lo, hi;
                for (std::size_t a = 0; a < 3; ++a) {
                    lo[a] = offset[a] + kRegionVoxels * bins.regions[r][a];
                    hi[a] = std::min(lo[a] + kRegionVoxels - 1, job.tile.last(int(a)));
                }
                std::array<const std::uint64_t*, kRegionLeaves> words{};
                for (std::size_t l = bins.leaves_first[r]; l != bins.leaves_first[r + 1]; ++l)
                    words[std::size_t(bins.leaves[l].number)] =
                        bits.data() + bins.occupied[bins.leaves[l].slot] * BitGrid::kWordsPerBrick;
                region.start(lo, hi, words);
                local_rounded += brute_force ? region.accumulate(AllTriangles{std::uint32_t(job.mesh.usable.size())})
                                             : region.accumulate(bins.of(r));
                for (std::size_t l = bins.leaves_first[r]; l != bins.leaves_first[r + 1]; ++l) {
                    const TileBins::Leaf& leaf = bins.leaves[l];
                    region.takeMeans(leaf.number, words[std::size_t(leaf.number)],
                                     block->data() + out[first + leaf.slot].offset, local_unreached);
                }
            }
            pieces.fetch_add(region.pieces(), std::memory_order_relaxed);
            unreached.fetch_add(local_unreached, std::memory_order_relaxed);
            rounded.fetch_add(local_rounded, std::memory_order_relaxed);
        });
    });
    return {pieces.load(), unreached.load(), rounded.load()};
}

void assembleAttributes(std::vector<AttributeLeaf>& leaves, AttributeGrid& grid, int threads) {
    std::sort(leaves.begin(), leaves.end(),
              [](const AttributeLeaf& a, const AttributeLeaf& b) { return a.brick < b.brick; });
    // Each leaf's place in the result.
    std::vector<std::size_t> start(leaves.size() + 1, 0);
    for (std::size_t n = 0; n < leaves.size(); ++n) start[n + 1] = start[n] + leaves[n].size();
    // One block with every leaf's values in brick order (the cpu method's, one tile) is the
    // result as it is.
    const bool one_block = !leaves.empty() && leaves[0].block && leaves[0].block->size() == start.back() &&
        std::all_of(leaves.begin(), leaves.end(), [&](const AttributeLeaf& leaf) {
            return leaf.block == leaves[0].block && leaf.offset == start[std::size_t(&leaf - leaves.data())];
        });
    if (one_block) {
        grid.values = std::move(*leaves[0].block);
        leaves.clear();
        return;
    }
    // Else the copies (and frees) in parallel: the values of a large grid are tens of MB.
    grid.values.clear();
    grid.values.resize(start.back());
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.size(), 64), [&](const auto& range) {
            for (std::size_t n = range.begin(); n != range.end(); ++n) {
                std::copy(leaves[n].data(), leaves[n].data() + leaves[n].size(),
                          grid.values.begin() + std::ptrdiff_t(start[n]));
                std::vector<float>().swap(leaves[n].values);
            }
        });
    });
    leaves.clear();  // the blocks go with their last leaf
}

}  // namespace hyvox::attributes
