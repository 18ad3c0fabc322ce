// SPDX-License-Identifier: GPL-3.0-or-later
// Per-triangle preparation shared by every path, and the triangle-parallel loop
// (section 3.2): columns of the dominant plane, 2D test, depth range, remaining planes.
#include "common/mesh_input.glsl"
#include "common/overlap.glsl"
#include "common/bit_output.glsl"

struct LoadedTriangle {
    uint tri;  // its index in the triangle list
    ivec3 origin;  // unswizzled global cell of vertex 0
    vec3 v0, v1, v2;  // relative to origin
    vec3 n;  // cross of two edges (unswizzled)
};

LoadedTriangle loadForVoxelizing(uint tri) {
    LoadedTriangle l;
    l.tri = tri;
    loadTriangle(tri, l.origin, l.v0, l.v1, l.v2);
    l.n = cross(l.v1 - l.v0, l.v2 - l.v1);
    return l;
}

// The depth axis: the normal's dominant axis, or for a planeless triangle (a segment) its
// shortest, so each column holds few of its voxels (segmentDepthRange).
int depthAxis(LoadedTriangle l) {
    if (l.n != vec3(0.0)) return dominantAxis(l.n);
    const vec3 extent = max(l.v0, max(l.v1, l.v2)) - min(l.v0, min(l.v1, l.v2));
    return extent.x <= extent.y && extent.x <= extent.z ? 0 : (extent.y <= extent.z ? 1 : 2);
}

TriangleSetup prepareLoaded(LoadedTriangle l) {
    const int axis = depthAxis(l);
    return setupTriangle(swizzleToDominant(l.v0, axis), swizzleToDominant(l.v1, axis), swizzleToDominant(l.v2, axis),
                         swizzleToDominant(l.origin, axis), axis, swizzleToDominant(clipLow(), axis),
                         swizzleToDominant(clipHigh(), axis));
}

// Area of the projection on the dominant plane, voxel units² (the hybrid's classifier).
float projectedArea(LoadedTriangle l) { return 0.5 * max(abs(l.n.x), max(abs(l.n.y), abs(l.n.z))); }

// Conservative mode: a triangle whose bounding box touches no voxel but one (it lies inside
// that voxel's open box) overlaps exactly that voxel, so it needs none of the per-triangle
// setup. Most triangles of finely tessellated scans at usual resolutions are such (the
// 871k dragon's at 256³). Returns true when it handled l.
bool voxelizeIfInsideOneVoxel(LoadedTriangle l) {
#if HYVOX_THIN
    return false;  // thin mode may leave that voxel empty (the plane can miss its centre line)
#else
    const vec3 bmin = min(l.v0, min(l.v1, l.v2)), bmax = max(l.v0, max(l.v1, l.v2));
    const ivec3 lo = ivec3(ceil(bmin)) - 1, hi = ivec3(floor(bmax));
    if (lo != hi) return false;
    const ivec3 p = lo + l.origin;
    if (all(greaterThanEqual(p, clipLow())) && all(lessThanEqual(p, clipHigh()))) setVoxel(p, l.tri);
    return true;
#endif
}

bool clippedAway(TriangleSetup t) { return any(greaterThan(t.lo, t.hi)); }

// All voxels of global column (x, y) on the dominant plane; tri: the triangle t was set up from.
void voxelizeColumn(TriangleSetup t, ivec2 column, uint tri) {
    const vec2 q = vec2(column - t.origin.xy);
    if (!insideXY(t, q)) return;
    const ivec2 range = depthRange(t, q);
    for (int z = range.x; z <= range.y; ++z)
        if (insideRemaining(t, vec3(q, float(z - t.origin.z)))) setVoxel(unswizzle(ivec3(column, z), t.axis), tri);
}

// Chunks bound the loop iterations of one invocation. Mesa's llvmpipe caps the loop
// iterations of a whole shader invocation at 65535 (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS,
// one counter shared by all loops) and silently stops there, which would cut large
// triangles short; there the host sets a chunk side (at most 4 loop iterations per column)
// and dispatches one invocation per triangle and chunk. On hardware chunkSide is 0: one
// invocation walks the whole triangle, as in the paper.
layout(location = HYVOX_LOC_CHUNK_SIDE) uniform int chunkSide;

void voxelizeTriangleChunk(TriangleSetup t, uint tri, uint chunk) {
    ivec2 lo = t.lo.xy, hi = t.hi.xy;
    if (chunkSide > 0) {
        const ivec2 tiles = (hi - lo + chunkSide) / chunkSide;
        if (chunk >= uint(tiles.x * tiles.y)) return;
        lo += chunkSide * ivec2(int(chunk) % tiles.x, int(chunk) / tiles.x);
        hi = min(hi, lo + chunkSide - 1);
    } else if (chunk > 0u) {
        return;
    }
    for (int x = lo.x; x <= hi.x; ++x)
        for (int y = lo.y; y <= hi.y; ++y) voxelizeColumn(t, ivec2(x, y), tri);
}

// Chunks past the first have nothing to do for a triangle that fits one chunk: skip its
// setup (on llvmpipe every triangle gets as many chunk invocations as the largest needs).
bool beyondItsChunks(LoadedTriangle l, uint chunk) {
    if (chunk == 0u) return false;
    const vec3 extent = max(l.v0, max(l.v1, l.v2)) - min(l.v0, min(l.v1, l.v2));
    return max(extent.x, max(extent.y, extent.z)) + 2.0 < float(chunkSide);
}
