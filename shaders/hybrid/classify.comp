// SPDX-License-Identifier: GPL-3.0-or-later
// Method `hybrid`, pass 1 (section 3.4.2): classify each triangle by the area of its
// projection on the dominant plane; voxelize small ones here at once and append large ones
// to a list whose length becomes the vertex count of pass 2's indirect draw.
#include "common/voxelize_triangle.glsl"

#include "common/compute_index.glsl"
layout(location = HYVOX_LOC_CUTOFF) uniform float cutoff;
layout(std430, binding = HYVOX_SSBO_DRAW) restrict buffer DrawCommand {
    uint drawVertexCount;  // DrawArraysIndirectCommand: count, instanceCount, first, baseInstance
    uint drawInstanceCount;
    uint drawFirst;
    uint drawBaseInstance;
};
layout(std430, binding = HYVOX_SSBO_LARGE) writeonly restrict buffer LargeTriangles { uint largeTriangles[]; };

void main() {
    const uint tri = invocationTriangle();
    if (tri >= triangleCount) return;
    const LoadedTriangle l = loadForVoxelizing(tri);
    if (beyondItsChunks(l, invocationChunk())) return;
    const bool large = projectedArea(l) > cutoff;
    if (!large && invocationChunk() == 0u && voxelizeIfInsideOneVoxel(l)) return;
    const TriangleSetup t = prepareLoaded(l);
    if (clippedAway(t)) return;
    if (large) {
        if (invocationChunk() == 0u) largeTriangles[atomicAdd(drawVertexCount, 3u) / 3u] = tri;
    } else {
        voxelizeTriangleChunk(t, tri, invocationChunk());
    }
}
