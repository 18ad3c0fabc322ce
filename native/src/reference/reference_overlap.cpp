// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference/reference_overlap.h"

#include <algorithm>
#include <cmath>

#include "core/triangle_normal.h"

namespace hyvox::reference {
namespace {

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double sign(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }

Vec3 centreOf(const Voxel& voxel) { return {voxel[0] + 0.5, voxel[1] + 0.5, voxel[2] + 0.5}; }

// Akenine-Möller's separating-axis test of a triangle against the closed box centred at
// the origin with half-size h: separated only if some axis strictly separates them, so a
// triangle touching a face, edge or corner of the box counts as overlapping.
bool triangleBoxSat(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3 (&edges)[3], const Vec3& n, double h) {
    const Vec3 verts[3] = {a, b, c};

    auto separatedOn = [&](const Vec3& axis) {
        const double p0 = dot(axis, verts[0]), p1 = dot(axis, verts[1]), p2 = dot(axis, verts[2]);
        const double r = h * (std::fabs(axis[0]) + std::fabs(axis[1]) + std::fabs(axis[2]));
        return std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r;
    };

    // Triangle normal first: it rejects most voxels of a large triangle's bounding box.
    if (separatedOn(n)) return false;
    // The three box normals.
    for (int axis = 0; axis < 3; ++axis) {
        const double lo = std::min({a[axis], b[axis], c[axis]});
        const double hi = std::max({a[axis], b[axis], c[axis]});
        if (lo > h || hi < -h) return false;
    }
    // The nine edge x box-normal axes.
    for (const Vec3& edge : edges)
        for (int axis = 0; axis < 3; ++axis) {
            Vec3 unit{0, 0, 0};
            unit[axis] = 1.0;
            if (separatedOn(cross(unit, edge))) return false;
        }
    return true;
}

// Schwarz & Seidel's 6-separating test against the voxel centred at the origin whose box has
// half-size h (the octahedron and the 2D diamonds inscribed in it have "radius" h). A
// planeless triangle (a segment or a point in voxel space) has no plane to test and no
// winding in any projection: there every projected edge's line must pass the diamond,
// on either side.
bool sixSeparatingTest(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3 (&edges)[3], const Vec3& n, double h) {
    // The triangle's bounding box must meet the box (the edge tests alone would accept
    // voxels beyond a sharp corner of the triangle).
    for (int axis = 0; axis < 3; ++axis) {
        const double lo = std::min({a[axis], b[axis], c[axis]});
        const double hi = std::max({a[axis], b[axis], c[axis]});
        if (lo > h || hi < -h) return false;
    }
    const Vec3 verts[3] = {a, b, c};
    if (n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0) {
        const int planes[3][2] = {{0, 1}, {1, 2}, {2, 0}};
        for (const auto& plane : planes)
            for (int i = 0; i < 3; ++i) {
                const double nu = -edges[i][plane[1]], nv = edges[i][plane[0]];
                const double distance = nu * (0.0 - verts[i][plane[0]]) + nv * (0.0 - verts[i][plane[1]]);
                if (std::fabs(distance) > h * std::max(std::fabs(nu), std::fabs(nv))) return false;
            }
        return true;
    }

    // Plane against the inscribed octahedron |x|+|y|+|z| <= h: its support in direction n is
    // h * max|n_i|, and the centre's signed distance (times |n|) is -n.a.
    const double n_inf = std::max({std::fabs(n[0]), std::fabs(n[1]), std::fabs(n[2])});
    if (std::fabs(dot(n, a)) > h * n_inf) return false;

    // Projections onto the planes (u,v) = (x,y), (y,z), (z,x); w is the remaining axis,
    // whose normal component gives the projected triangle's winding.
    const int planes[3][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}};
    for (const auto& plane : planes) {
        const int u = plane[0], v = plane[1], w = plane[2];
        const double winding = sign(n[w]);
        if (winding == 0.0) continue;  // the projection is a segment: the plane test covers it
        for (int i = 0; i < 3; ++i) {
            // Inward normal of the projected edge, and the point of the 2D diamond
            // |u|+|v| <= h furthest along it (support h * max(|nu|, |nv|)).
            const double nu = -winding * edges[i][v];
            const double nv = winding * edges[i][u];
            const double distance = nu * (0.0 - verts[i][u]) + nv * (0.0 - verts[i][v]);
            if (distance + h * std::max(std::fabs(nu), std::fabs(nv)) < 0.0) return false;
        }
    }
    return true;
}

}  // namespace

Triangle voxelSpaceTriangle(const ValidatedMesh& mesh, std::uint32_t index, const GridSpec& grid) {
    return {grid.toVoxel(mesh.vertex(index, 0)), grid.toVoxel(mesh.vertex(index, 1)),
            grid.toVoxel(mesh.vertex(index, 2))};
}

bool overlaps(const Triangle& triangle, const Voxel& voxel, Mode mode, double delta) {
    // Work relative to the voxel centre: small numbers, and the box is symmetric.
    const Vec3 centre = centreOf(voxel);
    const Vec3 a = sub(triangle[0], centre), b = sub(triangle[1], centre), c = sub(triangle[2], centre);
    // The edges (and so the normal and the windings) from the corners themselves, not from
    // the centred ones: centring rounds a sliver's width away near the grid's origin (1e-19
    // beside 17), and with it the plane the thin test needs. The cpu method takes them alike.
    const Vec3 edges[3] = {sub(triangle[1], triangle[0]), sub(triangle[2], triangle[1]), sub(triangle[0], triangle[2])};
    // The normal from the two shortest edges, as the cpu method takes it: e0 x e1 loses a
    // sliver's width to rounding (core/triangle_normal.h).
    const Vec3 n = stableTriangleNormal(triangle[0], triangle[1], triangle[2]);
    const double h = 0.5 + delta;
    return mode == Mode::Conservative ? triangleBoxSat(a, b, c, edges, n, h) : sixSeparatingTest(a, b, c, edges, n, h);
}

VoxelRange candidateVoxels(const Triangle& triangle, const std::array<std::int32_t, 3>& dims, double delta) {
    VoxelRange range;
    for (int axis = 0; axis < 3; ++axis) {
        const double lo = std::min({triangle[0][axis], triangle[1][axis], triangle[2][axis]});
        const double hi = std::max({triangle[0][axis], triangle[1][axis], triangle[2][axis]});
        // Voxel i's grown box [i - delta, i + 1 + delta] meets [lo, hi] iff
        // lo - 1 - delta <= i <= hi + delta. Clamp both ends in double before converting to
        // int so geometry far outside the grid, on either side, cannot overflow.
        const double outside = double(dims[axis]);
        const double first = std::ceil(std::clamp(lo - 1.0 - delta, -1.0, outside));
        const double last = std::floor(std::clamp(hi + delta, -1.0, outside));
        range.lo[axis] = std::max(0, int(first));
        range.hi[axis] = std::min(dims[axis] - 1, int(last));
    }
    return range;
}

}  // namespace hyvox::reference
