// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The samples every brick of an open mesh reads first (solid/smooth_winding.h): w - c at the
// corners and the middle of each brick's box, evaluated a block of bricks at a time.
//
// A corner is shared by up to eight bricks and must have one value whichever thread asks
// first, and an open mesh at a high resolution has very many. One at a time
// (FastWinding::atMany, a few points a walk) each walks the tree; here the corners and
// middles of a block of 4×4×4 bricks are evaluated together by one walk of the tree
// (FastWinding::atBox: the clusters far from the whole block as one local expansion about its
// centre), far cheaper a point (docs/why/solid.md), by whichever thread first asks
// for one of them. Each value depends on its block alone, never on the threads or the order:
// a block two threads compute at once is computed the same way by both, and the first one
// stored is kept.
//
// Along each axis, brick k's box runs from 8k to top(k) = 8k + 8 (the next brick's first
// voxel) or, at the grid's end, the last voxel. Its corners' coordinates are 8k and the
// grid's last voxel; its middle is (8k + top(k)) / 2. A point is a box corner when all three
// coordinates are corner coordinates, a box middle when all three are middles; other points
// (a halved box's) are not kept here.
#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "solid/ray_crossings.h"
#include "solid/winding_less_crossings.h"

namespace hyvox::solid {

// Samples are taken this far above a voxel centre, off any horizontal face through the centre
// (the smooth part is continuous: its value holds at the centre).
constexpr double kSampleLift = 0.00390625;
// The height at which the voxel column `column` is sampled for a centre at height h: h +
// kSampleLift, moved up by kSampleLift until no crossing lies within rounding of it (the first
// such height, whatever the crossings' order).
double sampleHeight(const std::vector<RayCrossings::Crossing>& column, double centre);
// The signed crossings of `column` below height h (c).
int crossingsBelow(const std::vector<RayCrossings::Crossing>& column, double h);

class BrickSamples {
public:
    using Int3 = std::array<std::int32_t, 3>;
    BrickSamples(const WindingLessCrossings& winding, const RayCrossings& rays, const Int3& dims);
    ~BrickSamples();
    BrickSamples(const BrickSamples&) = delete;
    BrickSamples& operator=(const BrickSamples&) = delete;
    // w - c at voxel p's centre (sampled just above it) when p is a brick box's corner or
    // middle (true), evaluating its block first if no thread has; else false.
    bool find(const Int3& p, double& value) const;
    // The points of the blocks evaluated so far (a block two threads evaluated at once counted
    // once).
    std::uint64_t evaluations() const { return evaluations_.load(std::memory_order_relaxed); }

private:
    static constexpr int kBlock = 4;                             // bricks per block side
    static constexpr int kSlots = 2 * kBlock * kBlock * kBlock;  // corners, then middles
    struct Block {
        double values[kSlots];        // NaN where the block has no such point
        std::uint64_t evaluated = 0;  // its points
    };
    // Along one axis: the corner coordinates 8k (k < bricks) and the last voxel (index
    // `bricks`), and the bricks' middles.
    struct Axis {
        std::int32_t dims = 0, bricks = 0;
        std::int32_t top(std::int32_t k) const { return 8 * k + 8 < dims ? 8 * k + 8 : dims - 1; }
        std::int32_t middle(std::int32_t k) const { return (8 * k + top(k)) / 2; }
        // The coordinate of corner index n (0..bricks), or -1 when there is none (the last
        // voxel already a multiple of 8).
        std::int32_t corner(std::int32_t n) const;
        // The coordinate of brick k's middle, or -1 when it is a corner coordinate (a box of
        // at most two voxels along the axis) or k is off the grid.
        std::int32_t middleOf(std::int32_t k) const;
        // Corner index of coordinate c, or -1.
        std::int32_t cornerIndex(std::int32_t c) const;
        // Brick whose middle is coordinate c, or -1.
        std::int32_t middleIndex(std::int32_t c) const;
    };
    // Block b's entry; its row of blocks along z is allocated when first asked for.
    std::atomic<Block*>& entry(const Int3& b) const;
    const Block& block(const Int3& b) const;
    void evaluate(const Int3& b, Block& out) const;

    const WindingLessCrossings& winding_;
    const RayCrossings& rays_;
    std::array<Axis, 3> axes_;
    Int3 blocks_{};  // blocks along each axis
    // The blocks by (x, y) row, each row an array along z made when one of its blocks is
    // first asked for: the table grows with the blocks an open mesh's surface reaches, not with
    // the grid (a dense table of 16384³'s blocks would be a gigabyte of pointers).
    std::unique_ptr<std::atomic<std::atomic<Block*>*>[]> rows_;
    mutable std::atomic<std::uint64_t> evaluations_{0};
};

}  // namespace hyvox::solid
