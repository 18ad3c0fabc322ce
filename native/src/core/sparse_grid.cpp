// SPDX-License-Identifier: GPL-3.0-or-later
#include "hyvox/sparse_grid.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace hyvox {
namespace {

bool empty(const std::uint64_t* words) {
    std::uint64_t any = 0;
    for (int w = 0; w < BitGrid::kWordsPerBrick; ++w) any |= words[w];
    return any == 0;
}

bool byBrick(const SparseGrid::Leaf& a, const SparseGrid::Leaf& b) { return a.brick < b.brick; }

}  // namespace

SparseGrid::SparseGrid(std::array<std::int32_t, 3> dims) : dims_(dims), bricks_(BrickLayout::over(dims)) {
    for (int a = 0; a < 3; ++a)
        if (dims[a] < 1) throw std::invalid_argument("SparseGrid dimensions must be positive");
}

SparseGrid SparseGrid::fromBitGrid(const BitGrid& dense) {
    SparseGrid sparse(dense.dims());
    sparse.addTile(dense, {0, 0, 0});
    sparse.finish();
    return sparse;
}

void SparseGrid::addTile(const BitGrid& tile, const std::array<std::int32_t, 3>& offset) {
    const BrickLayout& local = tile.bricks();
    std::array<std::int32_t, 3> first{};
    for (int a = 0; a < 3; ++a) {
        if (offset[a] % BrickLayout::kSide != 0 || offset[a] < 0 ||
            offset[a] / BrickLayout::kSide + local.counts[a] > bricks_.counts[a])
            throw std::invalid_argument("SparseGrid::addTile: the tile is not a brick-aligned box of the grid");
        first[a] = offset[a] / BrickLayout::kSide;
    }
    sorted_ = leaves_.empty();
    for (std::int32_t bx = 0; bx < local.counts[0]; ++bx)
        for (std::int32_t by = 0; by < local.counts[1]; ++by)
            for (std::int32_t bz = 0; bz < local.counts[2]; ++bz) {
                const std::uint64_t* words = tile.data() + local.index(bx, by, bz) * BitGrid::kWordsPerBrick;
                if (empty(words)) continue;
                Leaf leaf;
                leaf.brick = bricks_.index(first[0] + bx, first[1] + by, first[2] + bz);
                std::memcpy(leaf.words, words, sizeof leaf.words);
                leaves_.push_back(leaf);
            }
    // One tile's bricks come out in brick order only when it spans the grid's y and z (the
    // layout is x-major), and tiles interleave: finish() sorts once, after the last tile.
    sorted_ = sorted_ && local.counts[1] == bricks_.counts[1] && local.counts[2] == bricks_.counts[2];
}

void SparseGrid::finish() {
    if (!sorted_) std::sort(leaves_.begin(), leaves_.end(), byBrick);
    sorted_ = true;
}

void SparseGrid::requireFinished() const {
    if (!sorted_) throw std::logic_error("SparseGrid: finish() must follow the last addTile()");
}

const SparseGrid::Leaf* SparseGrid::find(std::uint64_t brick) const {
    requireFinished();
    const auto it = std::lower_bound(leaves_.begin(), leaves_.end(), brick,
                                     [](const Leaf& leaf, std::uint64_t b) { return leaf.brick < b; });
    return it != leaves_.end() && it->brick == brick ? &*it : nullptr;
}

bool SparseGrid::test(int i, int j, int k) const {
    const Leaf* leaf = find(bricks_.indexOfVoxel(i, j, k));
    return leaf && (leaf->words[i & 7] & BitGrid::bitMask(j, k)) != 0;
}

void SparseGrid::set(int i, int j, int k) {
    requireFinished();
    const std::uint64_t brick = bricks_.indexOfVoxel(i, j, k);
    auto it = std::lower_bound(leaves_.begin(), leaves_.end(), brick,
                               [](const Leaf& leaf, std::uint64_t b) { return leaf.brick < b; });
    if (it == leaves_.end() || it->brick != brick) {
        Leaf leaf{};
        leaf.brick = brick;
        it = leaves_.insert(it, leaf);
    }
    it->words[i & 7] |= BitGrid::bitMask(j, k);
}

std::uint64_t SparseGrid::count() const {
    std::uint64_t total = 0;
    for (const Leaf& leaf : leaves_)
        for (std::uint64_t w : leaf.words) total += std::uint64_t(__builtin_popcountll(w));
    return total;
}

std::vector<std::array<std::int32_t, 3>> SparseGrid::coords() const {
    std::vector<std::array<std::int32_t, 3>> out;
    out.reserve(count());
    for (const Leaf& leaf : leaves_) {
        const std::array<std::int32_t, 3> at = bricks_.at(leaf.brick);
        for (int x = 0; x < BitGrid::kWordsPerBrick; ++x) {
            std::uint64_t word = leaf.words[x];
            while (word) {
                const int bit = __builtin_ctzll(word);
                word &= word - 1;
                out.push_back({at[0] * 8 + x, at[1] * 8 + (bit >> 3), at[2] * 8 + (bit & 7)});
            }
        }
    }
    return out;
}

BitGrid SparseGrid::toBitGrid() const {
    BitGrid dense(dims_);
    for (const Leaf& leaf : leaves_)
        std::memcpy(dense.data() + leaf.brick * BitGrid::kWordsPerBrick, leaf.words, sizeof leaf.words);
    return dense;
}

bool SparseGrid::operator==(const SparseGrid& other) const {
    requireFinished();
    other.requireFinished();
    if (dims_ != other.dims_ || leaves_.size() != other.leaves_.size()) return false;
    for (std::size_t n = 0; n < leaves_.size(); ++n)
        if (leaves_[n].brick != other.leaves_[n].brick ||
            std::memcmp(leaves_[n].words, other.leaves_[n].words, sizeof leaves_[n].words) != 0)
            return false;
    return true;
}

}  // namespace hyvox
