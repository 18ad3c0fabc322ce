// SPDX-License-Identifier: GPL-3.0-or-later
// Section 3.2's point injection, shared by the geometry shader (one point per micro-triangle)
// and the compute shader (one point per triangle the tessellator would leave whole): a bit
// per voxel (atomicOr, common/leaf_layout.glsl) and, with COUNTS, the number of points per
// voxel. Integer atomic adds commute, so counts are the same on every run.
// Counts live in 512-entry blocks handed out to 8³ bricks on first touch, so only bricks
// the surface reaches cost memory.
#include "tessellation/bindings.glsl"
#include "common/leaf_layout.glsl"

layout(location = HYVOX_LOC_GRID_DIMS) uniform ivec3 gridDims;
layout(std430, binding = HYVOX_SSBO_BITS) coherent restrict buffer Bits { uint bits[]; };
layout(std430, binding = HYVOX_TESS_SSBO_COUNTERS) coherent restrict buffer Counters { uint counters[]; };
#ifdef COUNTS
layout(std430, binding = HYVOX_TESS_SSBO_BRICK_TABLE) coherent restrict buffer BrickTable { uint brickBlock[]; };
layout(std430, binding = HYVOX_TESS_SSBO_COUNT_POOL) coherent restrict buffer CountPool { uint countPool[]; };
layout(location = HYVOX_TESS_LOC_POOL_BLOCKS) uniform uint poolBlocks;
layout(location = HYVOX_TESS_LOC_PREFILLED) uniform uint prefilled;
#endif
#ifdef ATTRIBUTES
#include "tessellation/point_values.glsl"
#endif

// A point at `local` voxel units from the integer cell `origin`, at barycentrics `bary` of
// usable triangle `tri` (used by ATTRIBUTES only).
void injectPoint(ivec3 origin, vec3 local, uint tri, vec3 bary) {
    atomicAdd(counters[HYVOX_TESS_COUNTER_POINTS], 1u);
    const ivec3 voxel = origin + ivec3(floor(local));
    if (any(lessThan(voxel, ivec3(0))) || any(greaterThanEqual(voxel, gridDims))) {
        atomicAdd(counters[HYVOX_TESS_COUNTER_CLIPPED], 1u);
        return;
    }
    const uvec3 v = uvec3(voxel);
    const uint brick = leafBrick(v, leafBrickCounts(gridDims));
    const uint n = leafBit(v);
    const uint word = leafWord(brick, n), mask = leafMask(n);
    // Dense meshes put many points in one voxel: skip the atomic when the bit is already set.
    if ((bits[word] & mask) == 0u) atomicOr(bits[word], mask);
#ifdef COUNTS
    uint block = brickBlock[brick];
    if (block == 0u && prefilled == 0u) {
        // Lock-free first touch: take a fresh block, publish it unless another point won the
        // race (then use the winner's and leave ours unused). Running out is detected on the
        // host, which then draws again into a table it filled in from this run's bits.
        const uint mine = atomicAdd(counters[HYVOX_TESS_COUNTER_BLOCKS], 1u) + 1u;
        if (mine <= poolBlocks) {
            const uint previous = atomicCompSwap(brickBlock[brick], 0u, mine);
            block = previous == 0u ? mine : previous;
        } else {
            block = atomicOr(brickBlock[brick], 0u);  // another point may have won meanwhile
        }
    }
    if (block != 0u) {
        atomicAdd(countPool[(block - 1u) * 512u + n], 1u);
#ifdef ATTRIBUTES
        addPointValues(block, n, tri, bary);
#endif
    }
#endif
}
