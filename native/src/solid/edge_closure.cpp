// SPDX-License-Identifier: GPL-3.0-or-later
#include "solid/edge_closure.h"

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cstring>
#include <tuple>

namespace hyvox::solid {
namespace {

// A position's bits as a sortable key; -0 and +0 are one position.
std::array<std::uint32_t, 3> positionKey(const float* p) {
    std::array<std::uint32_t, 3> key{};
    for (int a = 0; a < 3; ++a) {
        const float v = p[a] == 0.0f ? 0.0f : p[a];
        std::memcpy(&key[a], &v, sizeof v);
    }
    return key;
}

// One id per distinct position, for every vertex.
std::vector<std::uint32_t> weldVertices(const MeshView& view) {
    std::vector<std::uint32_t> order(view.vertex_count);
    for (std::uint32_t v = 0; v < order.size(); ++v) order[v] = v;
    auto key = [&](std::uint32_t v) { return positionKey(view.positions + 3 * std::size_t(v)); };
    // Sorted on all threads: on meshes of a million triangles this check is most of solid mode's
    // own time.
    tbb::parallel_sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) { return key(x) < key(y); });
    std::vector<std::uint32_t> weld(view.vertex_count);
    for (std::size_t n = 0; n < order.size(); ++n)
        weld[order[n]] = n > 0 && key(order[n]) == key(order[n - 1]) ? weld[order[n - 1]] : order[n];
    return weld;
}

struct DirectedEdge {
    std::uint32_t low, high;  // welded ids, low < high
    bool forward;             // the triangle runs low -> high
    bool operator<(const DirectedEdge& o) const { return std::tie(low, high) < std::tie(o.low, o.high); }
};

}  // namespace

EdgeClosure checkEdges(const ValidatedMesh& mesh, const GridSpec& grid) {
    const MeshView& view = mesh.view;
    const std::vector<std::uint32_t> weld = weldVertices(view);
    std::vector<DirectedEdge> edges;
    edges.reserve(3 * mesh.usable.size());
    // Every triangle, the degenerate ones included: a zero-area sliver between two edges is part
    // of the surface's topology (without it they would look open), and adds no solid angle
    // and no ray crossing.
    for (std::size_t t = 0; t < view.triangle_count; ++t) {
        const std::uint32_t* v = view.triangles + 3 * t;
        for (int c = 0; c < 3; ++c) {
            const std::uint32_t from = weld[v[c]], to = weld[v[(c + 1) % 3]];
            if (from == to) continue;  // welded away: no edge
            edges.push_back({std::min(from, to), std::max(from, to), from < to});
        }
    }
    tbb::parallel_sort(edges.begin(), edges.end());
    EdgeClosure out;
    for (std::size_t first = 0; first < edges.size();) {
        std::size_t last = first;
        std::uint32_t forward = 0, backward = 0;
        for (; last < edges.size() && edges[last].low == edges[first].low && edges[last].high == edges[first].high; ++last)
            (edges[last].forward ? forward : backward) += 1;
        const std::uint32_t uses = forward + backward;
        if (uses == 1) ++out.boundary_edges;
        else if (uses > 2) ++out.nonmanifold_edges;
        else if (forward != backward) ++out.misoriented_edges;
        if (forward != backward) {
            // Oriented the way the surplus uses run: the open edges then form closed loops
            // (gradient_bound.cpp relies on that for its far-field bound).
            const std::uint32_t from = forward > backward ? edges[first].low : edges[first].high;
            const std::uint32_t to = forward > backward ? edges[first].high : edges[first].low;
            const float* a = view.positions + 3 * std::size_t(from);
            const float* b = view.positions + 3 * std::size_t(to);
            out.open_edges.push_back({grid.toVoxel(std::array<float, 3>{a[0], a[1], a[2]}),
                                      grid.toVoxel(std::array<float, 3>{b[0], b[1], b[2]}),
                                      forward > backward ? forward - backward : backward - forward});
        }
        first = last;
    }
    return out;
}

}  // namespace hyvox::solid
