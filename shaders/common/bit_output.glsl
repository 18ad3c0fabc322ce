// SPDX-License-Identifier: GPL-3.0-or-later
// One bit per voxel in OpenVDB's leaf layout (common/leaf_layout.glsl). A run writes one
// tile of whole bricks along x (slab); bricks are counted from the tile's first one.
// With HYVOX_VOXEL_LIST the bit grid doubles as the per-voxel mutex of section 3.5: only
// the invocation that flips a bit from 0 to 1 appends the voxel to the list.
// With HYVOX_ATTRIBUTE_PAIRS every (voxel, triangle) pair that sets a bit is appended to the
// pair list, which shaders/hybrid/clip_pieces.comp then clips (colour and normal voxels).
#include "common/bindings.glsl"
#include "common/leaf_layout.glsl"

layout(std430, binding = HYVOX_SSBO_BITS) restrict buffer Bits { uint bits[]; };
layout(location = HYVOX_LOC_GRID_DIMS) uniform ivec3 gridDims;
layout(location = HYVOX_LOC_SLAB) uniform ivec2 slabX;

#if HYVOX_VOXEL_LIST
layout(std430, binding = HYVOX_SSBO_VOXEL_LIST) restrict buffer VoxelList {
    uint voxelListCount;  // may exceed the capacity: the host then retries with more room
    uint voxelListPad[3];     // entries start at byte 16
    uint voxelListEntries[];  // x, y, z per voxel
};
layout(location = HYVOX_LOC_LIST_CAPACITY) uniform uint voxelListCapacity;
#endif

#if HYVOX_ATTRIBUTE_PAIRS
layout(std430, binding = HYVOX_SSBO_PAIRS) restrict buffer AttributePairs {
    uint pairCount;  // may exceed the capacity: the host then retries with more room
    uint pairPad[3];  // entries start at byte 16
    uvec4 pairs[];    // x, y, z (tile voxel), triangle
};
layout(location = HYVOX_LOC_PAIR_CAPACITY) uniform uint pairCapacity;

void appendPair(ivec3 p, uint tri) {
    const uint slot = atomicAdd(pairCount, 1u);
    if (slot < pairCapacity) pairs[slot] = uvec4(uvec3(p), tri);
}
#endif

// The tile's inclusive voxel range, unswizzled.
ivec3 clipLow() { return ivec3(slabX.x, 0, 0); }
ivec3 clipHigh() { return ivec3(slabX.y - 1, gridDims.y - 1, gridDims.z - 1); }

// p: unswizzled global voxel inside the tile; tri: the triangle that overlaps it.
void setVoxel(ivec3 p, uint tri) {
#if HYVOX_ATTRIBUTE_PAIRS
    appendPair(p, tri);
#endif
    const uvec3 inTile = uvec3(p - ivec3(slabX.x, 0, 0));  // slabX.x is a multiple of 8
    const uint n = leafBit(inTile);
    const uint word = leafWord(leafBrick(inTile, leafBrickCounts(gridDims)), n);
    const uint mask = leafMask(n);
#if HYVOX_VOXEL_LIST
    const uint before = atomicOr(bits[word], mask);
    if ((before & mask) == 0u) {
        const uint slot = atomicAdd(voxelListCount, 1u);
        if (slot < voxelListCapacity) {
            voxelListEntries[3u * slot] = uint(p.x);
            voxelListEntries[3u * slot + 1u] = uint(p.y);
            voxelListEntries[3u * slot + 2u] = uint(p.z);
        }
    }
#else
    atomicOr(bits[word], mask);
#endif
}
