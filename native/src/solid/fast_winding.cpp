// SPDX-License-Identifier: GPL-3.0-or-later
#include "solid/fast_winding.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "solid/median_split.h"
#include "solid/solid_angle_sum.h"

namespace hyvox::solid {
namespace {

constexpr double kFourPi = 4.0 * M_PI;
constexpr std::uint32_t kLeafTriangles = 8;
// Subtrees of at least this many triangles build their two halves as parallel tasks.
constexpr std::uint32_t kParallelTriangles = 4096;
// Pieces a large triangle is cut into are at most this many voxels long, unless that would
// make more than kPieceBudget times the triangle count (plus a floor), when the length grows.
constexpr double kPieceVoxels = 4.0;
constexpr double kPieceBudget = 3.0;

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }

}  // namespace

double triangleWinding(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& q) {
    const Vec3 u = sub(a, q), v = sub(b, q), w = sub(c, q);
    const double lu = norm(u), lv = norm(v), lw = norm(w);
    const double det = dot(u, cross(v, w));
    const double denominator = lu * lv * lw + dot(u, v) * lw + dot(v, w) * lu + dot(w, u) * lv;
    return 2.0 * std::atan2(det, denominator) / kFourPi;
}

namespace {

// Cuts triangle (a, b, c) in halves at the middle of its longest edge until no edge is longer
// than `longest`. The halves' solid angles add up to the whole's at every point.
void cutLongEdges(const Vec3& a, const Vec3& b, const Vec3& c, double longest2, std::vector<std::array<Vec3, 3>>& out) {
    const double ab = dot(sub(a, b), sub(a, b)), bc = dot(sub(b, c), sub(b, c)), ca = dot(sub(c, a), sub(c, a));
    const double top = std::max({ab, bc, ca});
    if (top <= longest2) {
        out.push_back({a, b, c});
        return;
    }
    auto mid = [](const Vec3& x, const Vec3& y) {
        return Vec3{0.5 * (x[0] + y[0]), 0.5 * (x[1] + y[1]), 0.5 * (x[2] + y[2])};
    };
    if (top == ab) {
        const Vec3 m = mid(a, b);
        cutLongEdges(a, m, c, longest2, out);
        cutLongEdges(m, b, c, longest2, out);
    } else if (top == bc) {
        const Vec3 m = mid(b, c);
        cutLongEdges(a, b, m, longest2, out);
        cutLongEdges(a, m, c, longest2, out);
    } else {
        const Vec3 m = mid(c, a);
        cutLongEdges(a, b, m, longest2, out);
        cutLongEdges(m, b, c, longest2, out);
    }
}

// The nodes of the tree over `count` triangles (a leaf holds up to kLeafTriangles; an inner
// node splits its triangles count / 2 to the left): the node ids a subtree takes.
std::uint32_t treeNodes(std::uint32_t count) {
    return count > kLeafTriangles ? 1 + treeNodes(count / 2) + treeNodes(count - count / 2) : 1;
}

// How many pieces cutLongEdges makes of a triangle with these squared edge lengths, about.
double piecesAbout(double longest_edge2, double limit2) {
    return longest_edge2 <= limit2 ? 1.0 : 2.0 * longest_edge2 / limit2;
}

}  // namespace

