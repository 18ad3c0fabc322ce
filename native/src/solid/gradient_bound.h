// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// How fast an inside test's value can change inside a box that no triangle meets, from the
// open edges alone (solid/edge_closure.h).
//
// Winding number: the gradient of a triangle's solid angle at a point off the triangle is the
// Biot-Savart integral around its edges, ∮ dl × r / |r|³. Summed over the mesh, the uses of an
// edge that run both ways cancel, so |∇w| <= 1/(4π) Σ_open excess · length / distance², where
// distance is from the box to the edge. A closed, consistently oriented mesh has no open
// edge: w is constant on every surface-free connected region.
//
// The open edges, oriented by their surplus uses, form closed loops (every triangle is one),
// so far away their fields cancel to a dipole's: for a cluster of edges with net direction
// J = Σ excess · (b - a), weight W = Σ excess · length, all within R of a point c that lies
// d > R from a point p, the Taylor bound of the kernel r/|r|³ about c (its derivative has norm
// 2/|r|³) gives |∫ dl × (x - p)/|x - p|³| <= |J|/d² + 2 W R/(d - R)³: the far field falls as
// 1/d³ where loops close inside a cluster, instead of the W/d² of the edges one by one.
//
// Ray parity (rays along -z): a ray's crossing count changes only where the ray passes an
// open edge, so it is constant over a box unless the box reaches above some open edge's
// shadow: its xy range meets the edge's and its top lies above the edge's lowest point.
#include <array>
#include <cstdint>
#include <vector>

#include "solid/edge_closure.h"

namespace hyvox::solid {

struct Box {
    std::array<double, 3> lo, hi;  // voxel space
};

class GradientBound {
public:
    explicit GradientBound(const std::vector<OpenEdge>& edges);
    bool empty() const { return nodes_.empty(); }
    // An upper bound of |∇w| over `box`; stops adding (and returns infinity) as soon as the
    // bound passes `limit`. Infinite when an open edge meets the box.
    double windingSlope(const Box& box, double limit) const;
    // Whether the parity of -z rays may differ between two points of `box`.
    bool parityMayChange(const Box& box) const;
    // The open edges whose sheet above (where -z rays pass them: `down`) and below (where +z
    // rays do: `up`) meets `box`.
    struct Sheet {
        std::array<double, 3> a, b;  // the edge, in the direction of its surplus uses
        double excess;
    };
    void sheetsMeeting(const Box& box, std::vector<Sheet>& down, std::vector<Sheet>& up) const;
    // Every open edge as a sheet.
    std::vector<Sheet> allSheets() const;
    std::size_t edgeCount() const { return edges_.size(); }

private:
    struct Node {
        Box box;
        double weight = 0;                      // Σ excess · length
        std::array<double, 3> centre{}, net{};  // the box's centre; Σ excess · (b - a)
        double radius = 0;                      // from centre to the farthest edge end
        std::uint32_t first = 0, count = 0;
        std::int32_t left = -1, right = -1;
    };
    struct Edge {
        Box box;
        double weight;
        std::array<double, 3> a, b;  // the ends
        std::uint32_t excess;
    };
    std::int32_t build(std::uint32_t first, std::uint32_t count);

    std::vector<Edge> edges_;
    std::vector<Node> nodes_;
};

}  // namespace hyvox::solid
