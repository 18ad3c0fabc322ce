// SPDX-License-Identifier: GPL-3.0-or-later
#include "hyvox/mesh.h"

#include <cmath>
#include <limits>
#include <string>
#include <tuple>

#include "hyvox/errors.h"

namespace hyvox {
namespace {

bool isZeroArea(const float* a, const float* b, const float* c) {
    // Double products of float inputs are exact enough that "exactly zero" is meaningful:
    // every backend skips the same triangles.
    const double e0[3] = {double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2]};
    const double e1[3] = {double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2]};
    const double n0 = e0[1] * e1[2] - e0[2] * e1[1];
    const double n1 = e0[2] * e1[0] - e0[0] * e1[2];
    const double n2 = e0[0] * e1[1] - e0[1] * e1[0];
    return n0 == 0.0 && n1 == 0.0 && n2 == 0.0;
}

}  // namespace

ValidatedMesh validate(const MeshView& mesh, Interrupter* interrupter) {
    if (mesh.vertex_count == 0 || mesh.triangle_count == 0)
        throw InvalidInput("the mesh is empty (" + std::to_string(mesh.vertex_count) + " vertices, " +
                           std::to_string(mesh.triangle_count) + " triangles)");
    if (!mesh.positions || !mesh.triangles) throw InvalidInput("the mesh has no vertex or triangle data");
    if (mesh.vertex_count > std::numeric_limits<std::uint32_t>::max())
        throw InvalidInput("too many vertices for 32-bit indices");

    for (std::size_t v = 0; v < mesh.vertex_count; ++v)
        for (int a = 0; a < 3; ++a)
            if (!std::isfinite(mesh.positions[3 * v + a]))
                throw InvalidInput("vertex " + std::to_string(v) + " has a non-finite coordinate (NaN or Inf)");

    for (const auto& [values, width, name] : {std::tuple{mesh.uvs, 2, "UV"}, std::tuple{mesh.normals, 3, "normal"}})
        if (values)
            for (std::size_t i = 0; i < mesh.vertex_count * width; ++i)
                if (!std::isfinite(values[i]))
                    throw InvalidInput("vertex " + std::to_string(i / width) + " has a non-finite " + name);

    ValidatedMesh out;
    out.view = mesh;
    out.usable.reserve(mesh.triangle_count);
    const double inf = std::numeric_limits<double>::infinity();
    out.bounds.min = {inf, inf, inf};
    out.bounds.max = {-inf, -inf, -inf};
    for (std::size_t t = 0; t < mesh.triangle_count; ++t) {
        if (t % kInterruptCheckTriangles == 0) throwIfInterrupted(interrupter);
        const std::uint32_t* idx = mesh.triangles + 3 * t;
        for (int c = 0; c < 3; ++c)
            if (idx[c] >= mesh.vertex_count)
                throw InvalidInput("triangle " + std::to_string(t) + " refers to vertex " + std::to_string(idx[c]) +
                                   ", but the mesh has only " + std::to_string(mesh.vertex_count) + " vertices");
        const float* a = mesh.positions + 3 * std::size_t(idx[0]);
        const float* b = mesh.positions + 3 * std::size_t(idx[1]);
        const float* c = mesh.positions + 3 * std::size_t(idx[2]);
        if (idx[0] == idx[1] || idx[1] == idx[2] || idx[0] == idx[2] || isZeroArea(a, b, c)) {
            ++out.degenerate_count;
            continue;
        }
        out.usable.push_back(std::uint32_t(t));
        for (const float* p : {a, b, c})
            for (int axis = 0; axis < 3; ++axis) {
                if (p[axis] < out.bounds.min[axis]) out.bounds.min[axis] = p[axis];
                if (p[axis] > out.bounds.max[axis]) out.bounds.max[axis] = p[axis];
            }
    }
    if (out.usable.empty())
        throw InvalidInput("all " + std::to_string(mesh.triangle_count) +
                           " triangles are degenerate (zero area); nothing to voxelize");
    return out;
}

}  // namespace hyvox
