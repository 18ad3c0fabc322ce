// SPDX-License-Identifier: GPL-3.0-or-later
#include "tessellation/surface_attributes.h"

#include <array>
#include <cmath>

namespace hyvox::tessellation {
namespace {

using Vec3d = std::array<double, 3>;

Vec3d load(const std::vector<float>& v, std::uint32_t i) {
    return {double(v[3 * std::size_t(i)]), double(v[3 * std::size_t(i) + 1]), double(v[3 * std::size_t(i) + 2])};
}
Vec3d sub(const Vec3d& a, const Vec3d& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3d cross(const Vec3d& a, const Vec3d& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3d normalized(const Vec3d& a) {
    const double len = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    if (!(len > 0)) return {0, 0, 1};
    const double inv = 1.0 / len;
    return {a[0] * inv, a[1] * inv, a[2] * inv};
}

}  // namespace

SurfaceAttributes::SurfaceAttributes(const ValidatedMesh& mesh, const GridSpec& grid) {
    const std::size_t n = mesh.view.vertex_count;
    const float* world = mesh.view.positions;
    positions_.resize(3 * n);
    for (std::size_t v = 0; v < n; ++v) {
        const float* q = world + 3 * v;
        const std::array<double, 3> p = grid.toVoxel(std::array<float, 3>{q[0], q[1], q[2]});
        for (int axis = 0; axis < 3; ++axis) positions_[3 * v + axis] = float(p[axis]);
    }

    std::vector<double> normals(3 * n, 0.0);
    if (mesh.view.normals) {
        for (std::size_t i = 0; i < 3 * n; ++i) normals[i] = mesh.view.normals[i];
    } else {
        // Area-weighted: the unnormalized face normal is twice the area times the unit normal.
        for (std::uint32_t t : mesh.usable) {
            const std::uint32_t* idx = mesh.view.triangles + 3 * std::size_t(t);
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

}  // namespace hyvox::tessellation
