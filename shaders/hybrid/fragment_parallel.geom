// SPDX-License-Identifier: GPL-3.0-or-later
// Fragment-parallel setup (section 3.3): per-triangle values computed once here and passed
// flat; the triangle is drawn on its dominant plane (swizzle) and dilated after Hertel et
// al. so every voxel column its projection touches gets a fragment (conservative
// rasterization, 3.3.2). Clip distances trim the dilation to the bounding box, which keeps
// slivers (whose dilated corners shoot far out) from flooding the rasterizer.
#include "common/voxelize_triangle.glsl"

layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
layout(location = HYVOX_LOC_VIEWPORT) uniform vec2 viewportSize;

flat in uint vTriangle[];
flat out TriangleSetup gSetup;
flat out uint gTriangle;
out float gl_ClipDistance[4];

// l = sqrt(2)/2 voxel (half the pixel diagonal), plus 1/64 for the rasterizer's sub-pixel
// snapping; the fragment shader's exact test removes whatever the extra margin lets in.
const float kDilation = 0.70710678 + 1.0 / 64.0;

// Unit outward normal of edge a→b. The edge is scaled to a unit max-norm first: the length
// of a sliver's short end (1e-19 voxel) would underflow in float.
vec2 outwardNormal(vec2 a, vec2 b, float orientation) {
    const vec2 e = b - a;
    const vec2 s = e / max(abs(e.x), abs(e.y));
    return orientation * vec2(s.y, -s.x) / length(s);
}

void emit(vec2 window, TriangleSetup t) {
    gl_Position = vec4(window / viewportSize * 2.0 - 1.0, 0.0, 1.0);
    gl_ClipDistance[0] = window.x - float(t.lo.x);
    gl_ClipDistance[1] = float(t.hi.x + 1) - window.x;
    gl_ClipDistance[2] = window.y - float(t.lo.y);
    gl_ClipDistance[3] = float(t.hi.y + 1) - window.y;
    gSetup = t;
    gTriangle = vTriangle[0];
    EmitVertex();
}

// A triangle over the whole candidate rectangle, which the clip distances trim to it; the
// fragment shader's tests pick the voxels. For what cannot be dilated.
void emitCandidateRectangle(TriangleSetup t) {
    const vec2 lo = vec2(t.lo.xy) - 1.0, size = vec2(t.hi.xy - t.lo.xy) + 3.0;
    emit(lo, t);
    emit(lo + vec2(2.0 * size.x, 0.0), t);
    emit(lo + vec2(0.0, 2.0 * size.y), t);
    EndPrimitive();
}

void main() {
    const LoadedTriangle l = loadForVoxelizing(vTriangle[0]);
    const TriangleSetup t = prepareLoaded(l);
    if (clippedAway(t)) return;

    if (planeless(t)) {
        emitCandidateRectangle(t);  // no area to dilate: a segment or a point on this plane
        return;
    }

    vec2 a[3] = vec2[3](swizzleToDominant(l.v0, t.axis).xy, swizzleToDominant(l.v1, t.axis).xy,
                        swizzleToDominant(l.v2, t.axis).xy);
    const vec2 e01 = a[1] - a[0], e02 = a[2] - a[0];
    const float orientation = (e01.x * e02.y - e01.y * e02.x) >= 0.0 ? 1.0 : -1.0;
    vec2 normals[3];
    for (int i = 0; i < 3; ++i) normals[i] = outwardNormal(a[i], a[(i + 1) % 3], orientation);

    vec2 dilated[3];
    bool finite = true;
    for (int i = 0; i < 3; ++i) {
        // Dilated vertex i: where the edges before and after it, each pushed out by l, meet.
        const vec2 before = normals[(i + 2) % 3], after = normals[i];
        const float det = before.x * after.y - before.y * after.x;
        const vec2 offset = kDilation * vec2(after.y - before.y, before.x - after.x) / det;
        dilated[i] = vec2(t.origin.xy) + a[i] + offset;
        finite = finite && !any(isnan(dilated[i])) && !any(isinf(dilated[i]));
    }
    if (!finite) {  // a corner too sharp for float (its edges' normals coincide)
        emitCandidateRectangle(t);
        return;
    }
    for (int i = 0; i < 3; ++i) emit(dilated[i], t);
    EndPrimitive();
}
