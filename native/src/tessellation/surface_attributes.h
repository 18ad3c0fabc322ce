// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The per-vertex data the tessellation shaders need besides the GPU mesh for PN-triangles
// (Vlachos et al. 2001) and displacement: unit normals (the mesh's own, or area-weighted
// from the voxel-space positions) and UVs. The shaders (shaders/tessellation/surface.glsl)
// evaluate the surface from them; tests/native/support/surface_twin.h does the same on the
// CPU to check them.
#include <cstdint>
#include <vector>

#include "hyvox/grid.h"
#include "hyvox/mesh.h"

namespace hyvox::tessellation {

class SurfaceAttributes {
public:
    // Positions go to voxel space (in double, rounded once to float, as uploaded to the GPU);
    // normals are the mesh's own (normalized) or area-weighted ones; UVs are zero if absent.
    SurfaceAttributes(const ValidatedMesh& mesh, const GridSpec& grid);

    const std::vector<float>& positions() const { return positions_; }  // voxel space, N×3
    const std::vector<float>& normals() const { return normals_; }      // unit, N×3
    const std::vector<float>& uvs() const { return uvs_; }              // N×2

private:
    std::vector<float> positions_, normals_, uvs_;
};

}  // namespace hyvox::tessellation
