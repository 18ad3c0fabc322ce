// SPDX-License-Identifier: GPL-3.0-or-later
#include "solid/brick_samples.h"

#include <cmath>

namespace hyvox::solid {

double sampleHeight(const std::vector<RayCrossings::Crossing>& column, double centre) {
    double h = centre + kSampleLift;
    // Off every crossing by more than the rounding of its height.
    for (bool moved = true; moved;) {
        moved = false;
        for (const auto& c : column)
            if (std::fabs(c.z - h) < 1e-6) h += kSampleLift, moved = true;
    }
    return h;
}

int crossingsBelow(const std::vector<RayCrossings::Crossing>& column, double h) {
    int count = 0;
    for (const auto& c : column)
        if (c.z < h) count += c.sign;
    return count;
}

std::int32_t BrickSamples::Axis::corner(std::int32_t n) const {
    if (n < 0 || n > bricks) return -1;
    if (n < bricks) return 8 * n;
    return (dims - 1) % 8 == 0 ? -1 : dims - 1;
}

std::int32_t BrickSamples::Axis::middleOf(std::int32_t k) const {
    if (k < 0 || k >= bricks) return -1;
    const std::int32_t m = middle(k);
    return m % 8 == 0 || m == dims - 1 ? -1 : m;
}

std::int32_t BrickSamples::Axis::cornerIndex(std::int32_t c) const {
    if (c < 0 || c >= dims) return -1;
    if (c % 8 == 0) return c / 8;
    return c == dims - 1 ? bricks : -1;
}

std::int32_t BrickSamples::Axis::middleIndex(std::int32_t c) const {
    if (c < 0 || c >= dims) return -1;
    return middleOf(c / 8) == c ? c / 8 : -1;
}

BrickSamples::BrickSamples(const WindingLessCrossings& winding, const RayCrossings& rays, const Int3& dims)
    : winding_(winding), rays_(rays) {
    for (int d = 0; d < 3; ++d) {
        axes_[std::size_t(d)].dims = dims[std::size_t(d)];
        axes_[std::size_t(d)].bricks = (dims[std::size_t(d)] + 7) / 8;
        blocks_[std::size_t(d)] = axes_[std::size_t(d)].bricks / kBlock + 1;  // corner index `bricks` included
    }
    const std::size_t rows = std::size_t(blocks_[0]) * std::size_t(blocks_[1]);
    rows_ = std::make_unique<std::atomic<std::atomic<Block*>*>[]>(rows);
    for (std::size_t r = 0; r < rows; ++r) rows_[r].store(nullptr, std::memory_order_relaxed);
}

BrickSamples::~BrickSamples() {
    const std::size_t rows = std::size_t(blocks_[0]) * std::size_t(blocks_[1]);
    for (std::size_t r = 0; r < rows; ++r) {
        std::atomic<Block*>* row = rows_[r].load(std::memory_order_relaxed);
        if (!row) continue;
        for (std::int32_t z = 0; z < blocks_[2]; ++z) delete row[z].load(std::memory_order_relaxed);
        delete[] row;
    }
}

bool BrickSamples::find(const Int3& p, double& value) const {
    Int3 index;
    int slot_base = 0;
    bool corner = true, middle = true;
    Int3 corner_index, middle_index;
    for (int d = 0; d < 3; ++d) {
        corner_index[std::size_t(d)] = axes_[std::size_t(d)].cornerIndex(p[std::size_t(d)]);
        middle_index[std::size_t(d)] = axes_[std::size_t(d)].middleIndex(p[std::size_t(d)]);
        corner = corner && corner_index[std::size_t(d)] >= 0;
        middle = middle && middle_index[std::size_t(d)] >= 0;
    }
    if (corner)
        index = corner_index;
    else if (middle)
        index = middle_index, slot_base = kSlots / 2;
    else
        return false;
    const Block& b = block({index[0] / kBlock, index[1] / kBlock, index[2] / kBlock});
    const int slot = slot_base + ((index[0] % kBlock) * kBlock + index[1] % kBlock) * kBlock + index[2] % kBlock;
    value = b.values[slot];
    return true;
}

std::atomic<BrickSamples::Block*>& BrickSamples::entry(const Int3& b) const {
    std::atomic<std::atomic<Block*>*>& slot = rows_[std::size_t(b[0]) * std::size_t(blocks_[1]) + std::size_t(b[1])];
    std::atomic<Block*>* row = slot.load(std::memory_order_acquire);
    if (!row) {
        auto mine = std::make_unique<std::atomic<Block*>[]>(std::size_t(blocks_[2]));
        for (std::int32_t z = 0; z < blocks_[2]; ++z) mine[std::size_t(z)].store(nullptr, std::memory_order_relaxed);
        // Another thread may have stored a row meanwhile: then that one is used.
        if (slot.compare_exchange_strong(row, mine.get(), std::memory_order_acq_rel, std::memory_order_acquire))
            row = mine.release();
    }
    return row[b[2]];
}

const BrickSamples::Block& BrickSamples::block(const Int3& b) const {
    std::atomic<Block*>& entry = this->entry(b);
    Block* found = entry.load(std::memory_order_acquire);
    if (found) return *found;
    auto mine = std::make_unique<Block>();
    evaluate(b, *mine);
    // Another thread may have stored the same block meanwhile: its values equal these.
    if (!entry.compare_exchange_strong(found, mine.get(), std::memory_order_acq_rel, std::memory_order_acquire))
        return *found;
    evaluations_.fetch_add(mine->evaluated, std::memory_order_relaxed);  // the stored block's alone
    return *mine.release();
}

void BrickSamples::evaluate(const Int3& b, Block& out) const {
    std::vector<Vec3> points;
    std::vector<int> slots, below;
    std::vector<RayCrossings::Crossing> column;
    for (int kind = 0; kind < 2; ++kind) {  // corners, then middles
        auto coordinate = [&](int d, int n) {
            const std::int32_t k = kBlock * b[std::size_t(d)] + n;
            return kind == 0 ? axes_[std::size_t(d)].corner(k) : axes_[std::size_t(d)].middleOf(k);
        };
        for (int i = 0; i < kBlock; ++i) {
            const std::int32_t x = coordinate(0, i);
            for (int j = 0; j < kBlock; ++j) {
                const std::int32_t y = coordinate(1, j);
                if (x < 0 || y < 0) continue;
                bool have_column = false;
                for (int k = 0; k < kBlock; ++k) {
                    const std::int32_t z = coordinate(2, k);
                    if (z < 0) continue;
                    if (!have_column) rays_.column(x, y, column), have_column = true;
                    const double h = sampleHeight(column, z + 0.5);
                    points.push_back({x + 0.5, y + 0.5, h});
                    below.push_back(crossingsBelow(column, h));
                    slots.push_back(kind * kSlots / 2 + (i * kBlock + j) * kBlock + k);
                }
            }
        }
    }
    for (double& v : out.values) v = NAN;
    out.evaluated = points.size();
    if (points.empty()) return;
    std::vector<double> w(points.size());
    winding_.at(points.data(), below.data(), points.size(), true, w.data());
    for (std::size_t n = 0; n < points.size(); ++n) out.values[slots[n]] = w[n];
}

}  // namespace hyvox::solid
