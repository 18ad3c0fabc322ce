// SPDX-License-Identifier: GPL-3.0-or-later
// Places each generated vertex on the surface (flat or PN-triangle) and, with a displacement
// map, moves it along the interpolated normal by (height - midlevel) · strength: Blender's
// Displace modifier, sampled at the interpolated UV (section 3.3).
#include "tessellation/bindings.glsl"
#include "tessellation/surface_eval.glsl"

layout(triangles, equal_spacing, ccw) in;

in vec3 tcBary[];
patch in ivec3 tcOrigin;
patch in vec3 tcP[3];
patch in vec3 tcN[3];
patch in vec2 tcUv[3];
#ifdef PN_TRIANGLES
patch in vec3 tcB[7];
patch in vec3 tcNe[3];
#endif
out vec3 tePosition;  // voxel space, relative to teOrigin
flat out ivec3 teOrigin;
#ifdef ATTRIBUTES
patch in uint tcTriangle;
out vec3 teBary;  // w: where the vertex lies on the mesh triangle, for its attributes
flat out uint teTriangle;
#endif

#ifdef DISPLACEMENT
#include "tessellation/height.glsl"
#endif

void main() {
    const vec3 w = gl_TessCoord.x * tcBary[0] + gl_TessCoord.y * tcBary[1] + gl_TessCoord.z * tcBary[2];
    const TriangleSurface s = TriangleSurface(tcOrigin, tcP, tcN, tcUv);
#ifdef PN_TRIANGLES
    const PnCoefficients pn = PnCoefficients(tcB, tcNe);
    vec3 p = pnPosition(s, pn, w);
#else
    vec3 p = flatPosition(s, w);
#endif
#ifdef DISPLACEMENT
#ifdef PN_TRIANGLES
    const vec3 n = pnNormal(s, pn, w);
#else
    const vec3 n = flatNormal(s, w);
#endif
    p += n * displacement(surfaceUv(s, w));
#endif
    tePosition = p;
    teOrigin = tcOrigin;
#ifdef ATTRIBUTES
    teBary = w;
    teTriangle = tcTriangle;
#endif
}
