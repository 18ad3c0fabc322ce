// SPDX-License-Identifier: GPL-3.0-or-later
// Triangles in voxel space, loaded relative to a per-triangle local origin: the integer
// cell of the first vertex. Vertices arrive as an exact integer cell plus a float
// fraction (computed in double on the CPU), so small triangles keep ~1e-7 voxel precision
// wherever they are in a large grid.
#include "common/bindings.glsl"

struct HyvoxVertex {
    int cx, cy, cz;
    float fx, fy, fz;
};
layout(std430, binding = HYVOX_SSBO_VERTICES) readonly restrict buffer Vertices { HyvoxVertex vertices[]; };
layout(std430, binding = HYVOX_SSBO_TRIANGLES) readonly restrict buffer Triangles { uint triangleIndices[]; };
layout(location = HYVOX_LOC_TRIANGLE_COUNT) uniform uint triangleCount;

ivec3 vertexCell(uint v) { return ivec3(vertices[v].cx, vertices[v].cy, vertices[v].cz); }
vec3 vertexFraction(uint v) { return vec3(vertices[v].fx, vertices[v].fy, vertices[v].fz); }

void loadTriangle(uint tri, out ivec3 origin, out vec3 v0, out vec3 v1, out vec3 v2) {
    const uint i0 = triangleIndices[3u * tri], i1 = triangleIndices[3u * tri + 1u], i2 = triangleIndices[3u * tri + 2u];
    origin = vertexCell(i0);
    v0 = vertexFraction(i0);
    v1 = vec3(vertexCell(i1) - origin) + vertexFraction(i1);
    v2 = vec3(vertexCell(i2) - origin) + vertexFraction(i2);
}
