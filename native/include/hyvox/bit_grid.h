// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// One bit per voxel, laid out as OpenVDB leaf masks so a non-empty 8×8×8 brick converts
/// to a LeafNode<bool/float,3> value mask with a plain copy:
///   brick (bx,by,bz) = (i>>3, j>>3, k>>3), stored at BrickLayout::index = (bx*bricks_y + by)*bricks_z + bz;
///   inside a brick, bit n = (i&7)<<6 | (j&7)<<3 | (k&7) (OpenVDB's LeafNode::coordToOffset),
///   held in 64-bit word n>>6 at bit n&63 (OpenVDB's NodeMask<3> word layout).
/// On a little-endian machine the same memory read as uint32 words puts bit n in word n>>5 at
/// bit n&31, which is the layout the GL shaders use in their SSBO.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hyvox/grid.h"
#include "hyvox/zero_page_allocator.h"

namespace hyvox {

/// A dense box of voxels, one bit each (the layout above). Not thread-safe for writes except
/// setAtomic(); reads from many threads are fine.
class BitGrid {
public:
    static constexpr int kWordsPerBrick = 8;  ///< 512 bits
    /// The words of a brick whose 512 voxels are all set (a tile brick written as a leaf).
    static constexpr std::uint64_t kFullBrick[kWordsPerBrick] = {~0ull, ~0ull, ~0ull, ~0ull,
                                                                 ~0ull, ~0ull, ~0ull, ~0ull};

    BitGrid() = default;
    /// An empty box of `dims` voxels (its bricks padded to whole 8³; zero pages, not written).
    explicit BitGrid(std::array<std::int32_t, 3> dims);

    const std::array<std::int32_t, 3>& dims() const { return dims_; }               ///< voxels along x, y, z
    const BrickLayout& bricks() const { return bricks_; }                           ///< the bricks over dims
    std::size_t brickCount() const { return bricks_.total(); }                      ///< bricks held
    std::size_t byteSize() const { return words_.size() * sizeof(std::uint64_t); }  ///< memory of the bits

    ///@{
    /// The words, kWordsPerBrick per brick in brick order.
    std::uint64_t* data() { return words_.data(); }
    const std::uint64_t* data() const { return words_.data(); }
    ///@}
    std::size_t wordCount() const { return words_.size(); }  ///< words of data()

    /// Word index and bit mask of voxel (i,j,k); the voxel must be inside dims.
    std::size_t wordIndex(int i, int j, int k) const {
        return bricks_.indexOfVoxel(i, j, k) * kWordsPerBrick + std::size_t(i & 7);
    }
    /// The bit of voxel (., j, k) in its word (wordIndex()).
    static std::uint64_t bitMask(int j, int k) { return std::uint64_t(1) << (((j & 7) << 3) | (k & 7)); }
    /// Voxel (i,j,k)'s bit among its brick's 512 (word i & 7, bit (j & 7) * 8 + (k & 7)).
    static int bitInBrick(int i, int j, int k) { return ((i & 7) << 6) | ((j & 7) << 3) | (k & 7); }

    /// Whether voxel (i,j,k) lies inside dims.
    bool inside(int i, int j, int k) const {
        return i >= 0 && j >= 0 && k >= 0 && i < dims_[0] && j < dims_[1] && k < dims_[2];
    }
    /// Whether voxel (i,j,k) (inside dims) is set.
    bool test(int i, int j, int k) const { return (words_[wordIndex(i, j, k)] & bitMask(j, k)) != 0; }
    /// Sets voxel (i,j,k) (inside dims); one thread at a time.
    void set(int i, int j, int k) { words_[wordIndex(i, j, k)] |= bitMask(j, k); }
    /// Safe from many threads at once (no locks: one relaxed atomic OR on the word).
    void setAtomic(int i, int j, int k) {
        __atomic_fetch_or(&words_[wordIndex(i, j, k)], bitMask(j, k), __ATOMIC_RELAXED);
    }

    /// The number of set voxels.
    std::uint64_t count() const;
    /// (i,j,k) of every set voxel, brick by brick (the order of OpenVDB's leaf iteration
    /// is not promised; sort if order matters).
    std::vector<std::array<std::int32_t, 3>> coords() const;

    /// The same dims and the same voxels.
    bool operator==(const BitGrid& other) const { return dims_ == other.dims_ && words_ == other.words_; }

private:
    std::array<std::int32_t, 3> dims_{0, 0, 0};
    BrickLayout bricks_;
    std::vector<std::uint64_t, ZeroPageAllocator<std::uint64_t>> words_;
};

}  // namespace hyvox
