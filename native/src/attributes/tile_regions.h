// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A solid's tile bricks as the regions its attribute grids hold one value each
// (attributes/inside_values.h), found by brick in O(1).
#include <array>
#include <cstdint>
#include <vector>

#include "attributes/bit_count.h"
#include "hyvox/sparse_grid.h"

namespace hyvox::attributes {

// The tile bricks grouped as OpenVDB's prune() groups the density's tiles: a 128³ node (16³
// bricks) whose bricks are all tiles is one region, a 4096³ node whose 128³ nodes all are is
// one; every other tile brick is a region of its own. Looked up per brick in O(1): a table of
// the grid's 128³ nodes, each with a mask of its tile bricks.
class TileRegions {
public:
    struct Region {
        std::array<std::int32_t, 3> lo;  // first brick
        std::int32_t side;               // bricks: 1, 16 or 512
        int level;                       // 1, 2, 3
    };

    // The tile bricks of `solid` (finished) but `valued_tile_bricks` (sorted).
    TileRegions(const SparseGrid& solid, const std::vector<std::uint64_t>& valued_tile_bricks);

    const std::vector<Region>& regions() const { return regions_; }

    // The region holding brick (bx, by, bz), -1 when none (not a tile, or outside the grid).
    std::int64_t at(std::int32_t bx, std::int32_t by, std::int32_t bz) const {
        if (bx < 0 || by < 0 || bz < 0 || bx >= bricks_.counts[0] || by >= bricks_.counts[1] || bz >= bricks_.counts[2])
            return -1;
        const std::int32_t slot = node_of_[nodeIndex(bx / kNodeBricks, by / kNodeBricks, bz / kNodeBricks)];
        if (slot < 0) return -1;
        const Node& node = node_[std::size_t(slot)];
        if (node.whole) return node.base;
        const int bit = slotInNode({bx, by, bz});
        const std::uint64_t word = node.mask[std::size_t(bit >> 6)];
        if (!((word >> (bit & 63)) & 1u)) return -1;
        return node.base + std::int64_t(node.before[std::size_t(bit >> 6)]) + popcountBelow(word, bit);
    }

    // The regions touching region r (by a face, edge or corner), ascending.
    std::vector<std::int64_t> neighbours(std::int64_t r) const;

private:
    static constexpr int kNodeBricks = 16;  // a 128³ node's side in bricks
    static constexpr int kTopNodes = 32;    // a 4096³ node's side in 128³ nodes
    static constexpr int kNodeWords = kNodeBricks * kNodeBricks * kNodeBricks / 64;
    struct Node {
        std::array<std::uint64_t, kNodeWords> mask{};    // its tile bricks, slot (x*16 + y)*16 + z
        std::array<std::uint32_t, kNodeWords> before{};  // tile bricks in the words before
        bool whole = false;
        std::int64_t base = 0;  // its first region (or its region, when whole)
    };

    std::size_t nodeIndex(std::int32_t nx, std::int32_t ny, std::int32_t nz) const {
        return (std::size_t(nx) * std::size_t(nodes_[1]) + std::size_t(ny)) * std::size_t(nodes_[2]) + std::size_t(nz);
    }
    static int slotInNode(const std::array<std::int32_t, 3>& at) {
        return ((at[0] % kNodeBricks) << 8) | ((at[1] % kNodeBricks) << 4) | (at[2] % kNodeBricks);
    }
    std::uint64_t topKey(const std::array<std::int32_t, 3>& n) const {
        const std::uint64_t tops_y = std::uint64_t(nodes_[1] / kTopNodes + 1),
                            tops_z = std::uint64_t(nodes_[2] / kTopNodes + 1);
        return (std::uint64_t(n[0] / kTopNodes) * tops_y + std::uint64_t(n[1] / kTopNodes)) * tops_z +
            std::uint64_t(n[2] / kTopNodes);
    }
    template <typename F>
    void forEachNode(F&& f) {
        for (std::int32_t x = 0; x < nodes_[0]; ++x)
            for (std::int32_t y = 0; y < nodes_[1]; ++y)
                for (std::int32_t z = 0; z < nodes_[2]; ++z) {
                    const std::int32_t slot = node_of_[nodeIndex(x, y, z)];
                    if (slot >= 0) f(std::array<std::int32_t, 3>{x, y, z}, node_[std::size_t(slot)]);
                }
    }

    BrickLayout bricks_;
    std::array<std::int32_t, 3> nodes_{};
    std::vector<std::int32_t> node_of_;  // per 128³ node of the grid: index into node_, -1 = no tile brick
    std::vector<Node> node_;
    std::vector<Region> regions_;
};

}  // namespace hyvox::attributes
