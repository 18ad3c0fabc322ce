// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A hyvox mesh as the point and triangle arrays OpenVDB's mesh tools take, for the benchmarks'
// OpenVDB side (made before timing).
#include <openvdb/openvdb.h>

#include <vector>

#include "hyvox/mesh_io.h"

namespace hyvox::bench {

struct OpenVdbArrays {
    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> triangles;
};

// World positions, or with `to_index` index-space ones (as meshToVolume's adapter takes them).
inline OpenVdbArrays openvdbArrays(const Mesh& mesh, const openvdb::math::Transform* to_index = nullptr) {
    OpenVdbArrays out;
    out.points.resize(mesh.vertexCount());
    for (std::size_t v = 0; v < out.points.size(); ++v) {
        const openvdb::Vec3d p(mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]);
        out.points[v] = openvdb::Vec3s(to_index ? to_index->worldToIndex(p) : p);
    }
    out.triangles.resize(mesh.triangleCount());
    for (std::size_t t = 0; t < out.triangles.size(); ++t)
        out.triangles[t] = openvdb::Vec3I(mesh.triangles[3 * t], mesh.triangles[3 * t + 1], mesh.triangles[3 * t + 2]);
    return out;
}

}  // namespace hyvox::bench
