// SPDX-License-Identifier: GPL-3.0-or-later
#include "attributes/inside_values.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "attributes/bit_count.h"
#include "attributes/tile_regions.h"
#include "core/triangle_normal.h"

namespace hyvox::attributes {
namespace {

using Int3 = std::array<std::int32_t, 3>;
using Mask = std::array<std::uint64_t, BitGrid::kWordsPerBrick>;

bool testBit(const Mask& mask, int bit) { return (mask[std::size_t(bit >> 6)] >> (bit & 63)) & 1u; }
void setBit(Mask& mask, int bit) { mask[std::size_t(bit >> 6)] |= std::uint64_t(1) << (bit & 63); }

// The 27 bricks around a brick (itself in the middle), numbered (dx+1)*9 + (dy+1)*3 + (dz+1).
int nearIndex(int dx, int dy, int dz) { return (dx + 1) * 9 + (dy + 1) * 3 + (dz + 1); }

// The bricks whose voxels have values one by one, in brick order (the order of
// AttributeGrid::values): their set voxels, those valued so far, and the values.
struct LeafVoxels {
    BrickLayout layout;
    std::vector<std::uint64_t> brick;
    std::vector<Int3> at;
    std::vector<Mask> set, valued;
    std::vector<std::array<std::uint32_t, BitGrid::kWordsPerBrick>> before;  // set voxels in the words before
    std::vector<std::size_t> first;                                          // voxel number of the first
    std::vector<std::array<std::int32_t, 27>> near;                          // the 27 bricks around, index here or -1
    std::vector<float> values;                                               // channels per set voxel
    std::size_t channels = 0;

