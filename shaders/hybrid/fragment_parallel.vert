// SPDX-License-Identifier: GPL-3.0-or-later
// Methods `fragment` and `hybrid` pass 2: vertex pulling. Every three vertices name one
// triangle (all of them, or the large ones pass 1 listed); the geometry shader loads it.
#include "common/bindings.glsl"

#if HYVOX_FROM_LARGE_LIST
layout(std430, binding = HYVOX_SSBO_LARGE) readonly restrict buffer LargeTriangles { uint largeTriangles[]; };
#endif

flat out uint vTriangle;

void main() {
    const uint slot = uint(gl_VertexID) / 3u;
#if HYVOX_FROM_LARGE_LIST
    vTriangle = largeTriangles[slot];
#else
    vTriangle = slot;
#endif
    gl_Position = vec4(0.0);
}
