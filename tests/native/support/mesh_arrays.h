// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The one place test meshes held as flat arrays become a MeshView (TestMesh and
// TriangleSoup both store positions + triangles this way).
#include <cstdint>
#include <vector>

#include "hyvox/mesh.h"

namespace hyvox::test {

inline MeshView viewOf(const std::vector<float>& positions, const std::vector<std::uint32_t>& triangles) {
    MeshView v;
    v.positions = positions.data();
    v.vertex_count = positions.size() / 3;
    v.triangles = triangles.data();
    v.triangle_count = triangles.size() / 3;
    return v;
}

}  // namespace hyvox::test
