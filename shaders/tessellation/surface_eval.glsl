// SPDX-License-Identifier: GPL-3.0-or-later
// Evaluating a patch's surface at barycentric w, flat or as a PN-triangle (Vlachos et al.
// 2001), from its corners alone: no buffer access, so the control stage (corners from the
// mesh buffers, tessellation/surface.glsl) and the evaluation stage (corners handed over as
// patch outputs) share the very same formulas. native/src/tessellation/surface.cpp is the
// CPU twin.

struct TriangleSurface {
    ivec3 origin;
    vec3 p[3];
    vec3 n[3];
    vec2 uv[3];
};

// Control points b210 b120 b021 b012 b102 b201 b111, and mid-edge normals n110 n011 n101.
struct PnCoefficients {
    vec3 b[7];
    vec3 n[3];
};

vec3 pnEdgePoint(TriangleSurface s, int i, int j) {
    return (2.0 * s.p[i] + s.p[j] - dot(s.p[j] - s.p[i], s.n[i]) * s.n[i]) / 3.0;
}
vec3 pnEdgeNormal(TriangleSurface s, int i, int j) {
    const vec3 d = s.p[j] - s.p[i];
    const float v = 2.0 * dot(d, s.n[i] + s.n[j]) / dot(d, d);
    return normalize(s.n[i] + s.n[j] - v * d);
}

PnCoefficients pnCoefficients(TriangleSurface s) {
    PnCoefficients c;
    c.b[0] = pnEdgePoint(s, 0, 1);
    c.b[1] = pnEdgePoint(s, 1, 0);
    c.b[2] = pnEdgePoint(s, 1, 2);
    c.b[3] = pnEdgePoint(s, 2, 1);
    c.b[4] = pnEdgePoint(s, 2, 0);
    c.b[5] = pnEdgePoint(s, 0, 2);
    const vec3 e = (c.b[0] + c.b[1] + c.b[2] + c.b[3] + c.b[4] + c.b[5]) / 6.0;
    const vec3 v = (s.p[0] + s.p[1] + s.p[2]) / 3.0;
    c.b[6] = e + 0.5 * (e - v);
    c.n[0] = pnEdgeNormal(s, 0, 1);
    c.n[1] = pnEdgeNormal(s, 1, 2);
    c.n[2] = pnEdgeNormal(s, 2, 0);
    return c;
}

vec3 flatPosition(TriangleSurface s, vec3 w) { return w.x * s.p[0] + w.y * s.p[1] + w.z * s.p[2]; }
vec3 flatNormal(TriangleSurface s, vec3 w) { return normalize(w.x * s.n[0] + w.y * s.n[1] + w.z * s.n[2]); }
vec2 surfaceUv(TriangleSurface s, vec3 w) { return w.x * s.uv[0] + w.y * s.uv[1] + w.z * s.uv[2]; }

vec3 pnPosition(TriangleSurface s, PnCoefficients c, vec3 w) {
    return s.p[0] * (w.x * w.x * w.x) + s.p[1] * (w.y * w.y * w.y) + s.p[2] * (w.z * w.z * w.z) +
           c.b[0] * (3.0 * w.x * w.x * w.y) + c.b[1] * (3.0 * w.x * w.y * w.y) +
           c.b[5] * (3.0 * w.x * w.x * w.z) + c.b[2] * (3.0 * w.y * w.y * w.z) +
           c.b[4] * (3.0 * w.x * w.z * w.z) + c.b[3] * (3.0 * w.y * w.z * w.z) +
           c.b[6] * (6.0 * w.x * w.y * w.z);
}
vec3 pnNormal(TriangleSurface s, PnCoefficients c, vec3 w) {
    return normalize(s.n[0] * (w.x * w.x) + s.n[1] * (w.y * w.y) + s.n[2] * (w.z * w.z) + c.n[0] * (w.x * w.y) +
                     c.n[1] * (w.y * w.z) + c.n[2] * (w.x * w.z));
}
