// SPDX-License-Identifier: GPL-3.0-or-later
// Section 3.2: each micro-triangle becomes one point at its centroid, injected into the grid
// straight from here (the rasterizer is off).
#include "tessellation/inject.glsl"

layout(triangles) in;
layout(points, max_vertices = 1) out;

in vec3 tePosition[];
flat in ivec3 teOrigin[];

void main() { injectPoint(teOrigin[0], (tePosition[0] + tePosition[1] + tePosition[2]) / 3.0); }
