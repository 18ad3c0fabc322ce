// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The surface the tessellation method samples, on the CPU: a mesh in voxel space with
// per-vertex normals and UVs, evaluated flat or as PN-triangles (Vlachos et al. 2001) and
// displaced along the interpolated normal. The shaders (shaders/tessellation/surface.glsl)
// evaluate the same formulas; tests compare the two.
#include <array>
#include <cstdint>
#include <vector>

#include "hyvox/grid.h"
#include "hyvox/mesh.h"
#include "tessellation/displacement_map.h"

namespace hyvox::tessellation {

using Vec3d = std::array<double, 3>;

struct SurfacePoint {
    Vec3d position;  // voxel space
    Vec3d normal;    // unit
    std::array<double, 2> uv;
};

class Surface {
public:
    // Positions go to voxel space (in double, rounded once to float, as uploaded to the GPU);
    // normals are the mesh's own (normalized) or area-weighted ones; UVs are zero if absent.
    Surface(const ValidatedMesh& mesh, const GridSpec& grid);

    const std::vector<float>& normals() const { return normals_; }  // unit, N×3
    const std::vector<float>& uvs() const { return uvs_; }          // N×2

    // The corner positions of triangle t (voxel space).
    std::array<std::array<float, 3>, 3> corners(std::uint32_t t) const;

    // The point at barycentric (w0, w1, w2) of triangle t: flat or PN, then displaced by
    // (map(uv) - midlevel) * strength / voxel_size voxel units along the normal when a map is given.
    SurfacePoint evaluate(std::uint32_t t, const Vec3d& bary, bool pn) const;
    SurfacePoint evaluate(std::uint32_t t, const Vec3d& bary, bool pn, const DisplacementMap& map,
                          double strength_voxels, double midlevel) const;

private:
    std::vector<float> positions_, normals_, uvs_;
    const std::uint32_t* triangles_ = nullptr;
};

}  // namespace hyvox::tessellation
