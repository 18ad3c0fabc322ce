// SPDX-License-Identifier: GPL-3.0-or-later
#include "solid/sheet_winding.h"

#include <tbb/task_arena.h>

#include <cmath>

#include "solid/solid_angle_sum.h"

namespace hyvox::solid {
namespace {

// The side of the blocks a thread's sheets are stored relative to (voxels): near points keep
// float's precision (2^-18 voxel at 64), and a thread moving through a brick's neighbourhood
// re-stores them rarely.
constexpr double kBlock = 64;

}  // namespace

SheetWinding::SheetWinding(const ValidatedMesh& mesh, const GridSpec& grid, const GradientBound& bound, double beta)
    : mesh_(mesh), grid_(grid), beta_(beta), sheets_(bound.allSheets()) {}

SheetWinding::~SheetWinding() = default;

double SheetWinding::exactWinding(const Vec3& q) const {
    std::call_once(triangles_made_, [&] {
        for (auto& coordinate : corners_) coordinate.reserve(mesh_.usable.size());
        for (const std::uint32_t t : mesh_.usable)
            for (int c = 0; c < 3; ++c) {
                const Vec3 p = grid_.toVoxel(mesh_.vertex(t, c));
                for (int k = 0; k < 3; ++k) corners_[std::size_t(3 * c + k)].push_back(p[std::size_t(k)]);
            }
    });
    TriangleArrays arrays;
    for (std::size_t n = 0; n < 9; ++n) arrays.corners[n] = corners_[n].data();
    return solidAngleSum(arrays, 0, mesh_.usable.size(), q);
}

const FastWinding& SheetWinding::tree() const {
    // Built by the first thread to need it, the others waiting. Isolated: while its build
    // waits for its own parallel halves, the building thread must not take up another brick,
    // which could ask for the tree again on the same thread.
    std::call_once(tree_made_, [&] {
        tbb::this_task_arena::isolate([&] { tree_ = std::make_unique<FastWinding>(mesh_, grid_, beta_); });
    });
    return *tree_;
}

void SheetWinding::at(const Vec3* points, const int* below, std::size_t count, bool together, double* out) const {
    Local& local = local_.local();
    std::vector<std::size_t> undefined;
    for (std::size_t n = 0; n < count; ++n) {
        const Vec3& q = points[n];
        const std::array<double, 3> corner{kBlock * std::floor(q[0] / kBlock), kBlock * std::floor(q[1] / kBlock),
                                           kBlock * std::floor(q[2] / kBlock)};
        if (corner != local.corner) {
            local.sum.assign(sheets_, false, corner);
            local.corner = corner;
        }
        out[n] = -local.sum.at(q);
        if (std::isnan(out[n])) undefined.push_back(n);
    }
    if (undefined.empty()) return;
    const std::uint64_t before = undefined_points_.fetch_add(undefined.size(), std::memory_order_relaxed);
    if (before + undefined.size() <= kExactPoints) {
        for (const std::size_t n : undefined) out[n] = exactWinding(points[n]) - below[n];
        return;
    }
    std::vector<Vec3> near(undefined.size());
    std::vector<int> near_below(undefined.size());
    std::vector<double> values(undefined.size());
    for (std::size_t m = 0; m < undefined.size(); ++m)
        near[m] = points[undefined[m]], near_below[m] = below[undefined[m]];
    TreeLessCrossings(tree()).at(near.data(), near_below.data(), near.size(), together, values.data());
    for (std::size_t m = 0; m < undefined.size(); ++m) out[undefined[m]] = values[m];
}

}  // namespace hyvox::solid
