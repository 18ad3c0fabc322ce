// SPDX-License-Identifier: GPL-3.0-or-later
// Section 3.2: each micro-triangle becomes one point at its centroid, injected into the grid
// straight from here (the rasterizer is off).
#include "tessellation/inject.glsl"

layout(triangles) in;
layout(points, max_vertices = 1) out;

in vec3 tePosition[];
flat in ivec3 teOrigin[];
#ifdef ATTRIBUTES
in vec3 teBary[];  // on the mesh triangle, whether the patch is all of it or a pre-split piece
flat in uint teTriangle[];
#endif

void main() {
    const vec3 middle = (tePosition[0] + tePosition[1] + tePosition[2]) / 3.0;
#ifdef ATTRIBUTES
    injectPoint(teOrigin[0], middle, teTriangle[0], (teBary[0] + teBary[1] + teBary[2]) / 3.0);
#else
    injectPoint(teOrigin[0], middle, 0u, vec3(0.0));
#endif
}
