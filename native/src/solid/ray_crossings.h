// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Ray crossings: the surface crossings of the ray from a point straight down (-z), counted
// with their sign (+1 where the ray leaves through a face turned down, -1 up). Their parity is
// the parity rule; on a closed, consistently oriented mesh their sum is the winding number
// itself, exactly (overlapping or nested shells included). Exact for closed meshes, including rays through shared edges and vertices:
// vertices are snapped to a fixed-point lattice of 2^-20 voxel (every triangle that shares a
// vertex sees the same snapped vertex), the point-in-projected-triangle tests are exact
// 128-bit integer orientations, and a point lying exactly on a projected edge is decided as
// if it were moved by (ε, ε²) (symbolic perturbation), the same for both triangles of an edge,
// so a closed surface's shared edge or vertex is crossed exactly once.
#include <array>
#include <cstdint>
#include <vector>

#include "hyvox/grid.h"
#include "hyvox/mesh.h"

namespace hyvox::solid {

class RayCrossings {
public:
    // Throws InvalidInput when a vertex lies more than 2^40 voxels from the grid.
    RayCrossings(const ValidatedMesh& mesh, const GridSpec& grid);
    // The signed crossings of the ray from voxel (i,j,k)'s centre down (their count modulo 2 is
    // the parity). The centre must not lie on the surface.
    int at(int i, int j, int k) const;
    // Every crossing of the whole line through voxel column (i, j)'s centres: its height and
    // sign, in no order. The signed crossings below height z are the signs of those below z.
    struct Crossing {
        double z;
        int sign;
    };
    void column(int i, int j, std::vector<Crossing>& out) const;
    // The same for the block of columns [i0, i0 + ni) × [j0, j0 + nj) (inside the grid), into
    // out[(i - i0) nj + (j - j0)]: one pass over each 8×8 bucket's triangles instead of one per
    // column.
    void columns(int i0, int j0, int ni, int nj, std::vector<Crossing>* out) const;

private:
    // Calls visit(height, sign) for each crossing of column (i, j)'s line.
    template <typename Visit>
    void forEachCrossing(int i, int j, Visit visit) const;
    struct Triangle;
    // Calls visit(height, sign) if ray (px, py) (fixed point) crosses t.
    template <typename Visit>
    static void crossing(const Triangle& t, std::int64_t px, std::int64_t py, Visit visit);
    struct Triangle {
        std::array<std::int64_t, 3> x, y;  // snapped xy of the corners
        std::array<double, 3> z;           // voxel-space z of the corners
        int sign;                          // +1 when the face looks down (xy order clockwise)
        std::int64_t x_lo, x_hi, y_lo, y_hi;
    };
    std::array<std::int32_t, 2> columns_{0, 0};  // 8×8-ray columns along x and y
    std::vector<Triangle> triangles_;            // those whose projection is not a line
    std::vector<std::uint32_t> column_start_;    // CSR: triangles of column (cx, cy)
    std::vector<std::uint32_t> column_triangles_;
    // Beside each entry of column_triangles_: the bucket's rays in the triangle's xy box, as
    // (first x, last x, first y, last y), each the ray's offset in the bucket plus 1, clamped
    // to 0..9 (so "first > last" says no ray).
    std::vector<std::array<std::uint8_t, 4>> column_rays_;
};

}  // namespace hyvox::solid
