// SPDX-License-Identifier: GPL-3.0-or-later
#include "solid/gradient_bound.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "solid/median_split.h"

namespace hyvox::solid {
namespace {

constexpr std::uint32_t kLeafEdges = 8;
constexpr double kFarRadii = 2.0;  // a cluster this many radii away counts as a whole

double boxDistance2(const Box& a, const Box& b) {
    double d2 = 0;
    for (int k = 0; k < 3; ++k) {
        const double gap = std::max({0.0, a.lo[k] - b.hi[k], b.lo[k] - a.hi[k]});
        d2 += gap * gap;
    }
    return d2;
}

Box unite(const Box& a, const Box& b) {
    Box out;
    for (int k = 0; k < 3; ++k) out.lo[k] = std::min(a.lo[k], b.lo[k]), out.hi[k] = std::max(a.hi[k], b.hi[k]);
    return out;
}

// Whether the box's xy range meets that of an edge's (or a cluster's) box `edge`.
bool meetsInXy(const Box& box, const Box& edge) {
    return box.lo[0] <= edge.hi[0] && box.hi[0] >= edge.lo[0] && box.lo[1] <= edge.hi[1] && box.hi[1] >= edge.lo[1];
}

// Whether the box reaches the region above (`upward`: below) an edge whose own box is `edge`,
// where rays down (up) pass the edge.
bool reachesShadow(const Box& box, const Box& edge, bool upward) {
    return meetsInXy(box, edge) && (upward ? box.lo[2] <= edge.hi[2] : box.hi[2] >= edge.lo[2]);
}

}  // namespace

GradientBound::GradientBound(const std::vector<OpenEdge>& edges) {
    edges_.reserve(edges.size());
    for (const OpenEdge& e : edges) {
        Box box;
        double length2 = 0;
        for (int k = 0; k < 3; ++k) {
            box.lo[k] = std::min(e.a[k], e.b[k]);
            box.hi[k] = std::max(e.a[k], e.b[k]);
            length2 += (e.a[k] - e.b[k]) * (e.a[k] - e.b[k]);
        }
        edges_.push_back({box, double(e.excess) * std::sqrt(length2), e.a, e.b, e.excess});
    }
    if (!edges_.empty()) build(0, std::uint32_t(edges_.size()));
}

std::int32_t GradientBound::build(std::uint32_t first, std::uint32_t count) {
    const auto id = std::int32_t(nodes_.size());
    nodes_.emplace_back();
    Node node;
    node.first = first;
    node.count = count;
    node.box = edges_[first].box;
    for (std::uint32_t e = first; e < first + count; ++e) {
        node.box = unite(node.box, edges_[e].box);
        node.weight += edges_[e].weight;
        for (int k = 0; k < 3; ++k) node.net[k] += double(edges_[e].excess) * (edges_[e].b[k] - edges_[e].a[k]);
    }
    for (int k = 0; k < 3; ++k) node.centre[k] = 0.5 * (node.box.lo[k] + node.box.hi[k]);
    for (std::uint32_t e = first; e < first + count; ++e)
        for (const auto* end : {&edges_[e].a, &edges_[e].b}) {
            double r2 = 0;
            for (int k = 0; k < 3; ++k) r2 += ((*end)[k] - node.centre[k]) * ((*end)[k] - node.centre[k]);
            node.radius = std::max(node.radius, std::sqrt(r2));
        }
    if (count > kLeafEdges) {
        const std::uint32_t half = splitAtMedian(
            edges_, first, count, node.box.lo, node.box.hi,
            [](const Edge& e, int axis) {
                return e.box.lo[axis] + e.box.hi[axis];  // twice the centre
            },
            [](const Edge& x, const Edge& y) {
                return std::tie(x.a, x.b, x.excess, x.weight) < std::tie(y.a, y.b, y.excess, y.weight);
            });
        node.left = build(first, half);
        node.right = build(first + half, count - half);
    }
    nodes_[std::size_t(id)] = node;
    return id;
}

double GradientBound::windingSlope(const Box& box, double limit) const {
    if (nodes_.empty()) return 0.0;
    const double scaled_limit = limit * 4.0 * M_PI;
    double sum = 0;
    std::int32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = nodes_[std::size_t(stack[--top])];
        // From the box to the cluster's centre: at least d for every point of the box.
        double d2 = 0;
        for (int k = 0; k < 3; ++k) {
            const double gap = std::max({0.0, box.lo[k] - node.centre[k], node.centre[k] - box.hi[k]});
            d2 += gap * gap;
        }
        const double d = std::sqrt(d2);
        if (d >= kFarRadii * node.radius) {
            // Far: the dipole bound (see the header), or the edges at the nearest distance.
            const double net2 = node.net[0] * node.net[0] + node.net[1] * node.net[1] + node.net[2] * node.net[2];
            const double gap = d - node.radius;
            const double dipole = std::sqrt(net2) / d2 + 2.0 * node.weight * node.radius / (gap * gap * gap);
            const double box_d2 = boxDistance2(box, node.box);
            sum += box_d2 > 0 ? std::min(dipole, node.weight / box_d2) : dipole;
        } else if (node.left < 0) {
            for (std::uint32_t e = node.first; e < node.first + node.count; ++e) {
                const double de2 = boxDistance2(box, edges_[e].box);
                if (de2 <= 0) return HUGE_VAL;
                sum += edges_[e].weight / de2;
            }
        } else {
            // The nearer child first: where the bound fails (near an open edge, most boxes of
            // an open mesh) its largest terms come sooner, so fewer nodes are visited before it
            // does (docs/why/solid.md).
            const bool left_nearer = boxDistance2(box, nodes_[std::size_t(node.left)].box) <=
                boxDistance2(box, nodes_[std::size_t(node.right)].box);
            stack[top++] = left_nearer ? node.right : node.left;
            stack[top++] = left_nearer ? node.left : node.right;
        }
        // Past the limit: a partial sum, below the whole bound, must not pass for it (the
        // caller's own comparison, rounded, could find it just under the limit).
        if (sum > scaled_limit) return HUGE_VAL;
    }
    return sum / (4.0 * M_PI);
}