FastWinding::FastWinding(const ValidatedMesh& mesh, const GridSpec& grid, double beta) : beta_(beta) {
    // Large triangles are cut into pieces of a few voxels: a cluster's radius then follows the
    // pieces near it rather than the one large triangle the median split put among small ones,
    // which would open the cluster, and all its ancestors, for every point near the large one.
    std::vector<std::array<Vec3, 3>> whole;
    whole.reserve(mesh.usable.size());
    std::vector<double> longest2;
    longest2.reserve(mesh.usable.size());
    for (const std::uint32_t t : mesh.usable) {
        const std::array<Vec3, 3> tri{grid.toVoxel(mesh.vertex(t, 0)), grid.toVoxel(mesh.vertex(t, 1)),
                                      grid.toVoxel(mesh.vertex(t, 2))};
        whole.push_back(tri);
        double top = 0;
        for (int e = 0; e < 3; ++e)
            top = std::max(top, dot(sub(tri[e], tri[(e + 1) % 3]), sub(tri[e], tri[(e + 1) % 3])));
        longest2.push_back(top);
    }
    double limit = kPieceVoxels;
    const double budget = kPieceBudget * double(whole.size()) + 100000.0;
    for (;; limit *= 2) {
        double pieces = 0;
        for (const double l2 : longest2) pieces += piecesAbout(l2, limit * limit);
        if (pieces <= budget) break;
    }
    triangles_.reserve(whole.size());
    for (const auto& [a, b, c] : whole) cutLongEdges(a, b, c, limit * limit, triangles_);
    // Depth first, the left subtree before the right: each subtree's ids follow from the
    // triangle counts alone, so the two halves of a node build in parallel into their own
    // ranges and the tree is the same as a serial build's.
    nodes_.resize(treeNodes(std::uint32_t(triangles_.size())));
    build(0, 0, std::uint32_t(triangles_.size()));
    // What the traversal reads for every node it visits, apart from what it reads only for the
    // clusters it expands (fewer bytes per visit).
    visits_.reserve(nodes_.size());
    expansions_.reserve(nodes_.size());
    for (const Node& node : nodes_) {
        const double far = beta_ * node.radius;
        visits_.push_back({node.centre, far * far, node.first, node.count, node.left, node.right});
        const auto& m = node.moment;
        expansions_.push_back({node.area, m[0] + m[4] + m[8], m});
    }
    nodes_ = {};
    // The tree's depth (a parent's index is below its children's), for atMany()'s lists.
    std::vector<std::uint32_t> depth(visits_.size(), 0);
    for (std::size_t id = 0; id < visits_.size(); ++id) {
        if (visits_[id].left < 0) continue;
        depth[std::size_t(visits_[id].left)] = depth[std::size_t(visits_[id].right)] = depth[id] + 1;
        levels_ = std::max(levels_, depth[id] + 2);
    }
    // The leaves' triangles once more as arrays of coordinates, in tree order, for the
    // vectorised sum of their solid angles.
    for (int n = 0; n < 9; ++n) {
        corner_arrays_[std::size_t(n)].resize(triangles_.size());
        for (std::size_t t = 0; t < triangles_.size(); ++t)
            corner_arrays_[std::size_t(n)][t] = triangles_[t][std::size_t(n / 3)][std::size_t(n % 3)];
    }
}

void FastWinding::build(std::int32_t id, std::uint32_t first, std::uint32_t count) {
    Node node;
    node.first = first;
    node.count = count;
    Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (std::uint32_t t = first; t < first + count; ++t)
        for (const Vec3& p : triangles_[t])
            for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
    if (count > kLeafTriangles) {
        const std::uint32_t half = splitAtMedian(
            triangles_, first, count, lo, hi,
            [](const std::array<Vec3, 3>& t, int axis) {
                return t[0][axis] + t[1][axis] + t[2][axis];  // three times the centroid
            },
            std::less<std::array<Vec3, 3>>());
        node.left = id + 1;
        node.right = id + 1 + std::int32_t(treeNodes(half));
        auto left = [&] { build(node.left, first, half); };
        auto right = [&] { build(node.right, first + half, count - half); };
        if (count >= kParallelTriangles)
            tbb::parallel_invoke(left, right);
        else
            left(), right();
        // A cluster's sums from its two halves' (each level would otherwise read all the
        // triangles again): the area vectors and areas add; the centre is the halves' centres
        // weighted by their areas; a half's moment moves to the new centre by its area vector
        // times the shift, since sum area_i (x_j - c_j) = sum area_i (x_j - h_j) + A_i (h_j - c_j).
        const Node& l = nodes_[std::size_t(node.left)];
        const Node& r = nodes_[std::size_t(node.right)];
        node.total_area = l.total_area + r.total_area;
        for (int k = 0; k < 3; ++k) {
            node.area[k] = l.area[k] + r.area[k];
            node.centre[k] = node.total_area > 0
                ? (l.total_area * l.centre[k] + r.total_area * r.centre[k]) / node.total_area
                : 0.5 * (lo[k] + hi[k]);
        }
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                node.moment[3 * i + j] = l.moment[3 * i + j] + l.area[i] * (l.centre[j] - node.centre[j]) +
                    r.moment[3 * i + j] + r.area[i] * (r.centre[j] - node.centre[j]);
    } else {
        // A leaf's triangles in one order on every platform (its sums, and the vectorised sum
        // over corner_arrays_, add them in this order); equal triangles are interchangeable.
        std::sort(triangles_.begin() + first, triangles_.begin() + first + count);
        Vec3 weighted{0, 0, 0};
        for (std::uint32_t t = first; t < first + count; ++t) {
            const auto& [a, b, c] = triangles_[t];
            const Vec3 n = cross(sub(b, a), sub(c, a));
            const double area = 0.5 * norm(n);
            for (int k = 0; k < 3; ++k) {
                node.area[k] += 0.5 * n[k];
                weighted[k] += area * (a[k] + b[k] + c[k]) / 3.0;
            }
            node.total_area += area;
        }
        for (int k = 0; k < 3; ++k)
            node.centre[k] = node.total_area > 0 ? weighted[k] / node.total_area : 0.5 * (lo[k] + hi[k]);
        for (std::uint32_t t = first; t < first + count; ++t) {
            const auto& [a, b, c] = triangles_[t];
            const Vec3 n = cross(sub(b, a), sub(c, a));
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j)
                    node.moment[3 * i + j] += 0.5 * n[i] * ((a[j] + b[j] + c[j]) / 3.0 - node.centre[j]);
        }
    }
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 p{corner & 1 ? hi[0] : lo[0], corner & 2 ? hi[1] : lo[1], corner & 4 ? hi[2] : lo[2]};
        node.radius = std::max(node.radius, norm(sub(p, node.centre)));
    }
    nodes_[std::size_t(id)] = node;
}

