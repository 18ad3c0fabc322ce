// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The voxels of a grid, held only where they are: 8³ leaves in OpenVDB's leaf-mask layout
// (the bit layout of hyvox/bit_grid.h), one per non-empty brick, sorted by brick index.
// Memory follows the surface, not the box: a 16384³ grid of a plane holds its plane's leaves.
//
// Filled tile by tile (addTile, then finish): every method voxelizes one brick-aligned box of
// the grid at a time into a dense BitGrid, whose non-empty bricks are then copied here as
// leaves. Tiles do not overlap, so each leaf comes from exactly one tile.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hyvox/bit_grid.h"
#include "hyvox/grid.h"

namespace hyvox {

class SparseGrid {
public:
    struct Leaf {
        std::uint64_t brick;                                // BrickLayout::index of the whole grid
        std::uint64_t words[BitGrid::kWordsPerBrick];       // OpenVDB NodeMask<3> words
    };
    static constexpr std::size_t kLeafBytes = sizeof(Leaf);

    SparseGrid() = default;
    explicit SparseGrid(std::array<std::int32_t, 3> dims);
    static SparseGrid fromBitGrid(const BitGrid& dense);

    const std::array<std::int32_t, 3>& dims() const { return dims_; }
    const BrickLayout& bricks() const { return bricks_; }
    const std::vector<Leaf>& leaves() const { return leaves_; }
    std::size_t leafCount() const { return leaves_.size(); }
    std::size_t byteSize() const { return leaves_.capacity() * kLeafBytes; }

    // Copies the non-empty bricks of `tile`, whose voxel (0,0,0) is voxel `offset` of this grid
    // (a multiple of 8 on every axis; the tile must lie inside the grid, bricks padded past
    // the grid's edge excepted). Tiles added must not overlap.
    void addTile(const BitGrid& tile, const std::array<std::int32_t, 3>& offset);
    // Puts the leaves in brick order after the last addTile(); test(), set() and == need it.
    void finish();

    bool inside(int i, int j, int k) const {
        return i >= 0 && j >= 0 && k >= 0 && i < dims_[0] && j < dims_[1] && k < dims_[2];
    }
    bool test(int i, int j, int k) const;
    void set(int i, int j, int k);  // one voxel (tests, small edits): inserts its leaf if needed

    std::uint64_t count() const;
    // (i,j,k) of every set voxel, leaf by leaf in brick order.
    std::vector<std::array<std::int32_t, 3>> coords() const;
    // The same voxels as a dense grid (for small grids: it allocates the whole box).
    BitGrid toBitGrid() const;

    bool operator==(const SparseGrid& other) const;
    bool operator!=(const SparseGrid& other) const { return !(*this == other); }

private:
    const Leaf* find(std::uint64_t brick) const;
    void requireFinished() const;

    std::array<std::int32_t, 3> dims_{0, 0, 0};
    BrickLayout bricks_;
    std::vector<Leaf> leaves_;  // sorted by brick once finished
    bool sorted_ = true;
};

}  // namespace hyvox
