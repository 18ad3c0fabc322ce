// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The mesh as the GL shaders read it: voxel-space vertices split into an exact integer
// cell and a float fraction (computed in double here), and the usable triangles' indices.
// Shaders rebuild each triangle relative to its first vertex's cell, so precision does
// not degrade with distance from the grid origin. Both GL methods upload it.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hyvox/grid.h"
#include "hyvox/mesh.h"

namespace hyvox::gl {

struct GpuVertex {  // std430 layout of HyvoxVertex in shaders/common/mesh_input.glsl
    std::int32_t cell[3];
    float fraction[3];
};
static_assert(sizeof(GpuVertex) == 24, "must match the GLSL struct");

struct GpuMesh {
    std::vector<GpuVertex> vertices;
    std::vector<std::uint32_t> triangles;  // 3 per usable triangle
    std::uint64_t fingerprint = 0;         // of the whole mesh's positions and indices (cutoff cache key)
    std::size_t triangleCount() const { return triangles.size() / 3; }
};

// Cells are relative to voxel `offset` of the grid (the tile being filled): the voxel-space
// position is computed in the whole grid, then the integer offset is taken off the cell,
// exactly, so a tile's shaders see the same fractions as an untiled run.
GpuMesh makeGpuMesh(const ValidatedMesh& mesh, const GridSpec& grid,
                    const std::array<std::int32_t, 3>& offset = {0, 0, 0});

// Triangle t's corners in voxel space (cell + fraction, in double).
using TriangleCorners = std::array<std::array<double, 3>, 3>;
TriangleCorners triangleCorners(const GpuMesh& mesh, std::size_t t);

// The triangle's area projected on its dominant plane, in voxel units² (the measure the
// hybrid's classifier compares with the cutoff).
double projectedArea(const TriangleCorners& p);

}  // namespace hyvox::gl