double FastWinding::at(const Vec3& q) const {
    if (visits_.empty()) return 0.0;
    double sum = 0;  // solid angle over 4π, exact parts
    double far = 0;  // expansions, times 4π
    walk(0, q, sum, far);
    return sum + far / kFourPi;
}

void FastWinding::walk(std::int32_t root, const Vec3& q, double& sum, double& far) const {
    TriangleArrays arrays;
    for (std::size_t n = 0; n < 9; ++n) arrays.corners[n] = corner_arrays_[n].data();
    std::int32_t stack[128];
    int top = 0;
    stack[top++] = root;
    while (top > 0) {
        const std::size_t id = std::size_t(stack[--top]);
        const Visit& node = visits_[id];
        const Vec3 r = sub(node.centre, q);
        const double r2 = dot(r, r);
        if (r2 > node.far2) {
            const Expansion& e = expansions_[id];
            const double r1 = std::sqrt(r2), r3 = r2 * r1;
            const auto& m = e.moment;
            double rmr = 0;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) rmr += r[i] * m[3 * i + j] * r[j];
            far += dot(e.area, r) / r3 + e.trace / r3 - 3.0 * rmr / (r3 * r2);
        } else if (node.left < 0) {
            sum += solidAngleSum(arrays, node.first, node.count, q);
        } else {
            // The children are read next: start loading them now (the tree outgrows the caches).
            for (const std::int32_t child : {node.left, node.right}) {
                __builtin_prefetch(&visits_[std::size_t(child)]);
                __builtin_prefetch(&expansions_[std::size_t(child)]);
                stack[top++] = child;
            }
        }
    }
}

void FastWinding::atMany(const Vec3* points, std::size_t count, double* out) const {
    std::fill(out, out + count, 0.0);
    if (visits_.empty() || count == 0) return;
    TriangleArrays arrays;
    for (std::size_t n = 0; n < 9; ++n) arrays.corners[n] = corner_arrays_[n].data();
    // Per point the same decisions and the same order of additions as at() (children right
    // first, each subtree whole), kept in two sums as there: the same values to the bit.
    // Per thread, kept between calls (no allocation per brick): the expansions' sums, and the
    // points still near at each depth of the walk, one list per depth.
    thread_local std::vector<double> far;
    thread_local std::vector<std::uint32_t> lists;
    far.assign(count, 0.0);
    lists.resize(count * std::size_t(levels_ + 1));
    for (std::uint32_t i = 0; i < count; ++i) lists[i] = i;
    auto visit = [&](auto&& self, std::int32_t id, std::size_t depth, std::size_t n) -> void {
        const Visit& node = visits_[std::size_t(id)];
        const std::uint32_t* list = &lists[depth * count];
        std::uint32_t* near = &lists[(depth + 1) * count];
        std::size_t near_count = 0;
        for (std::size_t k = 0; k < n; ++k) {
            const std::uint32_t i = list[k];
            const Vec3 r = sub(node.centre, points[i]);
            const double r2 = dot(r, r);
            if (r2 > node.far2) {
                const Expansion& e = expansions_[std::size_t(id)];
                const double r1 = std::sqrt(r2), r3 = r2 * r1;
                const auto& m = e.moment;
                double rmr = 0;
                for (int a = 0; a < 3; ++a)
                    for (int b = 0; b < 3; ++b) rmr += r[a] * m[3 * a + b] * r[b];
                far[i] += dot(e.area, r) / r3 + e.trace / r3 - 3.0 * rmr / (r3 * r2);
            } else {
                near[near_count++] = i;
            }
        }
        if (near_count == 0) return;
        if (node.left < 0) {
            for (std::size_t k = 0; k < near_count; ++k)
                out[near[k]] += solidAngleSum(arrays, node.first, node.count, points[near[k]]);
            return;
        }
        self(self, node.right, depth + 1, near_count);
        self(self, node.left, depth + 1, near_count);
    };
    visit(visit, 0, 0, count);
    for (std::size_t i = 0; i < count; ++i) out[i] += far[i] / kFourPi;
}

}  // namespace hyvox::solid
