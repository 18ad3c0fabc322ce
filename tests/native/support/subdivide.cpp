// SPDX-License-Identifier: GPL-3.0-or-later
#include "support/subdivide.h"

#include <unordered_map>

#include "hyvox/errors.h"
#include "support/surface_twin.h"
#include "tessellation/displacement_map.h"

namespace hyvox::test {

Mesh midpointSubdivide(const MeshView& view, int levels) {
    Mesh mesh;
    mesh.positions.assign(view.positions, view.positions + 3 * view.vertex_count);
    mesh.triangles.assign(view.triangles, view.triangles + 3 * view.triangle_count);
    if (view.uvs) mesh.uvs.assign(view.uvs, view.uvs + 2 * view.vertex_count);
    for (int level = 0; level < levels; ++level) {
        std::unordered_map<std::uint64_t, std::uint32_t> midpoints;
        midpoints.reserve(mesh.triangles.size());
        auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const std::uint64_t key = a < b ? (std::uint64_t(a) << 32 | b) : (std::uint64_t(b) << 32 | a);
            auto [it, inserted] = midpoints.try_emplace(key, std::uint32_t(mesh.positions.size() / 3));
            if (inserted) {
                for (int axis = 0; axis < 3; ++axis)
                    mesh.positions.push_back(
                        0.5f * (mesh.positions[3 * std::size_t(a) + axis] + mesh.positions[3 * std::size_t(b) + axis]));
                if (!mesh.uvs.empty())
                    for (int k = 0; k < 2; ++k)
                        mesh.uvs.push_back(0.5f *
                                           (mesh.uvs[2 * std::size_t(a) + k] + mesh.uvs[2 * std::size_t(b) + k]));
            }
            return it->second;
        };
        std::vector<std::uint32_t> next;
        next.reserve(4 * mesh.triangles.size());
        for (std::size_t t = 0; t < mesh.triangles.size(); t += 3) {
            const std::uint32_t a = mesh.triangles[t], b = mesh.triangles[t + 1], c = mesh.triangles[t + 2];
            const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
            for (std::uint32_t v : {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca}) next.push_back(v);
        }
        mesh.triangles.swap(next);
    }
    return mesh;
}

Mesh subdivideAndDisplace(const ValidatedMesh& mesh, const GridSpec& grid, const TessellationOptions& options,
                          int pieces) {
    if (pieces < 1) throw InvalidInput("subdivideAndDisplace: pieces must be at least 1");
    const SurfaceTwin surface(mesh, grid);
    const tessellation::DisplacementMap map = tessellation::DisplacementMap::fromOptions(options);
    const double strength = options.displacement_strength / grid.voxel_size;
    Mesh out;
    // Lattice point (i, j) of a triangle: barycentric (1 - (i+j)/n, i/n, j/n).
    auto vertex = [&](std::uint32_t t, int i, int j) {
        const double u = double(i) / pieces, v = double(j) / pieces;
        const SurfacePoint p = surface.evaluate(t, {1.0 - u - v, u, v}, options.pn_triangles, map, strength,
                                                options.displacement_midlevel);
        for (int axis = 0; axis < 3; ++axis)
            out.positions.push_back(float(grid.origin[axis] + p.position[axis] * grid.voxel_size));  // back to world
        return std::uint32_t(out.positions.size() / 3 - 1);
    };
    for (std::uint32_t t : mesh.usable) {
        std::vector<std::uint32_t> lattice;  // row-major over i, j with i + j <= n
        for (int i = 0; i <= pieces; ++i)
            for (int j = 0; j + i <= pieces; ++j) lattice.push_back(vertex(t, i, j));
        auto at = [&](int i, int j) { return lattice[std::size_t(i * (pieces + 1) - i * (i - 1) / 2 + j)]; };
        for (int i = 0; i < pieces; ++i)
            for (int j = 0; j + i < pieces; ++j) {
                for (std::uint32_t v : {at(i, j), at(i + 1, j), at(i, j + 1)}) out.triangles.push_back(v);
                if (i + j + 1 < pieces)
                    for (std::uint32_t v : {at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)}) out.triangles.push_back(v);
            }
    }
    return out;
}

}  // namespace hyvox::test
