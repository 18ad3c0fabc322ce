// SPDX-License-Identifier: GPL-3.0-or-later
// Pulls patch corners without vertex attributes: patch p, corner c = gl_VertexID / 3, % 3.
// A direct patch is a whole mesh triangle; a pre-split patch is one of the n² sub-triangles
// of a triangle too large for GL_MAX_TESS_GEN_LEVEL (the single-pass stand-in for the
// paper's multi-pass subdivision, section 4.2), given by barycentric corners.
#include "tessellation/bindings.glsl"

layout(std430, binding = HYVOX_TESS_SSBO_PATCHES) readonly restrict buffer Patches { uint patchTriangles[]; };
layout(std430, binding = HYVOX_TESS_SSBO_SPLITS) readonly restrict buffer Splits { uvec4 splits[]; };
layout(location = HYVOX_TESS_LOC_SPLIT_MODE) uniform uint splitMode;
layout(location = HYVOX_TESS_LOC_PATCH_BASE) uniform uint patchBase;
layout(location = HYVOX_TESS_LOC_SPLIT_COUNT) uniform uint splitCount;

out uint vTriangle;
out vec3 vBary;

void main() {
    // Drawn either as one instance of 3 vertices per patch (gl_VertexID = corner) or as 3
    // vertices per patch in one instance (gl_InstanceID = 0); the sum covers both.
    const uint patchIndex = patchBase + uint(gl_InstanceID) + uint(gl_VertexID) / 3u;
    const uint corner = uint(gl_VertexID) % 3u;
    if (splitMode == 0u) {
        vTriangle = patchTriangles[patchIndex];
        vBary = vec3(corner == 0u ? 1.0 : 0.0, corner == 1u ? 1.0 : 0.0, corner == 2u ? 1.0 : 0.0);
        return;
    }
    // The split triangle owning this patch: the last entry whose first patch is <= it.
    uint lo = 0u, hi = splitCount - 1u;
    while (lo < hi) {
        const uint mid = (lo + hi + 1u) / 2u;
        if (splits[mid].z <= patchIndex) lo = mid; else hi = mid - 1u;
    }
    const uvec4 split = splits[lo];
    const uint n = split.y, local = patchIndex - split.z;
    // Row i of the lattice holds 2(n - i) - 1 sub-triangles (up, down, up, ...), so rows
    // before i hold i(2n - i); invert that, then correct the float estimate.
    const float nf = float(n);
    uint i = uint(max(floor(nf - sqrt(max(nf * nf - float(local), 0.0))), 0.0));
    while (i > 0u && i * (2u * n - i) > local) --i;
    while (i + 1u < n && (i + 1u) * (2u * n - i - 1u) <= local) ++i;
    const uint q = local - i * (2u * n - i), j = q / 2u;
    uvec2 c;
    if ((q & 1u) == 0u) c = corner == 0u ? uvec2(i, j) : (corner == 1u ? uvec2(i + 1u, j) : uvec2(i, j + 1u));
    else c = corner == 0u ? uvec2(i + 1u, j) : (corner == 1u ? uvec2(i + 1u, j + 1u) : uvec2(i, j + 1u));
    const vec2 uv = vec2(c) / nf;
    vTriangle = split.x;
    vBary = vec3(1.0 - uv.x - uv.y, uv.x, uv.y);
}
