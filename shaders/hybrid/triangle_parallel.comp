// SPDX-License-Identifier: GPL-3.0-or-later
// Method `triangle`: one invocation per triangle does the whole factored test (section 3.2).
#include "common/voxelize_triangle.glsl"

#include "common/compute_index.glsl"

void main() {
    const uint tri = invocationTriangle();
    if (tri >= triangleCount) return;
    const LoadedTriangle l = loadForVoxelizing(tri);
    if (beyondItsChunks(l, invocationChunk())) return;
    if (invocationChunk() == 0u && voxelizeIfInsideOneVoxel(l)) return;
    const TriangleSetup t = prepareLoaded(l);
    if (!clippedAway(t)) voxelizeTriangleChunk(t, tri, invocationChunk());
}
