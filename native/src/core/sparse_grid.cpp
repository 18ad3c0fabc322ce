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

bool full(const std::uint64_t* words) {
    std::uint64_t all = ~std::uint64_t(0);
    for (int w = 0; w < BitGrid::kWordsPerBrick; ++w) all &= words[w];
    return all == ~std::uint64_t(0);
}

bool byBrick(const SparseGrid::Leaf& a, const SparseGrid::Leaf& b) { return a.brick < b.brick; }

// Each voxel of a set tile brick, in the leaf layout.
void forEachVoxelOfBrick(const std::array<std::int32_t, 3>& at, std::vector<std::array<std::int32_t, 3>>& out) {
    for (int x = 0; x < 8; ++x)
        for (int bit = 0; bit < 64; ++bit)
            out.push_back({at[0] * 8 + x, at[1] * 8 + (bit >> 3), at[2] * 8 + (bit & 7)});
}

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

void SparseGrid::merge(const SparseGrid& more) {
    more.requireFinished();
    if (more.dims_ != dims_) throw std::invalid_argument("SparseGrid::merge: the grids differ in dimensions");
    leaves_.insert(leaves_.end(), more.leaves_.begin(), more.leaves_.end());
    tiles_.insert(tiles_.end(), more.tiles_.begin(), more.tiles_.end());
    sorted_ = false;
}

bool SparseGrid::brickWhole(std::uint64_t brick) const {
    const std::array<std::int32_t, 3> at = bricks_.at(brick);
    for (int a = 0; a < 3; ++a)
        if ((at[a] + 1) * BrickLayout::kSide > dims_[a]) return false;
    return true;
}

void SparseGrid::addTileRun(std::uint64_t begin, std::uint64_t end) {
    if (begin >= end) return;
    if (end > bricks_.total() || !brickWhole(begin) || !brickWhole(end - 1))
        throw std::invalid_argument("SparseGrid::addTileRun: tiles must be bricks wholly inside the grid");
    tiles_.push_back({begin, end});
    sorted_ = false;
}

void SparseGrid::addLeaf(const Leaf& leaf) {
    if (leaf.brick >= bricks_.total()) throw std::invalid_argument("SparseGrid::addLeaf: brick outside the grid");
    if (empty(leaf.words)) return;
    leaves_.push_back(leaf);
    sorted_ = false;
}

void SparseGrid::finish() {
    if (!sorted_) std::sort(leaves_.begin(), leaves_.end(), byBrick);
    // In place (no second copy of the leaves, which can be most of the memory budget): OR
    // leaves of one brick together; full leaves wholly in the grid become one-brick tiles.
    std::size_t kept = 0;
    for (std::size_t n = 0; n < leaves_.size(); ++n) {
        if (kept > 0 && leaves_[kept - 1].brick == leaves_[n].brick) {
            for (int w = 0; w < BitGrid::kWordsPerBrick; ++w) leaves_[kept - 1].words[w] |= leaves_[n].words[w];
        } else {
            leaves_[kept++] = leaves_[n];
        }
    }
    leaves_.resize(kept);
    for (const Leaf& leaf : leaves_)
        if (full(leaf.words) && brickWhole(leaf.brick)) tiles_.push_back({leaf.brick, leaf.brick + 1});
    // Tile runs sorted and merged where they overlap or touch.
    std::sort(tiles_.begin(), tiles_.end(), [](const TileRun& a, const TileRun& b) { return a.begin < b.begin; });
    std::size_t runs = 0;
    for (std::size_t n = 0; n < tiles_.size(); ++n) {
        if (runs > 0 && tiles_[n].begin <= tiles_[runs - 1].end)
            tiles_[runs - 1].end = std::max(tiles_[runs - 1].end, tiles_[n].end);
        else
            tiles_[runs++] = tiles_[n];
    }
    tiles_.resize(runs);
    // Leaves inside a tile (the full ones just made tiles among them) add nothing.
    kept = 0;
    std::size_t r = 0;
    for (std::size_t n = 0; n < leaves_.size(); ++n) {
        while (r < tiles_.size() && tiles_[r].end <= leaves_[n].brick) ++r;
        if (r < tiles_.size() && tiles_[r].begin <= leaves_[n].brick) continue;
        leaves_[kept++] = leaves_[n];
    }
    leaves_.resize(kept);
    leaves_.shrink_to_fit();
    tiles_.shrink_to_fit();
    sorted_ = true;
}

