// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Per-triangle precomputation of the factored triangle/voxel test (JCGT 2013 §3.1.2-3.1.3,
// after Schwarz & Seidel 2010), in voxel space where voxel p covers [p, p+1]^3.
//
// The triangle is swizzled so that w is its dominant normal axis and (u, v, w) is a cyclic
// (right-handed) permutation of (x, y, z): u = (w+1)%3, v = (w+2)%3. The voxelizer walks
// the (u, v) plane, finds the depth range along w from the plane, and confirms the two
// remaining projections (v, w) and (w, u).
//
// Each projected edge test is  f(p) = na*(pa - Va) + nb*(pb - Vb) + offset >= 0  with p the
// voxel's integer min corner: written relative to the edge's vertex so that axis-aligned
// edges and faces lying exactly on voxel planes evaluate exactly (a touch is a pass, so
// faces on voxel planes mark the voxels on both sides).
#include <array>
#include <cstdint>

#include "core/clamp_coord.h"
#include "hyvox/options.h"

namespace hyvox::cpu {

struct EdgeTest {
    double na, nb;  // inward normal of the projected edge (zero if the projection is a segment)
    double va, vb;  // the edge's start vertex in the plane's coordinates
    double offset;  // conservative: max(0,na)+max(0,nb); thin: the inscribed diamond's support
};

struct TriangleSetup {
    int w = 2;                     // dominant (depth) axis; u = (w+1)%3, v = (w+2)%3
    std::array<double, 3> origin;  // swizzled vertex 0 (the plane passes through it)
    std::array<double, 3> normal;  // swizzled, flipped so normal[2] (the w component) > 0
    EdgeTest uv[3], vw[3], wu[3];  // the three projections' edge tests
    // Depth range terms (see rasterizeRows, rasterize_triangle.h): conservative uses the
    // box's min/max corner offsets along the normal, thin the column centre.
    double depth_lo_offset = 0, depth_hi_offset = 0;
    // Clipped candidate voxel range in swizzled order (lo > hi: nothing to do).
    std::array<int, 3> lo{0, 0, 0}, hi{-1, -1, -1};
};

enum class SetupKind {
    Outside,        // the bounding box misses the grid: nothing to mark
    AllCandidates,  // conservative, and the triangle's extent lies within one voxel's range
                    // along at least two axes: every candidate voxel (unswizzled, out.lo to
                    // out.hi) holds a point of the triangle and is marked without any test
    Full,           // run the factored test over out's swizzled range
    Planeless,      // the corners' cross product is zero in voxel space (a segment or a
                    // point there): rasterizePlaneless (rasterize_planeless.h) over the
                    // unswizzled range out.lo to out.hi
};

// Builds the setup from voxel-space corners, the candidates clipped to the voxels
// clip_lo..clip_hi (inclusive, unswizzled x, y, z: the tile being filled).
SetupKind setupTriangle(const std::array<std::array<double, 3>, 3>& corners, Mode mode,
                        const std::array<std::int32_t, 3>& clip_lo, const std::array<std::int32_t, 3>& clip_hi,
                        TriangleSetup& out);

// The edge tests of one projection (a, b) of the corners c (any axis order) for a 2D
// triangle winding as sign `winding` (+1, -1; 0 makes tests that always pass).
void setupEdgeTests(const std::array<std::array<double, 3>, 3>& c, double winding, int a, int b, Mode mode,
                    EdgeTest out[3]);

// Whether voxel p (its min corner, in the projection's two coordinates) passes edge test e.
inline bool passes(const EdgeTest& e, double pa, double pb) {
    return e.na * (pa - e.va) + e.nb * (pb - e.vb) + e.offset >= 0.0;
}

// The setup's first step: the triangle's candidate voxels (unswizzled, inclusive) clipped to
// the tile, and per axis whether its unclipped extent lies within one voxel's range.
struct CandidateRange {
    std::array<int, 3> lo{0, 0, 0}, hi{-1, -1, -1};
    std::array<bool, 3> single{false, false, false};
    bool outside() const { return lo[0] > hi[0] || lo[1] > hi[1] || lo[2] > hi[2]; }
    int singleAxes() const { return int(single[0]) + int(single[1]) + int(single[2]); }
};

// The candidate range of voxel-space corners, clipped to clip_lo..clip_hi (the first step of
// setupTriangle above).
CandidateRange candidateRange(const std::array<std::array<double, 3>, 3>& corners,
                              const std::array<std::int32_t, 3>& clip_lo, const std::array<std::int32_t, 3>& clip_hi);

// The rest of the setup, for a range found by candidateRange or cellRange (vertex_cells.h);
// not outside(). The corners are read where they are stored (the vertex cache's entries: no
// copy of them is made).
SetupKind setupTriangle(const std::array<double, 3>& c0, const std::array<double, 3>& c1,
                        const std::array<double, 3>& c2, Mode mode, const CandidateRange& range, TriangleSetup& out);

// floor / ceil of values already clamped to a safe int range by clampCoord (the baseline
// x86-64 target has no inline rounding instruction, and libm calls dominate a small
// triangle's cost).
inline int floorToInt(double x) {
    const int i = int(x);
    return i - (x < double(i));
}
inline int ceilToInt(double x) {
    const int i = int(x);
    return i + (x > double(i));
}

}  // namespace hyvox::cpu
