// SPDX-License-Identifier: GPL-3.0-or-later
#include "solid/sheet_winding.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "solid/solid_angle_sum.h"

namespace hyvox::solid {
namespace {

// The side of the blocks a thread's sheets are stored relative to (voxels): near points keep
// float's precision (2^-18 voxel at 64), and a thread moving through a brick's neighbourhood
// re-stores them rarely.
constexpr double kBlock = 64;

// Twice the sheets' tie distance: the count must not miss a column their float test poisons.
constexpr double kNearEdge = 2.0 * SheetSum::kTie;

// The voxel columns (i + 0.5, j + 0.5) of the grid, and of a brick's width around it where
// samples may lie, within kNearEdge of the open edges in xy (the sheets are in voxel space),
// an edge's and another's counted apart: row by row, the edge's stretch inside the row's
// band of half-width kNearEdge, widened by it.
std::uint64_t columnsNearEdges(const std::vector<GradientBound::Sheet>& sheets, const GridSpec& grid) {
    constexpr double kMargin = 8;
    const double lo_i = -kMargin, hi_i = grid.dims[0] + kMargin, lo_j = -kMargin, hi_j = grid.dims[1] + kMargin;
    std::uint64_t columns = 0;
    for (const auto& sheet : sheets) {
        const auto& a = sheet.a;
        const auto& b = sheet.b;
        const double first_row = std::max(lo_j, std::ceil(std::min(a[1], b[1]) - kNearEdge - 0.5));
        const double last_row = std::min(hi_j - 1, std::floor(std::max(a[1], b[1]) + kNearEdge - 0.5));
        for (double j = first_row; j <= last_row; ++j) {
            const double y = j + 0.5, dy = b[1] - a[1];
            double t0 = 0, t1 = 1;
            if (std::fabs(dy) > 0) {
                t0 = (y - kNearEdge - a[1]) / dy, t1 = (y + kNearEdge - a[1]) / dy;
                if (t0 > t1) std::swap(t0, t1);
                t0 = std::max(t0, 0.0), t1 = std::min(t1, 1.0);
            }
            const double x0 = a[0] + t0 * (b[0] - a[0]), x1 = a[0] + t1 * (b[0] - a[0]);
            const double first = std::max(lo_i, std::ceil(std::min(x0, x1) - kNearEdge - 0.5));
            const double last = std::min(hi_i - 1, std::floor(std::max(x0, x1) + kNearEdge - 0.5));
            if (last >= first) columns += std::uint64_t(last - first + 1);
        }
    }
    return columns;
}

}  // namespace

SheetWinding::SheetWinding(const ValidatedMesh& mesh, const GridSpec& grid, const GradientBound& bound, double beta,
                           std::uint64_t exact_work)
    : mesh_(mesh),
      grid_(grid),
      beta_(beta),
      sheets_(bound.allSheets()),
      undefined_columns_(columnsNearEdges(sheets_, grid)),
      exact_where_undefined_(double(undefined_columns_) * grid.dims[2] * double(mesh.usable.size()) <=
                             double(exact_work)) {}

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
    undefined_points_.fetch_add(undefined.size(), std::memory_order_relaxed);
    if (exact_where_undefined_) {
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
