// SPDX-License-Identifier: GPL-3.0-or-later
// Section 3.3.1: swizzle every triangle so its dominant normal axis becomes z and its
// largest projection lies in the XY plane; the swizzles are cyclic, so cross products
// (normals, orientation) swizzle the same way. Ties pick x, then y (as the cpu backend
// does: in thin mode the dominant axis decides which voxels a 45-degree face marks).
int dominantAxis(vec3 n) {
    const vec3 a = abs(n);
    if (a.x >= a.y && a.x >= a.z) return 0;
    return a.y >= a.z ? 1 : 2;
}
vec3 swizzleToDominant(vec3 v, int axis) { return axis == 0 ? v.yzx : (axis == 1 ? v.zxy : v); }
ivec3 swizzleToDominant(ivec3 v, int axis) { return axis == 0 ? v.yzx : (axis == 1 ? v.zxy : v); }
ivec3 unswizzle(ivec3 p, int axis) { return axis == 0 ? p.zxy : (axis == 1 ? p.yzx : p); }
