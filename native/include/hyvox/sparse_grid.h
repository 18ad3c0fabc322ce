// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// The voxels of a grid, held only where they are: 8³ leaves in OpenVDB's leaf-mask layout
/// (the bit layout of hyvox/bit_grid.h), one per non-empty brick, sorted by brick index.
/// Memory follows the surface, not the box: a 16384³ grid of a plane holds its plane's leaves.
///
/// Filled tile by tile (addTile, then finish): every method voxelizes one brick-aligned box of
/// the grid at a time into a dense BitGrid, whose non-empty bricks are then copied here as
/// leaves. Tiles do not overlap, so each leaf comes from exactly one tile.
///
/// Wholly set bricks (a solid's interior) are not leaves but active tiles: runs of brick
/// indices [begin, end), 16 bytes a run, as OpenVDB holds a whole leaf as one tile value
/// (a level-1 tile). finish() turns every full leaf that lies wholly inside the grid into a
/// tile and drops leaves that a tile covers, so two grids with the same voxels compare equal
/// whatever way their voxels were added. Tile voxels are voxels like any other: count(),
/// test(), coords() and toBitGrid() include them (coords() lists each of their 512 voxels).
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hyvox/bit_grid.h"
#include "hyvox/grid.h"

namespace hyvox {

/// The voxels of a grid as leaves and tiles (above). Reads of a finished grid are
/// thread-safe; every change (addTile, set, finish, ...) needs the grid to itself.
class SparseGrid {
public:
    /// One non-empty, not wholly set brick.
    struct Leaf {
        std::uint64_t brick;                           ///< BrickLayout::index of the whole grid
        std::uint64_t words[BitGrid::kWordsPerBrick];  ///< OpenVDB NodeMask<3> words
    };
    static constexpr std::size_t kLeafBytes = sizeof(Leaf);  ///< memory of one leaf
    /// Consecutive wholly set bricks.
    struct TileRun {
        std::uint64_t begin;  ///< the first brick (BrickLayout index), all 512 voxels set
        std::uint64_t end;    ///< one past the last brick
    };

    SparseGrid() = default;
    /// An empty grid of `dims` voxels.
    explicit SparseGrid(std::array<std::int32_t, 3> dims);
    /// The voxels of a dense grid (finished).
    static SparseGrid fromBitGrid(const BitGrid& dense);

    const std::array<std::int32_t, 3>& dims() const { return dims_; }  ///< voxels along x, y, z
    const BrickLayout& bricks() const { return bricks_; }              ///< the bricks over dims
    const std::vector<Leaf>& leaves() const { return leaves_; }        ///< in brick order once finished
    std::size_t leafCount() const { return leaves_.size(); }           ///< leaves held
    const std::vector<TileRun>& tileRuns() const { return tiles_; }    ///< sorted, disjoint, not adjacent
    std::uint64_t tileCount() const;                                   ///< bricks held as tiles
    /// Memory of the leaves and tiles, bytes.
    std::size_t byteSize() const { return leaves_.capacity() * kLeafBytes + tiles_.capacity() * sizeof(TileRun); }

    /// Copies the non-empty bricks of `tile`, whose voxel (0,0,0) is voxel `offset` of this grid
    /// (a multiple of 8 on every axis; the tile must lie inside the grid, bricks padded past
    /// the grid's edge excepted). Tiles added must not overlap.
    void addTile(const BitGrid& tile, const std::array<std::int32_t, 3>& offset);
    /// Adds the voxels of `more` (same dims, finished) to these (solid mode: the inside to the
    /// surface). Overlaps are fine: the result is the union.
    void merge(const SparseGrid& more);
    /// Sets every voxel of bricks [begin, end), which must lie wholly inside the grid.
    void addTileRun(std::uint64_t begin, std::uint64_t end);
    /// Adds one leaf (brick index and words); it may overlap what is there (finish() ORs them).
    void addLeaf(const Leaf& leaf);
    /// Puts the leaves in brick order after the last addTile(); test(), set() and == need it.
    /// Also ORs leaves of the same brick together and makes full leaves tiles (see above).
    void finish();
    /// Whether brick (bx,by,bz) lies wholly inside the grid (only those may be tiles).
    bool brickWhole(std::uint64_t brick) const;
    /// Whether the (finished) grid holds `brick` as part of a tile.
    bool inTile(std::uint64_t brick) const;

    /// Whether voxel (i,j,k) lies inside dims.
    bool inside(int i, int j, int k) const {
        return i >= 0 && j >= 0 && k >= 0 && i < dims_[0] && j < dims_[1] && k < dims_[2];
    }
    /// Whether voxel (i,j,k) (inside dims) is set; the grid must be finished.
    bool test(int i, int j, int k) const;
    /// The words of `brick` (finished): its leaf's, all set for a tile, none for an empty brick.
    void brickWords(std::uint64_t brick, std::uint64_t out[BitGrid::kWordsPerBrick]) const;
    void set(int i, int j, int k);  ///< one voxel (tests, small edits): inserts its leaf if needed

    /// The number of set voxels, tiles included.
    std::uint64_t count() const;
    /// (i,j,k) of every set voxel, leaf by leaf in brick order.
    std::vector<std::array<std::int32_t, 3>> coords() const;
    /// The same voxels as a dense grid (for small grids: it allocates the whole box).
    BitGrid toBitGrid() const;

    /// The same dims and the same voxels (both finished).
    bool operator==(const SparseGrid& other) const;
    /// Not operator==.
    bool operator!=(const SparseGrid& other) const { return !(*this == other); }

private:
    const Leaf* find(std::uint64_t brick) const;
    void requireFinished() const;

    std::array<std::int32_t, 3> dims_{0, 0, 0};
    BrickLayout bricks_;
    std::vector<Leaf> leaves_;    // sorted by brick once finished
    std::vector<TileRun> tiles_;  // sorted and merged once finished
    bool sorted_ = true;
};

}  // namespace hyvox