    std::int64_t find(std::uint64_t b) const {
        const auto it = std::lower_bound(brick.begin(), brick.end(), b);
        return it != brick.end() && *it == b ? std::int64_t(it - brick.begin()) : -1;
    }
    std::size_t offset(std::size_t n, int bit) const {
        const std::uint64_t word = set[n][std::size_t(bit >> 6)];
        return (first[n] + before[n][std::size_t(bit >> 6)] + std::size_t(popcountBelow(word, bit))) * channels;
    }
    float* value(std::size_t n, int bit) { return values.data() + offset(n, bit); }
    const float* value(std::size_t n, int bit) const { return values.data() + offset(n, bit); }
    std::uint64_t pending(std::size_t n) const {
        std::uint64_t count = 0;
        for (int w = 0; w < BitGrid::kWordsPerBrick; ++w)
            count += std::uint64_t(popcount(set[n][std::size_t(w)] & ~valued[n][std::size_t(w)]));
        return count;
    }
};

// The regions' values (in the AttributeTile each will become) and the layer that gave them.
struct RegionValues {
    std::vector<AttributeTile> tiles;
    std::vector<std::int32_t> layer;  // -1: none yet
};

// The 26-neighbourhood dilation of a brick's mask, one axis at a time (a 3x3x3 box is the
// product of three 3-taps): along z (bit z of each 8-bit row; the rows' ends from the bricks
// before and after), along y (rows of a word), along x (words). `before`/`after`: the masks of
// the bricks before and after along that axis.
constexpr std::uint64_t kRowStart = 0x0101010101010101ull, kRowEnd = 0x8080808080808080ull;
Mask dilateZ(const Mask& m, const Mask& before, const Mask& after) {
    Mask out;
    for (std::size_t x = 0; x < 8; ++x)
        out[x] = m[x] | ((m[x] << 1) & ~kRowStart) | ((m[x] >> 1) & ~kRowEnd) | ((before[x] >> 7) & kRowStart) |
            ((after[x] << 7) & kRowEnd);
    return out;
}
Mask dilateY(const Mask& m, const Mask& before, const Mask& after) {
    Mask out;
    for (std::size_t x = 0; x < 8; ++x)
        out[x] = m[x] | (m[x] << 8) | (m[x] >> 8) | (before[x] >> 56) | (after[x] << 56);
    return out;
}
Mask dilateX(const Mask& m, const Mask& before, const Mask& after) {
    Mask out;
    for (std::size_t x = 0; x < 8; ++x) out[x] = m[x] | (x > 0 ? m[x - 1] : before[7]) | (x < 7 ? m[x + 1] : after[0]);
    return out;
}

// For each voxel of a brick, its 26 neighbours in (dx, dy, dz) order: the brick around
// (nearIndex) and the bit in it. Made once.
struct NeighbourTable {
    struct Step {
        std::uint8_t brick;
        std::uint16_t bit;
    };
    std::array<std::array<Step, 26>, 512> steps;
};
const NeighbourTable& neighbourTable() {
    static const NeighbourTable table = [] {
        NeighbourTable t{};
        for (int bit = 0; bit < 512; ++bit) {
            const int x = bit >> 6, y = (bit >> 3) & 7, z = bit & 7;
            int m = 0;
            for (int dx = -1; dx <= 1; ++dx)
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dz = -1; dz <= 1; ++dz) {
                        if (dx == 0 && dy == 0 && dz == 0) continue;
                        const int nx = x + dx, ny = y + dy, nz = z + dz;
                        const int ox = nx < 0 ? -1
                            : nx > 7          ? 1
                                              : 0,
                                  oy = ny < 0 ? -1
                            : ny > 7          ? 1
                                              : 0,
                                  oz = nz < 0 ? -1
                            : nz > 7          ? 1
                                              : 0;
                        t.steps[std::size_t(bit)][std::size_t(m++)] = {
                            std::uint8_t(nearIndex(ox, oy, oz)),
                            std::uint16_t(((nx & 7) << 6) | ((ny & 7) << 3) | (nz & 7))};
                    }
        }
        return t;
    }();
    return table;
}

// Leaf layers from the voxels valued so far until no pending voxel gains a value; with
// `regions`, a valued region's voxels count as valued neighbours. Each layer finds its voxels
// as the pending ones under the dilation of the valued ones, so a voxel is averaged once.
// Returns {layers, voxels}.
std::pair<std::uint64_t, std::uint64_t> leafLayers(LeafVoxels& leaf, const AttributeGrid& layout,
                                                   const TileRegions* regions, const RegionValues* region_values,
                                                   tbb::task_arena& arena) {
    const int channels = int(leaf.channels);
    const std::size_t bricks = leaf.brick.size();
    static const Mask kNone{}, kAll{~0ull, ~0ull, ~0ull, ~0ull, ~0ull, ~0ull, ~0ull, ~0ull};
    // The bricks around each that are valued regions (their voxels all valued), as bits by nearIndex.
    std::vector<std::uint32_t> region_around(bricks, 0);
    if (regions)
        arena.execute([&] {
            tbb::parallel_for(std::size_t(0), bricks, [&](std::size_t n) {
                for (int k = 0; k < 27; ++k) {
                    if (leaf.near[n][std::size_t(k)] >= 0) continue;
                    const std::int64_t r = regions->at(leaf.at[n][0] + k / 9 - 1, leaf.at[n][1] + (k / 3) % 3 - 1,
                                                       leaf.at[n][2] + k % 3 - 1);
                    if (r >= 0 && region_values->layer[std::size_t(r)] >= 0) region_around[n] |= 1u << k;
                }
            });
        });
    auto around = [&](const std::vector<Mask>& masks, std::size_t n, int dx, int dy, int dz) -> const Mask& {
        const int k = nearIndex(dx, dy, dz);
        const std::int32_t other = leaf.near[n][std::size_t(k)];
        if (other >= 0) return masks[std::size_t(other)];
        return (region_around[n] >> k) & 1u ? kAll : kNone;
    };
    std::vector<std::uint32_t> pending;  // bricks with set voxels not valued yet
    for (std::size_t n = 0; n < bricks; ++n)
        if (leaf.pending(n)) pending.push_back(std::uint32_t(n));
    const NeighbourTable& table = neighbourTable();
    std::uint64_t layers = 0, voxels = 0;
    while (!pending.empty()) {
        // This layer's voxels, written in place (no read sees them: reads take valued voxels
        // only, and `valued` changes after the layer).
        std::vector<Mask> fresh(pending.size());
        arena.execute([&] {
            tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pending.size(), 16), [&](const auto& range) {
                for (std::size_t a = range.begin(); a != range.end(); ++a) {
                    const std::size_t n = pending[a];
                    const Int3& at = leaf.at[n];
                    // The valued voxels' dilation over the 27 bricks around: along z in each of
                    // the 9 columns, along y in each of the 3 slabs, then along x. (All from this
                    // brick's own neighbourhood: a brick between two leaves need not be a leaf.)
                    Mask slab[3];
                    for (int dx = -1; dx <= 1; ++dx) {
                        Mask column[3];
                        for (int dy = -1; dy <= 1; ++dy)
                            column[dy + 1] =
                                dilateZ(around(leaf.valued, n, dx, dy, 0), around(leaf.valued, n, dx, dy, -1),
                                        around(leaf.valued, n, dx, dy, 1));
                        slab[dx + 1] = dilateY(column[1], column[0], column[2]);
                    }
                    const Mask reach = dilateX(slab[1], slab[0], slab[2]);
                    for (int w = 0; w < BitGrid::kWordsPerBrick; ++w) {
                        const std::uint64_t word_fresh =
                            leaf.set[n][std::size_t(w)] & ~leaf.valued[n][std::size_t(w)] & reach[std::size_t(w)];
                        fresh[a][std::size_t(w)] = word_fresh;
                        for (std::uint64_t word = word_fresh; word; word &= word - 1) {
                            const int bit = w * 64 + __builtin_ctzll(word);
                            double sums[kMaxChannels] = {};
                            int count = 0;
                            auto add = [&](const float* value) {
                                for (int c = 0; c < channels; ++c) sums[c] += double(value[c]);
                                ++count;
                            };
                            for (const NeighbourTable::Step& step : table.steps[std::size_t(bit)]) {
                                const std::int32_t other = leaf.near[n][step.brick];
                                if (other >= 0) {
                                    if (testBit(leaf.valued[std::size_t(other)], step.bit))
                                        add(leaf.value(std::size_t(other), step.bit));
                                } else if ((region_around[n] >> step.brick) & 1u) {
                                    add(region_values
                                            ->tiles[std::size_t(regions->at(at[0] + step.brick / 9 - 1,
                                                                            at[1] + (step.brick / 3) % 3 - 1,
                                                                            at[2] + step.brick % 3 - 1))]
                                            .values.data());
                                }
                            }
                            meanOfSums(layout, sums, double(count), leaf.value(n, bit));
                        }
                    }
                }
            });
        });
        std::uint64_t gained = 0;
        for (std::size_t a = 0; a < pending.size(); ++a)
            for (int w = 0; w < BitGrid::kWordsPerBrick; ++w) {
                leaf.valued[pending[a]][std::size_t(w)] |= fresh[a][std::size_t(w)];
                gained += std::uint64_t(popcount(fresh[a][std::size_t(w)]));
            }
        if (gained == 0) break;
        ++layers;
        voxels += gained;
        pending.erase(std::remove_if(pending.begin(), pending.end(), [&](std::uint32_t n) { return !leaf.pending(n); }),
                      pending.end());
    }
    return {layers, voxels};
}

