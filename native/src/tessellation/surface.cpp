// SPDX-License-Identifier: GPL-3.0-or-later
#include "tessellation/surface.h"

#include <cmath>

namespace hyvox::tessellation {
namespace {

Vec3d load(const std::vector<float>& v, std::uint32_t i) {
    return {double(v[3 * std::size_t(i)]), double(v[3 * std::size_t(i) + 1]), double(v[3 * std::size_t(i) + 2])};
}
Vec3d add(const Vec3d& a, const Vec3d& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec3d sub(const Vec3d& a, const Vec3d& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3d mul(const Vec3d& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
double dot(const Vec3d& a, const Vec3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3d cross(const Vec3d& a, const Vec3d& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3d normalized(const Vec3d& a) {
    const double len = std::sqrt(dot(a, a));
    return len > 0 ? mul(a, 1.0 / len) : Vec3d{0, 0, 1};
}

}  // namespace

Surface::Surface(const ValidatedMesh& mesh, const GridSpec& grid) : triangles_(mesh.view.triangles) {
    const std::size_t n = mesh.view.vertex_count;
    positions_.resize(3 * n);
    for (std::size_t i = 0; i < 3 * n; ++i)
        positions_[i] = float((double(mesh.view.positions[i]) - grid.origin[i % 3]) / grid.voxel_size);

    std::vector<double> normals(3 * n, 0.0);
    if (mesh.view.normals) {
        for (std::size_t i = 0; i < 3 * n; ++i) normals[i] = mesh.view.normals[i];
    } else {
        // Area-weighted: the unnormalized face normal is twice the area times the unit normal.
        for (std::uint32_t t : mesh.usable) {
            const std::uint32_t* idx = triangles_ + 3 * std::size_t(t);
            const Vec3d a = load(positions_, idx[0]), b = load(positions_, idx[1]), c = load(positions_, idx[2]);
            const Vec3d face = cross(sub(b, a), sub(c, a));
            for (int corner = 0; corner < 3; ++corner)
                for (int axis = 0; axis < 3; ++axis) normals[3 * std::size_t(idx[corner]) + axis] += face[axis];
        }
    }
    normals_.resize(3 * n);
    for (std::size_t v = 0; v < n; ++v) {
        const Vec3d unit = normalized({normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]});
        for (int axis = 0; axis < 3; ++axis) normals_[3 * v + axis] = float(unit[axis]);
    }
    uvs_.assign(2 * n, 0.0f);
    if (mesh.view.uvs) uvs_.assign(mesh.view.uvs, mesh.view.uvs + 2 * n);
}

std::array<std::array<float, 3>, 3> Surface::corners(std::uint32_t t) const {
    std::array<std::array<float, 3>, 3> out{};
    for (int c = 0; c < 3; ++c)
        for (int axis = 0; axis < 3; ++axis) out[c][axis] = positions_[3 * std::size_t(triangles_[3 * t + c]) + axis];
    return out;
}

SurfacePoint Surface::evaluate(std::uint32_t t, const Vec3d& w, bool pn) const {
    const std::uint32_t* idx = triangles_ + 3 * std::size_t(t);
    const Vec3d p[3] = {load(positions_, idx[0]), load(positions_, idx[1]), load(positions_, idx[2])};
    const Vec3d n[3] = {load(normals_, idx[0]), load(normals_, idx[1]), load(normals_, idx[2])};
    SurfacePoint out;
    for (int k = 0; k < 2; ++k)
        out.uv[k] = w[0] * uvs_[2 * std::size_t(idx[0]) + k] + w[1] * uvs_[2 * std::size_t(idx[1]) + k] +
                    w[2] * uvs_[2 * std::size_t(idx[2]) + k];
    if (!pn) {
        out.position = add(add(mul(p[0], w[0]), mul(p[1], w[1])), mul(p[2], w[2]));
        out.normal = normalized(add(add(mul(n[0], w[0]), mul(n[1], w[1])), mul(n[2], w[2])));
        return out;
    }
    // Cubic Bézier control points: each edge third pulled onto the tangent plane of its
    // nearer corner; the centre b111 lifted by half its offset from the flat centre.
    auto edgePoint = [&](int i, int j) {
        const double wij = dot(sub(p[j], p[i]), n[i]);
        return mul(sub(add(mul(p[i], 2.0), p[j]), mul(n[i], wij)), 1.0 / 3.0);
    };
    const Vec3d b210 = edgePoint(0, 1), b120 = edgePoint(1, 0), b021 = edgePoint(1, 2);
    const Vec3d b012 = edgePoint(2, 1), b102 = edgePoint(2, 0), b201 = edgePoint(0, 2);
    const Vec3d e = mul(add(add(add(b210, b120), add(b021, b012)), add(b102, b201)), 1.0 / 6.0);
    const Vec3d v = mul(add(add(p[0], p[1]), p[2]), 1.0 / 3.0);
    const Vec3d b111 = add(e, mul(sub(e, v), 0.5));
    const double u0 = w[0], u1 = w[1], u2 = w[2];
    Vec3d pos = add(add(mul(p[0], u0 * u0 * u0), mul(p[1], u1 * u1 * u1)), mul(p[2], u2 * u2 * u2));
    pos = add(pos, mul(b210, 3 * u0 * u0 * u1));
    pos = add(pos, mul(b120, 3 * u0 * u1 * u1));
    pos = add(pos, mul(b201, 3 * u0 * u0 * u2));
    pos = add(pos, mul(b021, 3 * u1 * u1 * u2));
    pos = add(pos, mul(b102, 3 * u0 * u2 * u2));
    pos = add(pos, mul(b012, 3 * u1 * u2 * u2));
    pos = add(pos, mul(b111, 6 * u0 * u1 * u2));
    out.position = pos;
    // Quadratic normals: mid-edge normals mirrored across the plane perpendicular to the edge.
    auto edgeNormal = [&](int i, int j) {
        const Vec3d d = sub(p[j], p[i]);
        const double vij = 2.0 * dot(d, add(n[i], n[j])) / dot(d, d);
        return normalized(sub(add(n[i], n[j]), mul(d, vij)));
    };
    const Vec3d n110 = edgeNormal(0, 1), n011 = edgeNormal(1, 2), n101 = edgeNormal(2, 0);
    Vec3d nor = add(add(mul(n[0], u0 * u0), mul(n[1], u1 * u1)), mul(n[2], u2 * u2));
    nor = add(add(add(nor, mul(n110, u0 * u1)), mul(n011, u1 * u2)), mul(n101, u0 * u2));
    out.normal = normalized(nor);
    return out;
}

SurfacePoint Surface::evaluate(std::uint32_t t, const Vec3d& bary, bool pn, const DisplacementMap& map,
                               double strength_voxels, double midlevel) const {
    SurfacePoint out = evaluate(t, bary, pn);
    if (map.empty()) return out;
    const double offset = (double(map.sample(out.uv[0], out.uv[1])) - midlevel) * strength_voxels;
    out.position = add(out.position, mul(out.normal, offset));
    return out;
}

}  // namespace hyvox::tessellation
