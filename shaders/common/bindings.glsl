// SPDX-License-Identifier: GPL-3.0-or-later
// Binding points and uniform locations, declared once: the GLSL includes this file and so
// does the C++ driver (native/src/gl/binding_points.h), which is why it holds nothing but
// #defines. tests/native/test_gl_layer.cpp checks the linked programs agree.
#ifndef HYVOX_BINDINGS_GLSL
#define HYVOX_BINDINGS_GLSL

// Shader storage buffers
#define HYVOX_SSBO_BITS 0        // uint words, OpenVDB leaf layout (see hyvox/bit_grid.h)
#define HYVOX_SSBO_VERTICES 1    // voxel-space vertices: int cell xyz + float fraction xyz
#define HYVOX_SSBO_TRIANGLES 2   // uint vertex indices, 3 per triangle
#define HYVOX_SSBO_LARGE 3       // hybrid: indices of triangles deferred to rasterization
#define HYVOX_SSBO_DRAW 4        // hybrid: DrawArraysIndirectCommand filled by classify.comp
#define HYVOX_SSBO_VOXEL_LIST 5  // voxel list (section 3.5): count, then x,y,z per voxel
#define HYVOX_SSBO_PAIRS 6       // attributes: count, then (x, y, z, triangle) per voxel a triangle overlaps
#define HYVOX_SSBO_PIECES 7      // attributes: each pair's clipped piece (area, centroid, kind)

// Uniform locations
#define HYVOX_LOC_GRID_DIMS 0       // ivec3 voxels per axis
#define HYVOX_LOC_SLAB 1            // ivec2 [x0, x1): the tile of x this run writes
#define HYVOX_LOC_TRIANGLE_COUNT 2  // uint
#define HYVOX_LOC_CUTOFF 3          // float, voxel units squared
#define HYVOX_LOC_VIEWPORT 4        // vec2 framebuffer size in pixels (= voxels)
#define HYVOX_LOC_LIST_CAPACITY 5   // uint entries the voxel list can hold
#define HYVOX_LOC_CHUNK_SIDE 6      // int: columns per side of one invocation's chunk (0 = all)
#define HYVOX_LOC_PAIR_CAPACITY 7   // uint pairs the pair list can hold
#define HYVOX_LOC_PAIR_COUNT 8      // uint pairs to clip

#define HYVOX_LOCAL_SIZE 64  // compute work-group size

// Kinds of clipped piece (shaders/hybrid/clip_pieces.comp)
#define HYVOX_PIECE_EXACT 0u   // clipped to the voxel's closed box
#define HYVOX_PIECE_MARGIN 1u  // empty there (rounding); clipped to the box grown by the touch margin
#define HYVOX_PIECE_NONE 2u    // empty even then

#endif
