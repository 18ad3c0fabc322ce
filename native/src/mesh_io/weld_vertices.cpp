// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh_io/weld_vertices.h"

#include <cstdint>
#include <cstring>
#include <unordered_map>
#include <vector>

namespace hyvox::mesh_io {

void weldIdenticalVertices(Mesh& mesh) {
    const std::size_t n = mesh.vertexCount();
    const std::size_t colors = mesh.hasColors() ? 4 : 0;
    const std::size_t uvs = mesh.hasUvs() ? 2 : 0;
    struct Key {
        float v[9];
        std::size_t size;
        bool operator==(const Key& o) const { return std::memcmp(v, o.v, size * sizeof(float)) == 0; }
    };
    struct Hash {
        std::size_t operator()(const Key& k) const {
            std::uint64_t h = 1469598103934665603ull;
            const auto* bytes = reinterpret_cast<const unsigned char*>(k.v);
            for (std::size_t b = 0; b < k.size * sizeof(float); ++b) h = (h ^ bytes[b]) * 1099511628211ull;
            return std::size_t(h);
        }
    };
    std::unordered_map<Key, std::uint32_t, Hash> index;
    index.reserve(n);
    std::vector<std::uint32_t> remap(n);
    Mesh out;
    out.colors_alpha = mesh.colors_alpha;
    out.warnings = std::move(mesh.warnings);
    for (std::size_t v = 0; v < n; ++v) {
        Key key{};
        key.size = 3 + colors + uvs;
        std::memcpy(key.v, &mesh.positions[3 * v], 3 * sizeof(float));
        if (colors) std::memcpy(key.v + 3, &mesh.colors[4 * v], 4 * sizeof(float));
        if (uvs) std::memcpy(key.v + 3 + colors, &mesh.uvs[2 * v], 2 * sizeof(float));
        const auto [it, inserted] = index.emplace(key, std::uint32_t(out.vertexCount()));
        if (inserted) {
            out.positions.insert(out.positions.end(), key.v, key.v + 3);
            if (colors) out.colors.insert(out.colors.end(), key.v + 3, key.v + 7);
            if (uvs) out.uvs.insert(out.uvs.end(), key.v + 3 + colors, key.v + 5 + colors);
        }
        remap[v] = it->second;
    }
    out.triangles = std::move(mesh.triangles);
    for (std::uint32_t& t : out.triangles) t = remap[t];
    mesh = std::move(out);
}

}  // namespace hyvox::mesh_io
