// SPDX-License-Identifier: GPL-3.0-or-later
// Colour and normal voxels of methods `triangle`, `fragment` and `hybrid` (JCGT 2013 section
// 3.6, with the area weights of docs/design.md "Attributes"): one invocation per (voxel, triangle)
// pair the voxelizing passes listed clips the triangle to the voxel's closed box and writes
// the piece's area and centroid. The host sums the pieces' attributes in a fixed order, with
// the code the cpu method uses (native/src/attributes/).
//
// The clip is the one of native/src/attributes/clip_to_voxel.cpp, plane for plane and in
// double: x, then y, then z, each slab's low plane first; points on a plane count as inside;
// a piece whose exact clip is empty (a touch lost to rounding) is clipped again against the
// box grown by HYVOX_TOUCH_MARGIN and marked, so the host can use it as the cpu method does
// (only for voxels no exact piece reached). A pass of its own, one invocation per pair, keeps
// the voxelizing loops as they were (llvmpipe's per-invocation loop budget, see
// common/voxelize_triangle.glsl) and spreads a large triangle's pieces over many invocations.
#include "common/mesh_input.glsl"

// Each invocation's polygons live in shared memory: llvmpipe compiles dynamically indexed
// local arrays into long chains of selects (a minute to compile, slow to run), shared memory
// into plain loads and stores. 32 invocations × 2 polygons × 16 corners × 24 bytes = 24 KiB,
// within the 32 KiB every GL 4.3 device has.
const uint kGroupSize = 32u;
layout(local_size_x = 32) in;

layout(std430, binding = HYVOX_SSBO_PAIRS) readonly restrict buffer AttributePairs {
    uint pairCount;
    uint pairPad[3];
    uvec4 pairs[];  // x, y, z (tile voxel), triangle
};

// std430: 20 bytes each, as hybrid::GpuPiece reads them.
struct Piece {
    float area;  // voxel units²
    float cx, cy, cz;  // centroid relative to the voxel's min corner
    uint kind;  // HYVOX_PIECE_*
};
layout(std430, binding = HYVOX_SSBO_PIECES) writeonly restrict buffer Pieces { Piece pieces[]; };
layout(location = HYVOX_LOC_PAIR_COUNT) uniform uint pairsToClip;

const int kMaxCorners = 16;  // as attributes::Polygon: 9 at most, room for exact touches' repeats
// The polygon being clipped and the one the next plane leaves (current, 1 - current).
shared dvec3 corners[2 * kMaxCorners * kGroupSize];
int cornerCount[2];
int current;

dvec3 corner(int polygon, int k) { return corners[(polygon * kMaxCorners + k) * int(kGroupSize) + int(gl_LocalInvocationID.x)]; }
void setCorner(int polygon, int k, dvec3 p) {
    corners[(polygon * kMaxCorners + k) * int(kGroupSize) + int(gl_LocalInvocationID.x)] = p;
}

// Component `axis` of p, without dynamic indexing (which llvmpipe makes slow).
double along(dvec3 p, int axis) { return axis == 0 ? p.x : (axis == 1 ? p.y : p.z); }
dvec3 placedOn(dvec3 p, int axis, double bound) {
    return dvec3(axis == 0 ? bound : p.x, axis == 1 ? bound : p.y, axis == 2 ? bound : p.z);
}

// Keeps the part of the current polygon with sign * (x[axis] - bound) >= 0 (clipPlane in C++).
void clipPlane(int axis, double bound, double sign) {
    const int from = current, to = 1 - current;
    const int count = cornerCount[from];
    int n = 0;
    for (int e = 0; e < count; ++e) {
        const dvec3 cur = corner(from, e), nxt = corner(from, e + 1 < count ? e + 1 : 0);
        const double dc = sign * (along(cur, axis) - bound), dn = sign * (along(nxt, axis) - bound);
        if (dc >= 0.0LF && n < kMaxCorners) setCorner(to, n++, cur);
        if (((dc > 0.0LF && dn < 0.0LF) || (dc < 0.0LF && dn > 0.0LF)) && n < kMaxCorners) {
            const double t = dc / (dc - dn);
            setCorner(to, n++, placedOn(cur + (nxt - cur) * t, axis, bound));
        }
    }
    cornerCount[to] = n;
    current = to;
}

// The triangle (relative to the voxel's min corner) clipped to [-margin, 1 + margin]³; false
// when nothing is left.
bool clipToBox(dvec3 v0, dvec3 v1, dvec3 v2, double margin) {
    current = 0;
    setCorner(0, 0, v0);
    setCorner(0, 1, v1);
    setCorner(0, 2, v2);
    cornerCount[0] = 3;
    for (int axis = 0; axis < 3; ++axis) {
        clipPlane(axis, -margin, 1.0LF);
        if (cornerCount[current] > 0) clipPlane(axis, 1.0LF + margin, -1.0LF);
        if (cornerCount[current] == 0) return false;
    }
    return true;
}

// Area and centroid of the clipped polygon (measurePiece in C++): a fan from the first corner;
// below HYVOX_TOUCH_AREA a touch, whose centre is the midpoint of its two farthest points.
void measure(out double area, out dvec3 pieceCentre) {
    const int count = cornerCount[current];
    const dvec3 p0 = corner(current, 0);
    area = 0.0LF;
    dvec3 moment = dvec3(0.0LF);
    for (int k = 1; k + 1 < count; ++k) {
        const dvec3 pk = corner(current, k), pk1 = corner(current, k + 1);
        const dvec3 c = cross(pk - p0, pk1 - p0);
        const double tri = 0.5LF * sqrt(dot(c, c));
        area += tri;
        moment += tri * (p0 + pk + pk1) / 3.0LF;
    }
    if (area >= HYVOX_TOUCH_AREA) {
        pieceCentre = moment / area;
        return;
    }
    dvec3 bestI = p0, bestJ = p0;
    double best = -1.0LF;
    for (int i = 0; i < count; ++i)
        for (int j = 0; j < count; ++j) {
            const dvec3 d = corner(current, i) - corner(current, j);
            if (dot(d, d) > best) {
                best = dot(d, d);
                bestI = corner(current, i);
                bestJ = corner(current, j);
            }
        }
    pieceCentre = 0.5LF * (bestI + bestJ);
}

// Vertex v relative to voxel p's min corner, exactly (integer cells, then the fraction).
dvec3 relativeTo(uint v, ivec3 p) { return dvec3(vertexCell(v) - p) + dvec3(vertexFraction(v)); }

void main() {
    const uint pair = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * kGroupSize + gl_LocalInvocationID.x;
    if (pair >= pairsToClip) return;
    const ivec3 p = ivec3(pairs[pair].xyz);
    const uint tri = pairs[pair].w;
    const dvec3 v0 = relativeTo(triangleIndices[3u * tri], p), v1 = relativeTo(triangleIndices[3u * tri + 1u], p),
                v2 = relativeTo(triangleIndices[3u * tri + 2u], p);
    uint kind = HYVOX_PIECE_EXACT;
    if (!clipToBox(v0, v1, v2, 0.0LF)) kind = clipToBox(v0, v1, v2, HYVOX_TOUCH_MARGIN) ? HYVOX_PIECE_MARGIN : HYVOX_PIECE_NONE;
    double area = 0.0LF;
    dvec3 pieceCentre = dvec3(0.5LF);
    if (kind != HYVOX_PIECE_NONE) measure(area, pieceCentre);
    pieces[pair] = Piece(float(area), float(pieceCentre.x), float(pieceCentre.y), float(pieceCentre.z), kind);
}
