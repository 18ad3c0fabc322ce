// SPDX-License-Identifier: GPL-3.0-or-later
// The displacement height at a UV: GL_LINEAR + GL_CLAMP_TO_EDGE by hand over a float
// buffer (rows bottom-up), so the CPU twin (DisplacementMap::sample) matches exactly rather
// than up to a GPU's 8-bit filter weights.
#include "tessellation/bindings.glsl"

layout(std430, binding = HYVOX_TESS_SSBO_HEIGHTS) readonly restrict buffer Heights { float heights[]; };
layout(location = HYVOX_TESS_LOC_HEIGHT_SIZE) uniform ivec2 heightSize;
layout(location = HYVOX_TESS_LOC_DISPLACE) uniform vec2 displace;  // strength (voxels), midlevel

float height(vec2 uv) {
    const vec2 x = uv * vec2(heightSize) - 0.5;
    const vec2 f = floor(x), a = x - f;
    const ivec2 hi = heightSize - 1;
    const ivec2 i0 = ivec2(clamp(f, vec2(0.0), vec2(hi))), i1 = ivec2(clamp(f + 1.0, vec2(0.0), vec2(hi)));
    const float h00 = heights[i0.y * heightSize.x + i0.x], h10 = heights[i0.y * heightSize.x + i1.x];
    const float h01 = heights[i1.y * heightSize.x + i0.x], h11 = heights[i1.y * heightSize.x + i1.x];
    return mix(mix(h00, h10, a.x), mix(h01, h11, a.x), a.y);
}

// The displacement along the unit normal, in voxels: Blender's Displace modifier.
float displacement(vec2 uv) { return (height(uv) - displace.y) * displace.x; }
