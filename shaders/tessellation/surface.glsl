// SPDX-License-Identifier: GPL-3.0-or-later
// The surface a patch samples, loaded from the mesh buffers: a triangle in voxel space,
// relative to the integer cell of its first vertex (common/mesh_input.glsl keeps it
// precise), with its vertex normals and UVs. Evaluation: tessellation/surface_eval.glsl.
#include "common/mesh_input.glsl"
#include "tessellation/bindings.glsl"
#include "tessellation/surface_eval.glsl"

layout(std430, binding = HYVOX_TESS_SSBO_NORMALS) readonly restrict buffer Normals { float normalData[]; };
layout(std430, binding = HYVOX_TESS_SSBO_UVS) readonly restrict buffer Uvs { float uvData[]; };

TriangleSurface loadSurface(uint tri) {
    TriangleSurface s;
    loadTriangle(tri, s.origin, s.p[0], s.p[1], s.p[2]);
#if defined(PN_TRIANGLES) || defined(DISPLACEMENT)
    for (int c = 0; c < 3; ++c) {
        const uint v = triangleIndices[3u * tri + uint(c)];
        s.n[c] = vec3(normalData[3u * v], normalData[3u * v + 1u], normalData[3u * v + 2u]);
        s.uv[c] = vec2(uvData[2u * v], uvData[2u * v + 1u]);
    }
#else
    for (int c = 0; c < 3; ++c) {  // flat points need neither (the host uploads none)
        s.n[c] = vec3(0.0);
        s.uv[c] = vec2(0.0);
    }
#endif
    return s;
}
