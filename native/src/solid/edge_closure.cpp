// SPDX-License-Identifier: GPL-3.0-or-later
#include "solid/edge_closure.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstring>
#include <limits>

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
// A table open-addressed by the position's bits, at most half full, its slots holding the first
// vertex met at a position: the vertices are visited in index order, so that one is the lowest.
// One pass over the vertices where sorting their keys took several; the ids are the sort's.
std::vector<std::uint32_t> weldVertices(const MeshView& view) {
    constexpr std::uint32_t kEmpty = std::numeric_limits<std::uint32_t>::max();
    const std::size_t n = view.vertex_count;
    std::size_t size = 16;
    while (size < 2 * n) size *= 2;
    std::vector<std::uint32_t> slots(size, kEmpty);
    std::vector<std::uint32_t> weld(n);
    for (std::uint32_t v = 0; v < n; ++v) {
        const std::array<std::uint32_t, 3> key = positionKey(view.positions + 3 * std::size_t(v));
        std::uint64_t hash = ((std::uint64_t(key[0]) << 32) | key[1]) * 0x9E3779B97F4A7C15ull;
        hash = (hash ^ (hash >> 29) ^ key[2]) * 0xBF58476D1CE4E5B9ull;
        for (std::size_t slot = (hash ^ (hash >> 32)) & (size - 1);; slot = (slot + 1) & (size - 1)) {
            if (slots[slot] == kEmpty) {
                slots[slot] = weld[v] = v;
                break;
            }
            if (positionKey(view.positions + 3 * std::size_t(slots[slot])) == key) {
                weld[v] = slots[slot];
                break;
            }
        }
    }
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