std::uint64_t SparseGrid::tileCount() const {
    std::uint64_t total = 0;
    for (const TileRun& run : tiles_) total += run.end - run.begin;
    return total;
}

bool SparseGrid::inTile(std::uint64_t brick) const {
    requireFinished();
    const auto it = std::upper_bound(tiles_.begin(), tiles_.end(), brick,
                                     [](std::uint64_t b, const TileRun& run) { return b < run.begin; });
    return it != tiles_.begin() && brick < std::prev(it)->end;
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
    const std::uint64_t brick = bricks_.indexOfVoxel(i, j, k);
    const Leaf* leaf = find(brick);
    return (leaf && (leaf->words[i & 7] & BitGrid::bitMask(j, k)) != 0) || inTile(brick);
}

void SparseGrid::brickWords(std::uint64_t brick, std::uint64_t out[BitGrid::kWordsPerBrick]) const {
    const Leaf* leaf = find(brick);
    const bool tile = !leaf && inTile(brick);
    for (int w = 0; w < BitGrid::kWordsPerBrick; ++w) out[w] = leaf ? leaf->words[w] : tile ? ~std::uint64_t(0) : 0;
}

void SparseGrid::set(int i, int j, int k) {
    requireFinished();
    const std::uint64_t brick = bricks_.indexOfVoxel(i, j, k);
    if (inTile(brick)) return;
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
    return total + 512 * tileCount();
}

std::vector<std::array<std::int32_t, 3>> SparseGrid::coords() const {
    requireFinished();
    std::vector<std::array<std::int32_t, 3>> out;
    out.reserve(count());
    // Leaves and tiles merged in brick order.
    std::size_t r = 0;
    auto tilesBefore = [&](std::uint64_t brick) {
        for (; r < tiles_.size() && tiles_[r].begin < brick; ++r)
            for (std::uint64_t b = tiles_[r].begin; b < tiles_[r].end; ++b) forEachVoxelOfBrick(bricks_.at(b), out);
    };
    for (const Leaf& leaf : leaves_) {
        tilesBefore(leaf.brick);
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
    tilesBefore(~std::uint64_t(0));
    return out;
}

BitGrid SparseGrid::toBitGrid() const {
    BitGrid dense(dims_);
    for (const Leaf& leaf : leaves_)
        std::memcpy(dense.data() + leaf.brick * BitGrid::kWordsPerBrick, leaf.words, sizeof leaf.words);
    for (const TileRun& run : tiles_)
        std::fill(dense.data() + run.begin * BitGrid::kWordsPerBrick, dense.data() + run.end * BitGrid::kWordsPerBrick,
                  ~std::uint64_t(0));
    return dense;
}

bool SparseGrid::operator==(const SparseGrid& other) const {
    requireFinished();
    other.requireFinished();
    if (dims_ != other.dims_ || leaves_.size() != other.leaves_.size() || tiles_.size() != other.tiles_.size())
        return false;
    for (std::size_t n = 0; n < tiles_.size(); ++n)
        if (tiles_[n].begin != other.tiles_[n].begin || tiles_[n].end != other.tiles_[n].end) return false;
    for (std::size_t n = 0; n < leaves_.size(); ++n)
        if (leaves_[n].brick != other.leaves_[n].brick ||
            std::memcmp(leaves_[n].words, other.leaves_[n].words, sizeof leaves_[n].words) != 0)
            return false;
    return true;
}

}  // namespace hyvox
