// SPDX-License-Identifier: GPL-3.0-or-later
#include "gl/gpu_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/clamp_coord.h"

namespace hyvox::gl {
namespace {

std::uint64_t mix(std::uint64_t h, std::uint64_t word) {
    h ^= word + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    return h * 0xff51afd7ed558ccdull;
}

std::uint64_t fingerprintOf(const void* data, std::size_t bytes, std::uint64_t h) {
    const auto* p = static_cast<const unsigned char*>(data);
    std::size_t i = 0;
    for (; i + 8 <= bytes; i += 8) {
        std::uint64_t word;
        std::memcpy(&word, p + i, 8);
        h = mix(h, word);
    }
    for (; i < bytes; ++i) h = mix(h, p[i]);
    return h;
}

}  // namespace

GpuMesh makeGpuMesh(const ValidatedMesh& mesh, const GridSpec& grid, const std::array<std::int32_t, 3>& offset) {
    GpuMesh out;
    const MeshView& view = mesh.view;
    out.vertices.resize(view.vertex_count);
    for (std::size_t v = 0; v < view.vertex_count; ++v) {
        const float* p = view.positions + 3 * v;
        const std::array<double, 3> voxel = grid.toVoxel(std::array<float, 3>{p[0], p[1], p[2]});
        for (int a = 0; a < 3; ++a) {
            // Far-away vertices are clamped as the cpu backend clamps them (int conversion
            // stays defined); the clipped part inside the grid is then equally approximate on both.
            const double x = clampCoord(voxel[a]);
            const double cell = std::floor(x);
            out.vertices[v].cell[a] = std::int32_t(cell) - offset[a];
            out.vertices[v].fraction[a] = float(x - cell);
        }
    }
    out.triangles.reserve(mesh.usable.size() * 3);
    for (std::uint32_t t : mesh.usable)
        for (int c = 0; c < 3; ++c) out.triangles.push_back(view.triangles[3 * std::size_t(t) + c]);
    // Of the whole mesh (not the tile's triangles): every tile of one run shares it.
    std::uint64_t h = mix(view.vertex_count, view.triangle_count);
    h = fingerprintOf(view.positions, view.vertex_count * 3 * sizeof(float), h);
    out.fingerprint = fingerprintOf(view.triangles, view.triangle_count * 3 * sizeof(std::uint32_t), h);
    return out;
}

TriangleCorners triangleCorners(const GpuMesh& mesh, std::size_t t) {
    TriangleCorners p;
    for (int c = 0; c < 3; ++c) {
        const GpuVertex& v = mesh.vertices[mesh.triangles[3 * t + c]];
        for (int a = 0; a < 3; ++a) p[c][a] = double(v.cell[a]) + double(v.fraction[a]);
    }
    return p;
}

double projectedArea(const TriangleCorners& p) {
    const double e0[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const double e1[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    const double n[3] = {e0[1] * e1[2] - e0[2] * e1[1], e0[2] * e1[0] - e0[0] * e1[2], e0[0] * e1[1] - e0[1] * e1[0]};
    return 0.5 * std::max({std::fabs(n[0]), std::fabs(n[1]), std::fabs(n[2])});
}

}  // namespace hyvox::gl
