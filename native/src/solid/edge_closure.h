// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Is the mesh closed and consistently oriented? After welding vertices at identical
// positions, every edge must be used by exactly two triangles running it in opposite
// directions. The edges that fail are counted, and those whose uses do not cancel (one use,
// or more one way than the other) are kept: the winding number's gradient is a line integral
// over exactly these edges (solid/gradient_bound.h), and a ray's parity changes only where
// the ray passes one of them.
#include <array>
#include <cstdint>
#include <vector>

#include "hyvox/grid.h"
#include "hyvox/mesh.h"

namespace hyvox::solid {

struct OpenEdge {
    std::array<double, 3> a, b;  // voxel space, in the direction most uses run (a -> b)
    std::uint32_t excess;        // uses a->b - uses b->a (> 0)
};

struct EdgeClosure {
    std::uint64_t boundary_edges = 0;     // used once
    std::uint64_t nonmanifold_edges = 0;  // used more than twice
    std::uint64_t misoriented_edges = 0;  // used twice in the same direction
    std::vector<OpenEdge> open_edges;     // uses that do not cancel
    bool closedAndOriented() const { return boundary_edges == 0 && nonmanifold_edges == 0 && misoriented_edges == 0; }
};

EdgeClosure checkEdges(const ValidatedMesh& mesh, const GridSpec& grid);

}  // namespace hyvox::solid
