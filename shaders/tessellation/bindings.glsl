// SPDX-License-Identifier: GPL-3.0-or-later
// The tessellation method's binding points and uniform locations, on top of the shared ones
// (bits, vertices, triangles, grid dims). Included by the shaders and by
// native/src/tessellation/gl_tessellation.cpp, hence nothing but #defines.
#ifndef HYVOX_TESSELLATION_BINDINGS_GLSL
#define HYVOX_TESSELLATION_BINDINGS_GLSL
#include "common/bindings.glsl"

// Shader storage buffers (numbers after the shared ones)
#define HYVOX_TESS_SSBO_NORMALS 8       // float xyz per vertex, unit length
#define HYVOX_TESS_SSBO_UVS 9           // float uv per vertex
#define HYVOX_TESS_SSBO_PATCHES 10      // direct draw: uint triangle per patch
#define HYVOX_TESS_SSBO_SPLITS 11       // split draw: uvec4(triangle, pieces, first patch, 0)
#define HYVOX_TESS_SSBO_HEIGHTS 12      // displacement heights, rows bottom-up
#define HYVOX_TESS_SSBO_COUNTERS 13     // uint points, clipped points, count blocks taken
#define HYVOX_TESS_SSBO_BRICK_TABLE 14  // uint per 8³ brick: 0 or 1 + its block in the pool
#define HYVOX_TESS_SSBO_COUNT_POOL 15   // uint counts, 512 per block (OpenVDB leaf order)
// Attribute voxels (ATTRIBUTES): tessellation/point_values.glsl
#define HYVOX_TESS_SSBO_CORNER_VALUES 16  // float channels per corner, 3 corners per triangle
#define HYVOX_TESS_SSBO_TEXELS 17         // linear texels, rows top first (TEXTURE_COLOR)
#define HYVOX_TESS_SSBO_VALUE_POOL 18     // per block: 512 voxels × channels × (low, high) sums

// Uniform locations (HYVOX_LOC_GRID_DIMS = 0 is shared)
#define HYVOX_TESS_LOC_SPLIT_MODE 10     // uint: 0 = direct patches, 1 = pre-split patches
#define HYVOX_TESS_LOC_PATCH_BASE 11     // uint: first patch of this draw
#define HYVOX_TESS_LOC_SPLIT_COUNT 12    // uint: entries in the split list
#define HYVOX_TESS_LOC_GAMMA 13          // float γ of Eq. 1
#define HYVOX_TESS_LOC_MAX_LEVEL 14      // float GL_MAX_TESS_GEN_LEVEL
#define HYVOX_TESS_LOC_HEIGHT_SIZE 15    // ivec2 displacement image size
#define HYVOX_TESS_LOC_DISPLACE 16       // vec2 (strength in voxels, midlevel)
#define HYVOX_TESS_LOC_POOL_BLOCKS 17    // uint blocks the count pool holds
#define HYVOX_TESS_LOC_PREFILLED 18      // uint: 1 = the brick table is filled in, take no blocks
#define HYVOX_TESS_LOC_TEXTURE_SIZE 19   // ivec3 texture width, height, channels (TEXTURE_COLOR)

// Counter slots in HYVOX_TESS_SSBO_COUNTERS
#define HYVOX_TESS_COUNTER_POINTS 0
#define HYVOX_TESS_COUNTER_CLIPPED 1
#define HYVOX_TESS_COUNTER_BLOCKS 2

#endif
