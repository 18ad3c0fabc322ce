// SPDX-License-Identifier: GPL-3.0-or-later
#include "solid/gradient_bound.h"

#include <algorithm>
#include <cmath>

#include "solid/median_split.h"

namespace hyvox::solid {
namespace {

constexpr std::uint32_t kLeafEdges = 8;

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

// Whether the box reaches the region above an edge whose own box is `edge`.
bool reachesShadow(const Box& box, const Box& edge) {
    return box.lo[0] <= edge.hi[0] && box.hi[0] >= edge.lo[0] && box.lo[1] <= edge.hi[1] && box.hi[1] >= edge.lo[1] &&
           box.hi[2] >= edge.lo[2];
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
        edges_.push_back({box, double(e.excess) * std::sqrt(length2)});
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
    }
    if (count > kLeafEdges) {
        const std::uint32_t half = splitAtMedian(edges_, first, count, node.box.lo, node.box.hi, [](const Edge& e, int axis) {
            return e.box.lo[axis] + e.box.hi[axis];  // twice the centre
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
        const double d2 = boxDistance2(box, node.box);
        double size2 = 0;
        for (int k = 0; k < 3; ++k) size2 += (node.box.hi[k] - node.box.lo[k]) * (node.box.hi[k] - node.box.lo[k]);
        if (d2 > 0 && d2 >= 4 * size2) {
            sum += node.weight / d2;  // far enough: the whole cluster at the box's distance
        } else if (node.left < 0) {
            for (std::uint32_t e = node.first; e < node.first + node.count; ++e) {
                const double de2 = boxDistance2(box, edges_[e].box);
                if (de2 <= 0) return HUGE_VAL;
                sum += edges_[e].weight / de2;
            }
        } else {
            stack[top++] = node.left;
            stack[top++] = node.right;
        }
        if (sum > scaled_limit) break;
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
        if (!reachesShadow(box, node.box)) continue;
        if (node.left >= 0) {
            stack[top++] = node.left;
            stack[top++] = node.right;
            continue;
        }
        for (std::uint32_t e = node.first; e < node.first + node.count; ++e)
            if (reachesShadow(box, edges_[e].box)) return true;
    }
    return false;
}

}  // namespace hyvox::solid
