// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The generalized winding number (Jacobson et al. 2013) of a triangle soup at a point, by the
// hierarchical approximation of Barill et al. 2018 ("Fast winding numbers for soups and
// clouds"): a bounding volume hierarchy over the triangles; a cluster seen from farther than
// beta times its radius contributes its dipole expansion to second order (the area vector
// sum and the first moment of the area vectors about the cluster's area-weighted centre);
// nearer clusters are opened, down to each triangle's exact solid angle
// (van Oosterom & Strackee). Everything in voxel space, in double precision.
#include <array>
#include <cstdint>
#include <vector>

#include "hyvox/grid.h"
#include "hyvox/mesh.h"

namespace hyvox::solid {

using Vec3 = std::array<double, 3>;

// The exact solid angle of triangle (a, b, c) seen from q, over 4π: in (-0.5, 0.5).
double triangleWinding(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& q);

class FastWinding {
public:
    FastWinding(const ValidatedMesh& mesh, const GridSpec& grid, double beta);
    double at(const Vec3& q) const;
    // at() for many points at once (equal to it bit for bit): the points share one walk of
    // the tree, which then stays in the caches.
    void atMany(const Vec3* points, std::size_t count, double* out) const;
    // The winding numbers at many points close together (a brick's), with the clusters far
    // from all of them evaluated once for the box (solid/box_winding.cpp): within the fast
    // winding numbers' own accuracy of at(), but not equal to it bit for bit.
    void atBox(const Vec3* points, std::size_t count, double* out) const;

private:
    struct Node {
        Vec3 centre{};                       // area-weighted centroid of the cluster
        double radius = 0;                   // farthest corner of its box from centre
        Vec3 area{};                         // sum of area vectors (normal times area)
        double total_area = 0;               // sum of the triangles' areas (the centre's weights)
        std::array<double, 9> moment{};      // sum of area_i * (centroid - centre)_j
        std::uint32_t first = 0, count = 0;  // triangles [first, first + count) when a leaf
        std::int32_t left = -1, right = -1;
    };

public:
    // What the build holds per node beside the traversal's records (the memory estimate's).
    static constexpr std::size_t kBuildNodeBytes = sizeof(Node);

private:
    // Node `id` and its subtree over triangles [first, first + count): split top down, its
    // sums (area, centre, moment) gathered bottom up from its children's.
    void build(std::int32_t id, std::uint32_t first, std::uint32_t count);
    // at()'s walk of the subtree under `root` for q: adds the exact parts to `sum` and the
    // expansions (times 4π) to `far`.
    void walk(std::int32_t root, const Vec3& q, double& sum, double& far) const;
    struct Visit {  // per node, what deciding to expand or open it reads
        Vec3 centre;
        double far2;  // (beta radius)²: expanded from farther than this
        std::uint32_t first, count;
        std::int32_t left, right;
    };
    struct Expansion {  // per node, what expanding it reads
        Vec3 area;
        double trace;  // of the moment
        std::array<double, 9> moment;
    };

    double beta_;
    std::vector<std::array<Vec3, 3>> triangles_;        // voxel space, in tree order
    std::array<std::vector<double>, 9> corner_arrays_;  // the same, coordinate 3 c + k of corner c
    std::vector<Node> nodes_;                           // while building, depth first
    std::vector<Visit> visits_;
    std::vector<Expansion> expansions_;
    std::uint32_t levels_ = 1;  // nodes on the longest path from the root, plus one
};

}  // namespace hyvox::solid
