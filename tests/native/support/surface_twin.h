// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The tessellation method's surface on the CPU, the tests' twin of the shaders: flat or
// PN-triangles (Vlachos et al. 2001, shaders/tessellation/surface_eval.glsl) displaced along
// the interpolated normal by the height image, sampled like GL_LINEAR + GL_CLAMP_TO_EDGE
// (shaders/tessellation/height.glsl). Double precision, from the same per-vertex data the
// library uploads (tessellation::SurfaceAttributes).
#include <array>
#include <cstdint>

#include "hyvox/grid.h"
#include "hyvox/mesh.h"
#include "tessellation/displacement_map.h"
#include "tessellation/surface_attributes.h"

namespace hyvox::test {

using Vec3d = std::array<double, 3>;

// Bilinear at UV (u right, v up), texel centres at (x + 0.5) / width, clamped at the edges.
float sampleHeight(const tessellation::DisplacementMap& map, double u, double v);

struct SurfacePoint {
    Vec3d position;  // voxel space
    Vec3d normal;    // unit
    std::array<double, 2> uv;
};

class SurfaceTwin {
public:
    SurfaceTwin(const ValidatedMesh& mesh, const GridSpec& grid);

    // The corner positions of triangle t (voxel space, as uploaded).
    std::array<std::array<float, 3>, 3> corners(std::uint32_t t) const;

    // The point at barycentric (w0, w1, w2) of triangle t: flat or PN, then displaced by
    // (map(uv) - midlevel) * strength_voxels along the normal when a map is given.
    SurfacePoint evaluate(std::uint32_t t, const Vec3d& bary, bool pn) const;
    SurfacePoint evaluate(std::uint32_t t, const Vec3d& bary, bool pn, const tessellation::DisplacementMap& map,
                          double strength_voxels, double midlevel) const;

private:
    tessellation::SurfaceAttributes attributes_;
    const std::uint32_t* triangles_;
};

}  // namespace hyvox::test
