// SPDX-License-Identifier: GPL-3.0-or-later
// FastWinding::atBox: the fast winding numbers at many points close together (the voxels of
// one brick that must be evaluated outright, solid/smooth_winding.h), with one walk of the
// tree for the whole box instead of one per point.
//
// Every point lies within ρ of the box's centre q0. Seen from the box, a cluster (centre c,
// radius r, D = |c - q0|) is
//   far    when D - ρ > β max(r, ρ): farther than β times its radius from every point (at()
//          would expand it for each of them), and farther than β ρ from the box, so that its
//          field is one polynomial about q0 to 1/(β + 1)^4 (solid/local_expansion.h): it is
//          added to the box's local expansion, once;
//   small  when it is not far but its radius is at most ρ: each point walks it as at() does;
//   else it is opened. A leaf that is not far is opened to its triangles, each of which is a
//   cluster of its own (its first moment about its centroid is 0: at()'s expansion of a
//   one-triangle cluster is the dipole A·r/|r|³): far ones go to the local expansion, the
//   others are summed exactly at every point, vectorised (solid/solid_angle_sum.h).
// So a point's value takes the same expansions as at() for the small clusters, and for the
// rest the same two kinds of terms (a cluster's second-order expansion, a triangle's exact
// solid angle) with a stricter choice of which (a cluster is expanded only from farther
// away), plus the polynomial's truncation. tests/native/test_solid.cpp compares it with at()
// and with the exact sum on Sponza's points.
#include <algorithm>
#include <cmath>
#include <vector>

#include "solid/fast_winding.h"
#include "solid/local_expansion.h"
#include "solid/solid_angle_sum.h"

namespace hyvox::solid {
namespace {

constexpr double kFourPi = 4.0 * M_PI;

double distance(const Vec3& a, const Vec3& b) {
    const double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
    return std::sqrt(x * x + y * y + z * z);
}

// Per thread, kept from box to box (no allocation per brick once grown).
struct BoxScratch {
    LocalExpansion expansion;
    std::array<std::vector<float>, 9> near;  // the near triangles, coordinate 3 c + k of corner c, from the centre
    std::vector<std::int32_t> small;         // clusters each point walks
    std::vector<std::int32_t> stack;
};

}  // namespace

void FastWinding::atBox(const Vec3* points, std::size_t count, double* out) const {
    std::fill(out, out + count, 0.0);
    if (visits_.empty() || count == 0) return;
    // The box's centre and radius: the middle of the points' bounds, the farthest point.
    Vec3 lo = points[0], hi = points[0];
    for (std::size_t i = 1; i < count; ++i)
        for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], points[i][d]), hi[d] = std::max(hi[d], points[i][d]);
    const Vec3 centre{0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
    double rho = 0;
    for (std::size_t i = 0; i < count; ++i) rho = std::max(rho, distance(points[i], centre));

    thread_local BoxScratch scratch;
    LocalExpansion& expansion = scratch.expansion;
    expansion.reset(centre);
    for (auto& coordinate : scratch.near) coordinate.clear();
    scratch.small.clear();
    // far(D, r): the rule above, for a cluster of radius r whose centre is D from the box's.
    auto far = [&](double d, double r) { return d - rho > beta_ * std::max(r, rho); };
    auto& stack = scratch.stack;
    stack.assign(1, 0);
    while (!stack.empty()) {
        const std::int32_t id = stack.back();
        stack.pop_back();
        const Visit& node = visits_[std::size_t(id)];
        const double radius = std::sqrt(node.far2) / beta_;
        if (far(distance(node.centre, centre), radius)) {
            const Expansion& e = expansions_[std::size_t(id)];
            expansion.add(node.centre, e.area, &e.moment);
        } else if (node.left < 0) {
            for (std::uint32_t t = node.first; t < node.first + node.count; ++t) {
                const auto& [a, b, c] = triangles_[t];
                const Vec3 centroid{(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0, (a[2] + b[2] + c[2]) / 3.0};
                const double r = std::max({distance(a, centroid), distance(b, centroid), distance(c, centroid)});
                if (far(distance(centroid, centre), r)) {
                    const Vec3 u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
                    const Vec3 area{0.5 * (u[1] * v[2] - u[2] * v[1]), 0.5 * (u[2] * v[0] - u[0] * v[2]),
                                    0.5 * (u[0] * v[1] - u[1] * v[0])};
                    expansion.add(centroid, area, nullptr);
                } else {
                    for (std::size_t n = 0; n < 9; ++n)
                        scratch.near[n].push_back(float(triangles_[t][n / 3][n % 3] - centre[n % 3]));
                }
            }
        } else if (radius <= rho) {
            scratch.small.push_back(id);
        } else {
            stack.push_back(node.left);
            stack.push_back(node.right);
        }
    }
    FloatTriangleArrays near;
    for (std::size_t n = 0; n < 9; ++n) near.corners[n] = scratch.near[n].data();
    const std::size_t near_count = scratch.near[0].size();
    for (std::size_t i = 0; i < count; ++i) {
        const std::array<float, 3> q{float(points[i][0] - centre[0]), float(points[i][1] - centre[1]),
                                     float(points[i][2] - centre[2])};
        double sum = near_count > 0 ? solidAngleSum(near, near_count, q) : 0.0;
        double expanded = 0;
        for (const std::int32_t id : scratch.small) walk(id, points[i], sum, expanded);
        out[i] = sum + (expanded + expansion.at(points[i])) / kFourPi;
    }
}

}  // namespace hyvox::solid
