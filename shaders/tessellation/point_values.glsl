// SPDX-License-Identifier: GPL-3.0-or-later
// Attribute voxels of the tessellation (section 3.2's multi-valued voxels): every point adds
// its triangle's attributes at its barycentrics to its voxel's sums, beside the count; the
// host divides by the count (native/src/tessellation/point_values.cpp). Corner values are
// interpolated linearly (vertex/corner colours, palette, normals); with TEXTURE_COLOR the
// colour slots hold the corners' UVs and the texture is sampled at the interpolated UV.
// Sums are fixed point in two words (low, high) per channel: integer adds commute, so the
// sums, and the means, are the same on every run and device.
// Defines from the host: ATTRIBUTE_CHANNELS, VALUE_SCALE, VALUE_LIMIT, and with a texture
// TEXTURE_COLOR and COLOR_CHANNELS (3 or 4).
#include "tessellation/bindings.glsl"

layout(std430, binding = HYVOX_TESS_SSBO_CORNER_VALUES) readonly restrict buffer CornerValues { float cornerValues[]; };
layout(std430, binding = HYVOX_TESS_SSBO_VALUE_POOL) coherent restrict buffer ValuePool { uint valuePool[]; };

#ifdef TEXTURE_COLOR
layout(std430, binding = HYVOX_TESS_SSBO_TEXELS) readonly restrict buffer Texels { float texels[]; };
layout(location = HYVOX_TESS_LOC_TEXTURE_SIZE) uniform ivec3 texelGrid;  // width, height, channels

float texel(ivec2 at, int channel) { return texels[(at.y * texelGrid.x + at.x) * texelGrid.z + channel]; }

// hyvox::Texture::sample: bilinear between texel centres, repeat wrap, v = 0 the bottom row.
vec4 sampleTexture(vec2 uv) {
    const vec2 size = vec2(texelGrid.xy);
    const vec2 x = vec2(uv.x, 1.0 - uv.y) * size - 0.5;
    const vec2 f = floor(x), a = x - f;
    const ivec2 i0 = min(ivec2(mod(f, size)), texelGrid.xy - 1);  // mod's rounding may reach size
    const ivec2 i1 = (i0 + 1) % texelGrid.xy;
    vec4 rgba = vec4(0.0, 0.0, 0.0, 1.0);
    for (int c = 0; c < texelGrid.z; ++c) {
        const float top = mix(texel(i0, c), texel(ivec2(i1.x, i0.y), c), a.x);
        const float bottom = mix(texel(ivec2(i0.x, i1.y), c), texel(i1, c), a.x);
        rgba[c] = mix(top, bottom, a.y);
    }
    return rgba;
}
#endif

// Adds round(value · VALUE_SCALE) as a signed 64-bit integer to the (low, high) pair at `at`:
// the high word takes the low word's carry and the sign extension, so the pair is the exact
// two's-complement sum whatever the order of the adds.
void addFixed(uint at, float value) {
    const int v = int(round(clamp(value, -VALUE_LIMIT, VALUE_LIMIT) * VALUE_SCALE));
    const uint old = atomicAdd(valuePool[at], uint(v));
    const uint carry = old + uint(v) < old ? 1u : 0u;
    const uint high = carry + (v < 0 ? 0xffffffffu : 0u);
    if (high != 0u) atomicAdd(valuePool[at + 1u], high);
}

// The point at barycentrics `bary` of usable triangle `tri`, in voxel `n` of count block `block`.
void addPointValues(uint block, uint n, uint tri, vec3 bary) {
    float value[ATTRIBUTE_CHANNELS];
    const uint base = tri * 3u * uint(ATTRIBUTE_CHANNELS);
    for (int c = 0; c < ATTRIBUTE_CHANNELS; ++c)
        value[c] = bary.x * cornerValues[base + uint(c)] +
                   bary.y * cornerValues[base + uint(ATTRIBUTE_CHANNELS + c)] +
                   bary.z * cornerValues[base + uint(2 * ATTRIBUTE_CHANNELS + c)];
#ifdef TEXTURE_COLOR
    const vec4 rgba = sampleTexture(vec2(value[0], value[1]));
    for (int c = 0; c < COLOR_CHANNELS; ++c) value[c] = rgba[c];
#endif
    const uint at = ((block - 1u) * 512u + n) * uint(2 * ATTRIBUTE_CHANNELS);
    for (int c = 0; c < ATTRIBUTE_CHANNELS; ++c) addFixed(at + uint(2 * c), value[c]);
}
