// SPDX-License-Identifier: GPL-3.0-or-later
// The factored triangle/voxel overlap test of Schwarz & Seidel 2010 as the JCGT paper
// arranges it (sections 3.1.1-3.1.3), in swizzled local voxel space: voxel q (its min
// corner, relative to the triangle's local origin) is the closed box [q, q + 1].
//   conservative (26-separating): bounding box, plane, and the three 2D projections: exact
//     closed-box SAT, so voxels that merely touch the triangle count.
//   thin (6-separating, HYVOX_THIN=1): the plane must cross the voxel's centre segment along
//     the dominant axis, and each 2D projection must meet the voxel's inscribed diamond.
// A planeless triangle (its edges' cross product is zero: a segment or a point in voxel space,
// e.g. a needle whose two near corners coincide there) is what is left of it, tested as the
// cpu method and the reference do: every projected edge's line, on either side (each edge
// with winding +1; the collinear edges point both ways), and no plane; its depth range comes
// from the segment instead (segmentDepthRange).
// The appendix pseudocode is not followed where it has typos: its line 19 tests p_xy
// against the YZ/ZX edges (we use q.yz / q.zx), its thin offsets mix planes (we use
// 0.5 * max(|n_e.x|, |n_e.y|) of the same plane), and its depth ranges floor/ceil the wrong
// way round for faces on voxel planes (we derive them below so both sides are marked).
#include "common/swizzle.glsl"

#ifndef HYVOX_THIN
#define HYVOX_THIN 0
#endif

struct TriangleSetup {
    ivec3 origin;  // swizzled global cell of the local origin
    ivec3 lo;      // swizzled inclusive global voxel range: bounding box clipped to the tile
    ivec3 hi;
    int axis;      // dominant axis before swizzling (for unswizzle)
    vec3 n;        // normal, oriented so n.z > 0
    vec2 depth;    // factored depth-range constants (conservative: d_lo, d_hi; thin: d_cen)
    vec3 xy[3];    // per edge: 2D inward edge normal (x, y) and factored offset d (z)
    vec3 yz[3];
    vec3 zx[3];
    vec3 segFrom;  // planeless only (n == 0): the segment from its first to its last corner
    vec3 segDir;   // along its longest axis (swizzled, local)
};

bool planeless(TriangleSetup t) { return t.n.z == 0.0; }  // else n.z > 0 (see setupTriangle)

// Edge function of projected edge e starting at projected vertex a, for a 2D triangle with
// orientation sign s; returns (n_e, d_e) such that dot(n_e, q) + d_e >= 0 means voxel q's
// projection (square or diamond) reaches the inner side of the edge.
vec3 edgeFunction(vec2 e, vec2 a, float s) {
    const vec2 ne = s * vec2(-e.y, e.x);
#if HYVOX_THIN
    // Most interior point of the diamond inscribed in the square [q, q + 1]².
    const float d = dot(ne, vec2(0.5) - a) + 0.5 * max(abs(ne.x), abs(ne.y));
#else
    // Most interior corner of the square (the critical point).
    const float d = -dot(ne, a) + max(0.0, ne.x) + max(0.0, ne.y);
#endif
    return vec3(ne, d);
}

float orientationSign(float x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }

