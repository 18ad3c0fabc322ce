// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// w - c of an open mesh from the sheets of all its open edges (solid/smooth_winding.h: closing
// the surface with every open edge's sheet gives a surface whose winding number is c, so
// w - c = -Σ excess · (the sheets' winding numbers) everywhere off the surface), with no tree
// over the triangles. A point costs a term per open edge (SheetSum, eight floats a step), the
// tree a walk of thousands of nodes and triangles after a build of n log n: for a mesh with
// few open edges and many triangles (a sculpt, a scan with a hole at its base) the sheets
// are cheaper. Where a point's column passes within 1e-3 voxel of an open edge in xy the
// sheets' sum is not defined (the rays' tie-breaking decides there). Such points take the
// exact sum of every triangle's solid angle when the columns near the open edges are few
// enough for that sum to cost at most `exact_work` triangles' solid angles (each column's
// points counted as the grid's height: an upper bound in practice), otherwise the fast
// winding numbers' tree, built when the first of them comes (a mesh whose open edges run
// along the voxel columns' centre lines has many). Decided once, from the geometry, so
// the answer does not depend on which thread asks first.
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

#include "hyvox/grid.h"
#include "hyvox/mesh.h"
#include "solid/gradient_bound.h"
#include "solid/sheet_sum.h"
#include "solid/winding_less_crossings.h"

namespace hyvox::solid {

class SheetWinding final : public WindingLessCrossings {
public:
    // About the work of building the tree over 130k triangles: below it the exact sum costs
    // less than the tree's build would (docs/why/solid.md).
    static constexpr std::uint64_t kExactWork = std::uint64_t(1) << 24;
    SheetWinding(const ValidatedMesh& mesh, const GridSpec& grid, const GradientBound& bound, double beta,
                 std::uint64_t exact_work = kExactWork);
    ~SheetWinding() override;
    void at(const Vec3* points, const int* below, std::size_t count, bool together, double* out) const override;
    // The columns (at most) where the sheets' sum is not defined, and whether their points take
    // the exact sum (else the tree).
    std::uint64_t undefinedColumns() const { return undefined_columns_; }
    bool exactWhereUndefined() const { return exact_where_undefined_; }
    // The points the sheets could not take (all threads'), and whether the tree was built.
    std::uint64_t undefinedPoints() const { return undefined_points_.load(std::memory_order_relaxed); }
    bool treeBuilt() const { return tree_ != nullptr; }

private:
    // w at `q` exactly, the sum over every triangle.
    double exactWinding(const Vec3& q) const;
    const FastWinding& tree() const;

    const ValidatedMesh& mesh_;
    const GridSpec& grid_;
    double beta_;
    std::vector<GradientBound::Sheet> sheets_;
    std::uint64_t undefined_columns_;
    bool exact_where_undefined_;
    // Each thread's sheets, stored relative to a corner near its points (SheetSum keeps them in
    // floats): re-stored when a point lies in another block of kBlock³ voxels.
    struct Local {
        SheetSum sum;
        std::array<double, 3> corner{NAN, NAN, NAN};
    };
    mutable tbb::enumerable_thread_specific<Local> local_;
    mutable std::atomic<std::uint64_t> undefined_points_{0};
    mutable std::once_flag triangles_made_, tree_made_;
    mutable std::array<std::vector<double>, 9> corners_;  // voxel space, coordinate 3 c + k of corner c
    mutable std::unique_ptr<FastWinding> tree_;
};

}  // namespace hyvox::solid
