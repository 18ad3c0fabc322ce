// SPDX-License-Identifier: GPL-3.0-or-later
// Eq. 1: each outer level is γ times the edge's length in voxels, the inner level their mean,
// so every tessellated edge segment is at most 1/γ voxel long (tess_factors.h, the CPU twin;
// why this reading and γ = 2: docs/why/tessellation-gamma.md).
// Invocation 0 also loads the triangle and its PN coefficients once for the whole patch.
#include "tessellation/surface.glsl"

layout(vertices = 3) out;
layout(location = HYVOX_TESS_LOC_GAMMA) uniform float gamma;
layout(location = HYVOX_TESS_LOC_MAX_LEVEL) uniform float maxLevel;

in uint vTriangle[];
in vec3 vBary[];
out vec3 tcBary[];
patch out ivec3 tcOrigin;
patch out vec3 tcP[3];
patch out vec3 tcN[3];
patch out vec2 tcUv[3];
#ifdef ATTRIBUTES
patch out uint tcTriangle;
#endif
#ifdef PN_TRIANGLES
patch out vec3 tcB[7];
patch out vec3 tcNe[3];
#endif

float edgeLevel(vec3 a, vec3 b) {
    return gamma * length(a - b);
}

void main() {
    tcBary[gl_InvocationID] = vBary[gl_InvocationID];
    if (gl_InvocationID != 0) return;
    const TriangleSurface s = loadSurface(vTriangle[0]);
    tcOrigin = s.origin;
#ifdef ATTRIBUTES
    tcTriangle = vTriangle[0];
#endif
    for (int c = 0; c < 3; ++c) {
        tcP[c] = s.p[c];
        tcN[c] = s.n[c];
        tcUv[c] = s.uv[c];
    }
    vec3 corner[3];
#ifdef PN_TRIANGLES
    const PnCoefficients pn = pnCoefficients(s);
    for (int c = 0; c < 3; ++c) corner[c] = pnPosition(s, pn, vBary[c]);
    tcB = pn.b;
    tcNe = pn.n;
#else
    for (int c = 0; c < 3; ++c) corner[c] = flatPosition(s, vBary[c]);
#endif
    const float t0 = edgeLevel(corner[1], corner[2]);
    const float t1 = edgeLevel(corner[2], corner[0]);
    const float t2 = edgeLevel(corner[0], corner[1]);
    // Levels below 1 would discard the patch; the pre-split keeps them under maxLevel.
    gl_TessLevelOuter[0] = clamp(t0, 1.0, maxLevel);
    gl_TessLevelOuter[1] = clamp(t1, 1.0, maxLevel);
    gl_TessLevelOuter[2] = clamp(t2, 1.0, maxLevel);
    gl_TessLevelInner[0] = clamp((t0 + t1 + t2) / 3.0, 1.0, maxLevel);
}