// What leaf brick `n`'s valued voxels add to a region's shell mean: their values summed and counted.
struct ShellContribution {
    std::int64_t region;
    std::uint32_t count;
    std::array<double, kMaxChannels> sums;
};

// The contributions of brick `n` to the regions it touches (by a face, edge or corner), in
// region order, into `found`.
void shellContributions(const LeafVoxels& leaf, const TileRegions& regions, std::size_t n,
                        std::vector<ShellContribution>& found) {
    found.clear();
    const Int3& at = leaf.at[n];
    std::int64_t touching[26];
    int count = 0;
    for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dz = -1; dz <= 1; ++dz) {
                if (dx == 0 && dy == 0 && dz == 0) continue;
                const std::int64_t r = regions.at(at[0] + dx, at[1] + dy, at[2] + dz);
                if (r >= 0) touching[count++] = r;
            }
    std::sort(touching, touching + count);
    count = int(std::unique(touching, touching + count) - touching);
    for (int t = 0; t < count; ++t) {
        const TileRegions::Region& region = regions.regions()[std::size_t(touching[t])];
        ShellContribution c{touching[t], 0, {}};
        // The brick's voxels within one voxel of the region's box: a face, edge or corner.
        int lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::max(region.lo[a] * 8 - 1 - at[a] * 8, 0);
            hi[a] = std::min((region.lo[a] + region.side) * 8 - at[a] * 8, 7);
        }
        for (int x = lo[0]; x <= hi[0]; ++x)
            for (int y = lo[1]; y <= hi[1]; ++y)
                for (int z = lo[2]; z <= hi[2]; ++z) {
                    const int bit = (x << 6) | (y << 3) | z;
                    if (!testBit(leaf.valued[n], bit)) continue;
                    const float* value = leaf.value(n, bit);
                    for (std::size_t ch = 0; ch < leaf.channels; ++ch) c.sums[ch] += double(value[ch]);
                    ++c.count;
                }
        if (c.count) found.push_back(c);
    }
}

