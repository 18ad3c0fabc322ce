// SPDX-License-Identifier: GPL-3.0-or-later
// Places each generated vertex on the surface (flat or PN-triangle) and, with a displacement
// map, moves it along the interpolated normal by (height - midlevel) · strength: Blender's
// Displace modifier, sampled at the interpolated UV (section 3.3).
#include "tessellation/bindings.glsl"

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

#ifdef DISPLACEMENT
#include "tessellation/height.glsl"
#endif

void main() {
    const vec3 w = gl_TessCoord.x * tcBary[0] + gl_TessCoord.y * tcBary[1] + gl_TessCoord.z * tcBary[2];
#ifdef PN_TRIANGLES
    vec3 p = tcP[0] * (w.x * w.x * w.x) + tcP[1] * (w.y * w.y * w.y) + tcP[2] * (w.z * w.z * w.z) +
             tcB[0] * (3.0 * w.x * w.x * w.y) + tcB[1] * (3.0 * w.x * w.y * w.y) + tcB[5] * (3.0 * w.x * w.x * w.z) +
             tcB[2] * (3.0 * w.y * w.y * w.z) + tcB[4] * (3.0 * w.x * w.z * w.z) + tcB[3] * (3.0 * w.y * w.z * w.z) +
             tcB[6] * (6.0 * w.x * w.y * w.z);
#else
    vec3 p = w.x * tcP[0] + w.y * tcP[1] + w.z * tcP[2];
#endif
#ifdef DISPLACEMENT
#ifdef PN_TRIANGLES
    const vec3 n = normalize(tcN[0] * (w.x * w.x) + tcN[1] * (w.y * w.y) + tcN[2] * (w.z * w.z) +
                             tcNe[0] * (w.x * w.y) + tcNe[1] * (w.y * w.z) + tcNe[2] * (w.x * w.z));
#else
    const vec3 n = normalize(w.x * tcN[0] + w.y * tcN[1] + w.z * tcN[2]);
#endif
    const vec2 uv = w.x * tcUv[0] + w.y * tcUv[1] + w.z * tcUv[2];
    p += n * displacement(uv);
#endif
    tePosition = p;
    teOrigin = tcOrigin;
}
