// SPDX-License-Identifier: GPL-3.0-or-later
// The triangle an invocation handles: work groups along x, and y when there are more
// triangles than one dimension's work-group count allows (65535 × HYVOX_LOCAL_SIZE is the
// guaranteed minimum). Work groups along z are chunks of one triangle's columns.
#include "common/bindings.glsl"

layout(local_size_x = HYVOX_LOCAL_SIZE) in;

uint invocationTriangle() {
    return (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * uint(HYVOX_LOCAL_SIZE) +
           gl_LocalInvocationID.x;
}

uint invocationChunk() { return gl_WorkGroupID.z; }