// Region layer 0: each region's shell mean over the valued leaf voxels. The bricks'
// contributions are found in parallel and added to their regions' sums in brick order (the
// sums do not depend on threads), a window of bricks at a time: memory for one window's
// contributions, not for every brick's.
void shellValues(const LeafVoxels& leaf, const AttributeGrid& layout, const TileRegions& regions, RegionValues& out,
                 tbb::task_arena& arena) {
    const std::size_t channels = leaf.channels, bricks = leaf.brick.size();
    std::vector<double> sums(regions.regions().size() * channels, 0.0);
    std::vector<std::uint64_t> counts(regions.regions().size(), 0);
    constexpr std::size_t kWindow = 16384;
    std::vector<std::vector<ShellContribution>> per_brick(std::min(bricks, kWindow));
    for (std::size_t begin = 0; begin < bricks; begin += kWindow) {
        const std::size_t end = std::min(bricks, begin + kWindow);
        arena.execute([&] {
            tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, 64), [&](const auto& range) {
                for (std::size_t n = range.begin(); n != range.end(); ++n)
                    shellContributions(leaf, regions, n, per_brick[n - begin]);
            });
        });
        for (std::size_t n = begin; n != end; ++n)
            for (const ShellContribution& c : per_brick[n - begin]) {
                double* to = sums.data() + std::size_t(c.region) * channels;
                for (std::size_t ch = 0; ch < channels; ++ch) to[ch] += c.sums[ch];
                counts[std::size_t(c.region)] += c.count;
            }
    }
    for (std::size_t r = 0; r < counts.size(); ++r) {
        if (counts[r] == 0) continue;
        meanOfSums(layout, sums.data() + r * channels, double(counts[r]), out.tiles[r].values.data());
        out.layer[r] = 0;
    }
}

// Region layers after layer 0; returns how many valued something.
std::uint64_t regionLayers(const AttributeGrid& layout, const TileRegions& regions, RegionValues& out,
                           tbb::task_arena& arena) {
    const int channels = layout.channels();
    std::vector<std::int64_t> frontier;
    for (std::size_t r = 0; r < out.layer.size(); ++r)
        if (out.layer[r] == 0) frontier.push_back(std::int64_t(r));
    std::uint64_t layers = 0;
    while (!frontier.empty()) {
        std::vector<std::vector<std::int64_t>> found(frontier.size());
        arena.execute([&] {
            tbb::parallel_for(std::size_t(0), frontier.size(), [&](std::size_t f) {
                for (std::int64_t r : regions.neighbours(frontier[f]))
                    if (out.layer[std::size_t(r)] < 0) found[f].push_back(r);
            });
        });
        std::vector<std::int64_t> candidates;
        for (const auto& list : found) candidates.insert(candidates.end(), list.begin(), list.end());
        std::sort(candidates.begin(), candidates.end());
        candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
        if (candidates.empty()) break;
        std::vector<std::array<float, kMaxChannels>> value(candidates.size());
        arena.execute([&] {
            tbb::parallel_for(std::size_t(0), candidates.size(), [&](std::size_t c) {
                double sums[kMaxChannels] = {};
                int count = 0;
                for (std::int64_t r : regions.neighbours(candidates[c])) {
                    if (out.layer[std::size_t(r)] < 0) continue;
                    for (int ch = 0; ch < channels; ++ch)
                        sums[ch] += double(out.tiles[std::size_t(r)].values[std::size_t(ch)]);
                    ++count;
                }
                meanOfSums(layout, sums, double(count), value[c].data());
            });
        });
        ++layers;
        for (std::size_t c = 0; c < candidates.size(); ++c) {
            out.tiles[std::size_t(candidates[c])].values = value[c];
            out.layer[std::size_t(candidates[c])] = std::int32_t(layers);
        }
        frontier.swap(candidates);
    }
    return layers;
}

