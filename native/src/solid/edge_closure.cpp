// SPDX-License-Identifier: GPL-3.0-or-later
#include "solid/edge_closure.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
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

// One id per distinct position, for every vertex: the lowest index of the vertices there.
std::vector<std::uint32_t> weldVertices(const MeshView& view) {
    // Keys copied beside their vertex and sorted as plain words (a comparison that fetched both
    // positions cost three times as much); the index breaks ties, so the ids do not depend on
    // how the parallel sort splits the work.
    struct KeyedVertex {
        std::array<std::uint32_t, 3> key;
        std::uint32_t vertex;
        bool operator<(const KeyedVertex& o) const { return std::tie(key, vertex) < std::tie(o.key, o.vertex); }
    };
    std::vector<KeyedVertex> order(view.vertex_count);
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, view.vertex_count, 65536), [&](const auto& range) {
        for (std::uint32_t v = range.begin(); v < range.end(); ++v)
            order[v] = {positionKey(view.positions + 3 * std::size_t(v)), v};
    });
    // Sorted on all threads: on meshes of a million triangles this check is a large part of
    // solid mode's own time.
    tbb::parallel_sort(order.begin(), order.end());
    std::vector<std::uint32_t> weld(view.vertex_count);
    for (std::size_t n = 0; n < order.size(); ++n)
        weld[order[n].vertex] = n > 0 && order[n].key == order[n - 1].key ? weld[order[n - 1].vertex] : order[n].vertex;
    return weld;
}

// One use of an edge, filed under its lower welded end.
struct EdgeUse {
    std::uint32_t high;  // the other (higher) welded end
    bool forward;        // the triangle runs low -> high
};

}  // namespace

EdgeClosure checkEdges(const ValidatedMesh& mesh, const GridSpec& grid) {
    const MeshView& view = mesh.view;
    const std::vector<std::uint32_t> weld = weldVertices(view);
    // The uses are filed by their lower end (a counting pass, then a filling pass) rather than
    // sorted as a whole: a vertex has a handful of edges, so each one's list is sorted in place,
    // which made the check a small part of solid mode's time (docs/why/solid.md).
    // Every triangle, the degenerate ones included: a zero-area sliver between two edges is part
    // of the surface's topology (without it they would look open), and adds no solid angle
    // and no ray crossing.
    auto forEachEdge = [&](auto&& use) {
        for (std::size_t t = 0; t < view.triangle_count; ++t) {
            const std::uint32_t* v = view.triangles + 3 * t;
            for (int c = 0; c < 3; ++c) {
                const std::uint32_t from = weld[v[c]], to = weld[v[(c + 1) % 3]];
                if (from != to) use(from, to);  // welded away: no edge
            }
        }
    };
    std::vector<std::size_t> first_use(std::size_t(view.vertex_count) + 1, 0);
    forEachEdge([&](std::uint32_t from, std::uint32_t to) { ++first_use[std::min(from, to) + 1]; });
    for (std::size_t v = 0; v < view.vertex_count; ++v) first_use[v + 1] += first_use[v];
    std::vector<EdgeUse> uses(first_use.back());
    {
        std::vector<std::size_t> next(first_use.begin(), first_use.end() - 1);
        forEachEdge([&](std::uint32_t from, std::uint32_t to) {
            uses[next[std::min(from, to)]++] = {std::max(from, to), from < to};
        });
    }
    const auto byHigh = [](const EdgeUse& x, const EdgeUse& y) { return x.high < y.high; };
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, view.vertex_count, 4096), [&](const auto& range) {
        for (std::size_t v = range.begin(); v < range.end(); ++v)
            std::sort(uses.begin() + first_use[v], uses.begin() + first_use[v + 1], byHigh);
    });
    EdgeClosure out;
    for (std::uint32_t low = 0; low < view.vertex_count; ++low) {
        const std::size_t end = first_use[low + 1];
        for (std::size_t first = first_use[low]; first < end;) {
            const std::uint32_t high = uses[first].high;
            std::size_t last = first;
            std::uint32_t forward = 0, backward = 0;
            for (; last < end && uses[last].high == high; ++last) (uses[last].forward ? forward : backward) += 1;
            const std::uint32_t count = forward + backward;
            if (count == 1)
                ++out.boundary_edges;
            else if (count > 2)
                ++out.nonmanifold_edges;
            else if (forward != backward)
                ++out.misoriented_edges;
            if (forward != backward) {
                // Oriented the way the surplus uses run: the open edges then form closed loops
                // (gradient_bound.cpp relies on that for its far-field bound).
                const std::uint32_t from = forward > backward ? low : high;
                const std::uint32_t to = forward > backward ? high : low;
                const float* a = view.positions + 3 * std::size_t(from);
                const float* b = view.positions + 3 * std::size_t(to);
                out.open_edges.push_back({grid.toVoxel(std::array<float, 3>{a[0], a[1], a[2]}),
                                          grid.toVoxel(std::array<float, 3>{b[0], b[1], b[2]}),
                                          forward > backward ? forward - backward : backward - forward});
            }
            first = last;
        }
    }
    return out;
}

}  // namespace hyvox::solid