// v0..v2 and origin are swizzled; clipLo/clipHi the swizzled inclusive voxel range to write.
TriangleSetup setupTriangle(vec3 v0, vec3 v1, vec3 v2, ivec3 origin, int axis, ivec3 clipLo, ivec3 clipHi) {
    TriangleSetup t;
    t.origin = origin;
    t.axis = axis;
    const vec3 bmin = min(v0, min(v1, v2)), bmax = max(v0, max(v1, v2));
    // Voxel q's closed box meets [bmin, bmax] iff ceil(bmin) - 1 <= q <= floor(bmax).
    t.lo = max(clipLo, ivec3(ceil(bmin)) - 1 + origin);
    t.hi = min(clipHi, ivec3(floor(bmax)) + origin);

    const vec3 e0 = v1 - v0, e1 = v2 - v1, e2 = v0 - v2;
    vec3 n = cross(e0, e1);
    const bool noPlane = n == vec3(0.0);
    const float sx = noPlane ? 1.0 : orientationSign(n.x), sy = noPlane ? 1.0 : orientationSign(n.y),
                sz = noPlane ? 1.0 : orientationSign(n.z);
    t.segFrom = v0;
    t.segDir = vec3(0.0);
    if (noPlane) {
        const vec3 extent = bmax - bmin;
        const int m = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        const vec3 v[3] = vec3[3](v0, v1, v2);
        int first = 0, last = 0;
        for (int i = 1; i < 3; ++i) {
            if (v[i][m] < v[first][m]) first = i;
            if (v[i][m] > v[last][m]) last = i;
        }
        t.segFrom = v[first];
        t.segDir = v[last] - v[first];
    }
    t.xy[0] = edgeFunction(e0.xy, v0.xy, sz);
    t.xy[1] = edgeFunction(e1.xy, v1.xy, sz);
    t.xy[2] = edgeFunction(e2.xy, v2.xy, sz);
    t.yz[0] = edgeFunction(e0.yz, v0.yz, sx);
    t.yz[1] = edgeFunction(e1.yz, v1.yz, sx);
    t.yz[2] = edgeFunction(e2.yz, v2.yz, sx);
    t.zx[0] = edgeFunction(e0.zx, v0.zx, sy);
    t.zx[1] = edgeFunction(e1.zx, v1.zx, sy);
    t.zx[2] = edgeFunction(e2.zx, v2.zx, sy);

    n *= sz;  // n.z > 0 so the depth range runs upwards
    t.n = n;
    const float nv = dot(n, v0);
#if HYVOX_THIN
    // Height of the plane above the column's centre line (x + 0.5, y + 0.5), times n.z.
    t.depth = vec2(nv - 0.5 * n.x - 0.5 * n.y, 0.0);
#else
    // The box column [x,x+1]x[y,y+1] meets the plane at heights between these, times n.z.
    t.depth = vec2(nv - max(0.0, n.x) - max(0.0, n.y), nv - min(0.0, n.x) - min(0.0, n.y));
#endif
    return t;
}

bool edgeInside(vec3 edge, vec2 q) { return dot(edge.xy, q) + edge.z >= 0.0; }

// q: the column's local 2D min corner on the dominant plane.
bool insideXY(TriangleSetup t, vec2 q) {
    return edgeInside(t.xy[0], q) && edgeInside(t.xy[1], q) && edgeInside(t.xy[2], q);
}

// A planeless triangle's candidates in column q: the voxels around the part of its segment
// above the column's square, both widened by a voxel on every side against rounding (the edge
// tests decide). The depth axis is its shortest (prepareLoaded), so that part spans few.
ivec2 segmentDepthRange(TriangleSetup t, vec2 q) {
    float t0 = 0.0, t1 = 1.0;
    for (int a = 0; a < 2; ++a) {
        const float lo = q[a] - 1.0 - t.segFrom[a], hi = q[a] + 2.0 - t.segFrom[a];
        if (t.segDir[a] != 0.0) {
            const float ta = lo / t.segDir[a], tb = hi / t.segDir[a];
            t0 = max(t0, min(ta, tb));
            t1 = min(t1, max(ta, tb));
        } else if (lo > 0.0 || hi < 0.0) {
            return ivec2(1, 0);
        }
    }
    if (t0 > t1) return ivec2(1, 0);
    const float z0 = t.segFrom.z + t0 * t.segDir.z, z1 = t.segFrom.z + t1 * t.segDir.z;
    const int zlo = int(ceil(min(z0, z1))) - 2, zhi = int(floor(max(z0, z1))) + 1;
    return ivec2(max(t.lo.z, zlo + t.origin.z), min(t.hi.z, zhi + t.origin.z));
}

// Global z range of voxels in column q that the triangle's plane passes (step 4 of 3.1.3).
ivec2 depthRange(TriangleSetup t, vec2 q) {
    if (planeless(t)) return segmentDepthRange(t, q);
    const float inv = 1.0 / t.n.z, along = dot(t.n.xy, q);
#if HYVOX_THIN
    // Voxel z holds the crossing height h iff z <= h <= z + 1.
    const float h = (t.depth.x - along) * inv;
    const int zlo = int(ceil(h - 1.0)), zhi = int(floor(h));
#else
    // Voxel z's box reaches the plane iff z + 1 >= lowest height and z <= highest height.
    const int zlo = int(ceil((t.depth.x - along) * inv - 1.0)), zhi = int(floor((t.depth.y - along) * inv));
#endif
    return ivec2(max(t.lo.z, zlo + t.origin.z), min(t.hi.z, zhi + t.origin.z));
}

// The two remaining projections for local voxel q (step 5).
bool insideRemaining(TriangleSetup t, vec3 q) {
    return edgeInside(t.yz[0], q.yz) && edgeInside(t.yz[1], q.yz) && edgeInside(t.yz[2], q.yz) &&
           edgeInside(t.zx[0], q.zx) && edgeInside(t.zx[1], q.zx) && edgeInside(t.zx[2], q.zx);
}