std::vector<ValuedBrick> surfaceBricks(const SparseGrid& surface, const AttributeGrid& surface_values) {
    const std::vector<ValuedBrick> bricks = valuedBricks(surface, surface_values);
    std::size_t total = 0;
    for (const ValuedBrick& b : bricks)
        for (int w = 0; w < BitGrid::kWordsPerBrick; ++w) total += std::size_t(popcount(b.mask[w]));
    if (total * std::size_t(surface_values.channels()) != surface_values.values.size())
        throw std::logic_error("valueInside: the surface values do not match the surface voxels");
    return bricks;
}

}  // namespace

AttributeGrid valueInside(const SparseGrid& surface, const AttributeGrid& surface_values, const SparseGrid& solid,
                          const std::vector<float>& mesh_mean, int threads, InsideValueCounts& counts) {
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    AttributeGrid out;
    out.color = surface_values.color;
    out.alpha = surface_values.alpha;
    out.normal = surface_values.normal;
    const std::size_t channels = std::size_t(out.channels());
    const std::vector<ValuedBrick> from = surfaceBricks(surface, surface_values);

    // Whole bricks of the solid that hold surface voxels keep their voxels' values.
    for (const ValuedBrick& b : from)
        if (solid.inTile(b.brick)) out.valued_tile_bricks.push_back(b.brick);

    LeafVoxels leaf;
    leaf.layout = solid.bricks();
    leaf.channels = channels;
    const std::vector<ValuedBrick> solid_bricks = valuedBricks(solid, out);
    // Reserved exactly: a solid's leaves at 2048 and above number hundreds of thousands.
    leaf.brick.reserve(solid_bricks.size());
    leaf.at.reserve(solid_bricks.size());
    leaf.set.reserve(solid_bricks.size());
    leaf.before.reserve(solid_bricks.size());
    leaf.first.reserve(solid_bricks.size());
    for (const ValuedBrick& b : solid_bricks) {
        leaf.brick.push_back(b.brick);
        leaf.at.push_back(leaf.layout.at(b.brick));
        Mask mask;
        std::array<std::uint32_t, BitGrid::kWordsPerBrick> before{};
        std::uint32_t running = 0;
        for (int w = 0; w < BitGrid::kWordsPerBrick; ++w) {
            mask[std::size_t(w)] = b.mask[w];
            before[std::size_t(w)] = running;
            running += std::uint32_t(popcount(b.mask[w]));
        }
        leaf.set.push_back(mask);
        leaf.before.push_back(before);
        leaf.first.push_back(b.first);
    }
    const std::size_t bricks = leaf.brick.size();
    leaf.valued.assign(bricks, Mask{});
    leaf.near.resize(bricks);
    std::size_t total = 0;
    for (std::size_t n = 0; n < bricks; ++n)
        for (std::uint64_t word : leaf.set[n]) total += std::size_t(popcount(word));
    leaf.values.assign(total * channels, 0.0f);
    arena.execute([&] {
        // The bricks around each, one direction at a time: the bricks `at + offset` come in
        // ascending order as `at` does, so one walk along the sorted bricks finds them all.
        tbb::parallel_for(0, 27, [&](int k) {
            const int offset[3] = {k / 9 - 1, (k / 3) % 3 - 1, k % 3 - 1};
            std::size_t m = 0;
            for (std::size_t n = 0; n < bricks; ++n) {
                const Int3& at = leaf.at[n];
                const int x = at[0] + offset[0], y = at[1] + offset[1], z = at[2] + offset[2];
                std::int32_t found = -1;
                if (x >= 0 && y >= 0 && z >= 0 && x < leaf.layout.counts[0] && y < leaf.layout.counts[1] &&
                    z < leaf.layout.counts[2]) {
                    const std::uint64_t b = leaf.layout.index(x, y, z);
                    while (m < bricks && leaf.brick[m] < b) ++m;
                    if (m < bricks && leaf.brick[m] == b) found = std::int32_t(m);
                }
                leaf.near[n][std::size_t(k)] = found;
            }
        });
        // Layer 0: the surface voxels' own values.
        tbb::parallel_for(std::size_t(0), from.size(), [&](std::size_t s) {
            const ValuedBrick& b = from[s];
            const std::int64_t n = leaf.find(b.brick);
            if (n < 0) throw std::logic_error("valueInside: a surface brick is not in the solid");
            std::size_t voxel = b.first;
            for (int w = 0; w < BitGrid::kWordsPerBrick; ++w) {
                std::uint64_t word = b.mask[w];
                while (word) {
                    const int bit = w * 64 + __builtin_ctzll(word);
                    word &= word - 1;
                    if (!testBit(leaf.set[std::size_t(n)], bit))
                        throw std::logic_error("valueInside: a surface voxel is not in the solid");
                    const float* value = surface_values.values.data() + voxel++ * channels;
                    std::copy(value, value + channels, leaf.value(std::size_t(n), bit));
                    setBit(leaf.valued[std::size_t(n)], bit);
                }
            }
        });
    });

    const auto [layers, voxels] = leafLayers(leaf, out, nullptr, nullptr, arena);
    counts.layers = layers;
    counts.voxels = voxels;

    const TileRegions regions(solid, out.valued_tile_bricks);
    RegionValues region_values;
    region_values.tiles.resize(regions.regions().size());
    region_values.layer.assign(regions.regions().size(), -1);
    for (std::size_t r = 0; r < regions.regions().size(); ++r) {
        const TileRegions::Region& region = regions.regions()[r];
        AttributeTile& tile = region_values.tiles[r];
        for (int a = 0; a < 3; ++a) tile.origin[a] = region.lo[a] * BrickLayout::kSide;
        tile.level = region.level;
    }
    counts.regions = regions.regions().size();
    shellValues(leaf, out, regions, region_values, arena);
    counts.region_layers = regionLayers(out, regions, region_values, arena);

    // Leaf voxels the surface could not reach through leaves: on from the regions.
    bool pending = false;
    for (std::size_t n = 0; n < bricks && !pending; ++n) pending = leaf.pending(n) != 0;
    if (pending) {
        const auto through = leafLayers(leaf, out, &regions, &region_values, arena);
        counts.through_regions = through.second;
        counts.layers += through.first;
    }
    // Still nothing: the mesh's mean.
    for (std::size_t n = 0; n < bricks; ++n) {
        if (!leaf.pending(n)) continue;
        for (int bit = 0; bit < 512; ++bit)
            if (testBit(leaf.set[n], bit) && !testBit(leaf.valued[n], bit)) {
                std::copy(mesh_mean.begin(), mesh_mean.end(), leaf.value(n, bit));
                setBit(leaf.valued[n], bit);
                ++counts.fallback;
            }
    }
    for (std::size_t r = 0; r < region_values.layer.size(); ++r)
        if (region_values.layer[r] < 0) {
            std::copy(mesh_mean.begin(), mesh_mean.end(), region_values.tiles[r].values.begin());
            ++counts.fallback;
        }
    out.values = std::move(leaf.values);
    out.tiles = std::move(region_values.tiles);
    return out;
}

std::vector<float> meshMeanValue(const ValidatedMesh& mesh, const SurfaceValues& values) {
    const int channels = values.channels();
    double sums[kMaxChannels] = {};
    double area = 0;
    for (std::uint32_t t : mesh.usable) {
        Corner3 corner[3];
        for (int k = 0; k < 3; ++k) {
            const auto p = mesh.vertex(t, k);
            corner[k] = {double(p[0]), double(p[1]), double(p[2])};
        }
        const Corner3 normal = stableTriangleNormal(corner[0], corner[1], corner[2]);
        const double length = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
        if (!(length > 0)) continue;
        const std::array<double, 3> unit{normal[0] / length, normal[1] / length, normal[2] / length};
        double value[kMaxChannels];
        values.evaluate(t, {1.0 / 3, 1.0 / 3, 1.0 / 3}, unit, value);
        for (int c = 0; c < channels; ++c) sums[c] += 0.5 * length * value[c];
        area += 0.5 * length;
    }
    std::vector<float> mean(std::size_t(channels), 0.0f);
    meanOfSums(values.layout(), sums, area, mean.data());
    return mean;
}

}  // namespace hyvox::attributes
