// SPDX-License-Identifier: GPL-3.0-or-later
#include "support/surface_twin.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace hyvox::test {
namespace {

Vec3d load(const std::vector<float>& v, std::uint32_t i) {
    return {double(v[3 * std::size_t(i)]), double(v[3 * std::size_t(i) + 1]), double(v[3 * std::size_t(i) + 2])};
}
Vec3d add(const Vec3d& a, const Vec3d& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec3d sub(const Vec3d& a, const Vec3d& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3d mul(const Vec3d& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
double dot(const Vec3d& a, const Vec3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3d normalized(const Vec3d& a) {
    const double len = std::sqrt(dot(a, a));
    return len > 0 ? mul(a, 1.0 / len) : Vec3d{0, 0, 1};
}

}  // namespace

float sampleHeight(const tessellation::DisplacementMap& map, double u, double v) {
    // GL's bilinear filter: texel coordinate x = u·W - 0.5, neighbours clamped to the edge.
    const int width = map.width(), height = map.height();
    const std::vector<float>& rows = map.bottomUpRows();
    const double x = u * width - 0.5, y = v * height - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    const double ax = x - fx, ay = y - fy;
    auto texel = [&](double tx, double ty) {
        const int ix = int(std::clamp(tx, 0.0, double(width - 1)));
        const int iy = int(std::clamp(ty, 0.0, double(height - 1)));
        return double(rows[std::size_t(iy) * width + ix]);
    };
    const double bottom = texel(fx, fy) * (1 - ax) + texel(fx + 1, fy) * ax;
    const double top = texel(fx, fy + 1) * (1 - ax) + texel(fx + 1, fy + 1) * ax;
    return float(bottom * (1 - ay) + top * ay);
}

SurfaceTwin::SurfaceTwin(const ValidatedMesh& mesh, const GridSpec& grid)
    : attributes_(mesh, grid), triangles_(mesh.view.triangles) {}

std::array<std::array<float, 3>, 3> SurfaceTwin::corners(std::uint32_t t) const {
    std::array<std::array<float, 3>, 3> out{};
    const std::vector<float>& positions = attributes_.positions();
    for (int c = 0; c < 3; ++c)
        for (int axis = 0; axis < 3; ++axis) out[c][axis] = positions[3 * std::size_t(triangles_[3 * t + c]) + axis];
    return out;
}

SurfacePoint SurfaceTwin::evaluate(std::uint32_t t, const Vec3d& w, bool pn) const {
    const std::uint32_t* idx = triangles_ + 3 * std::size_t(t);
    const std::vector<float>& positions = attributes_.positions();
    const std::vector<float>& normals = attributes_.normals();
    const std::vector<float>& uvs = attributes_.uvs();
    const Vec3d p[3] = {load(positions, idx[0]), load(positions, idx[1]), load(positions, idx[2])};
    const Vec3d n[3] = {load(normals, idx[0]), load(normals, idx[1]), load(normals, idx[2])};
    SurfacePoint out;
    for (int k = 0; k < 2; ++k)
        out.uv[k] = w[0] * uvs[2 * std::size_t(idx[0]) + k] + w[1] * uvs[2 * std::size_t(idx[1]) + k] +
            w[2] * uvs[2 * std::size_t(idx[2]) + k];
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

SurfacePoint SurfaceTwin::evaluate(std::uint32_t t, const Vec3d& bary, bool pn,
                                   const tessellation::DisplacementMap& map, double strength_voxels,
                                   double midlevel) const {
    SurfacePoint out = evaluate(t, bary, pn);
    if (map.empty()) return out;
    const double offset = (double(sampleHeight(map, out.uv[0], out.uv[1])) - midlevel) * strength_voxels;
    out.position = add(out.position, mul(out.normal, offset));
    return out;
}

}  // namespace hyvox::test
