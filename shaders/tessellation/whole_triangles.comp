// SPDX-License-Identifier: GPL-3.0-or-later
// Triangles whose Eq. 1 factors are all at most 1: the tessellator would hand them back
// whole, so the vertex-to-geometry pipeline is skipped and one thread per triangle injects
// the same point the geometry shader would: the centroid of the (displaced) corners. PN
// evaluation leaves corners where they are, so PN-triangles need nothing more here.
#include "common/compute_index.glsl"
#include "tessellation/surface.glsl"
#include "tessellation/inject.glsl"
#ifdef DISPLACEMENT
#include "tessellation/height.glsl"
#endif

layout(std430, binding = HYVOX_TESS_SSBO_PATCHES) readonly restrict buffer Whole { uint wholeTriangles[]; };
layout(location = HYVOX_TESS_LOC_SPLIT_COUNT) uniform uint wholeCount;

void main() {
    const uint index = invocationTriangle();
    if (index >= wholeCount) return;
    const uint tri = wholeTriangles[index];
    const TriangleSurface s = loadSurface(tri);
    vec3 p[3] = s.p;
#ifdef DISPLACEMENT
    for (int c = 0; c < 3; ++c) p[c] += normalize(s.n[c]) * displacement(s.uv[c]);
#endif
    injectPoint(s.origin, (p[0] + p[1] + p[2]) / 3.0, tri, vec3(1.0 / 3.0));
}
