// SPDX-License-Identifier: GPL-3.0-or-later
// One fragment per voxel column of the dominant plane: the rest of the factored test
// (2D test, depth range, remaining planes: appendix lines 15-20) runs here, so dilation
// never adds a false voxel. Writes only the bit grid; the framebuffer has no attachments.
#include "common/voxelize_triangle.glsl"

flat in TriangleSetup gSetup;
flat in uint gTriangle;

void main() {
    const ivec2 column = ivec2(floor(gl_FragCoord.xy));
    if (any(lessThan(column, gSetup.lo.xy)) || any(greaterThan(column, gSetup.hi.xy))) return;
    voxelizeColumn(gSetup, column, gTriangle);
}