bool GradientBound::parityMayChange(const Box& box) const {
    if (nodes_.empty()) return false;
    std::int32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = nodes_[std::size_t(stack[--top])];
        if (!reachesShadow(box, node.box, false)) continue;
        if (node.left >= 0) {
            stack[top++] = node.left;
            stack[top++] = node.right;
            continue;
        }
        for (std::uint32_t e = node.first; e < node.first + node.count; ++e)
            if (reachesShadow(box, edges_[e].box, false)) return true;
    }
    return false;
}

void GradientBound::sheetsMeeting(const Box& box, std::vector<Sheet>& down, std::vector<Sheet>& up) const {
    down.clear();
    up.clear();
    if (nodes_.empty()) return;
    // A cluster whose xy range meets the box's reaches it from below or from above (or both):
    // one walk for both lists, each in the order its own walk would give.
    std::int32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = nodes_[std::size_t(stack[--top])];
        if (!meetsInXy(box, node.box)) continue;
        if (node.left >= 0) {
            stack[top++] = node.left;
            stack[top++] = node.right;
            continue;
        }
        for (std::uint32_t e = node.first; e < node.first + node.count; ++e) {
            const Edge& edge = edges_[e];
            if (reachesShadow(box, edge.box, false)) down.push_back({edge.a, edge.b, double(edge.excess)});
            if (reachesShadow(box, edge.box, true)) up.push_back({edge.a, edge.b, double(edge.excess)});
        }
    }
}

std::vector<GradientBound::Sheet> GradientBound::allSheets() const {
    std::vector<Sheet> sheets;
    sheets.reserve(edges_.size());
    for (const Edge& edge : edges_) sheets.push_back({edge.a, edge.b, double(edge.excess)});
    return sheets;
}

}  // namespace hyvox::solid
