// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A triangle cut into the voxels' closed boxes it meets by sweeping planes: into x slabs,
// each slab into y columns, each column into z cells (sweep_triangle.h permutes the axes so
// that z is the triangle's dominant one, and skips the columns it measures without cuts). Each plane cuts a polygon once and
// hands both sides on (the part below is the slab's, the rest goes on to the next plane), so a
// piece costs about one cut per axis, where clipping box by box (clipTriangleToVoxel) costs
// two per axis.
//
// Every edge remembers the line it lies on: an edge of the triangle (its corners in a fixed
// order, so two triangles sharing an edge cut it alike) or the cut of a plane through an
// earlier polygon (its two ends on the plane). A crossing point is interpolated between the
// ends of that line, not of the edge the previous plane left: a point's rounding does not
// depend on the planes cut before it, so neighbouring voxels, leaves and tiles see the same
// points and a touch through a voxel corner is found on every side (docs/design.md, "Attributes").
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "attributes/clip_to_voxel.h"

namespace hyvox::attributes {

// The lines of one triangle's sweep, as (a, b) with a before b in lexicographic order.
struct SweepLines {
    static constexpr int kMax = 32;
    static constexpr std::uint8_t kNone = 0xff;  // not recorded: interpolate on the edge itself
    std::array<Point, kMax> a, b;
    int n = 0;

    std::uint8_t add(const Point& p, const Point& q) {
        if (n == kMax) return kNone;
        const bool ordered = p <= q;
        a[std::size_t(n)] = ordered ? p : q;
        b[std::size_t(n)] = ordered ? q : p;
        return std::uint8_t(n++);
    }
};

// A convex polygon whose edge c (from corner c to c + 1) lies on lines[line[c]].
struct TracedPolygon {
    Polygon shape;
    std::array<std::uint8_t, Polygon::kMaxCorners> line;
};

// The triangle itself, where the sweep starts: its edges on lines of their own.
inline TracedPolygon tracedTriangle(const std::array<Point, 3>& corners, SweepLines& lines) {
    TracedPolygon whole;
    whole.shape.n = 3;
    for (std::size_t c = 0; c < 3; ++c) {
        whole.shape.p[c] = corners[c];
        whole.line[c] = lines.add(corners[c], corners[(c + 1) % 3]);
    }
    return whole;
}

// The parts of `in` with x[Axis] <= at (`below`) and >= at (`above`); corners on the plane go
// to both, crossing points are placed exactly on it. With `record_cut` the new edges along
// the plane get a new line of `lines` (its ends: the extreme points on the plane), else none
// (kNone: those edges are not cut again). Either side may be left empty (n = 0).
template <int Axis>
void splitAtPlane(const TracedPolygon& in, double at, SweepLines& lines, bool record_cut, TracedPolygon& below,
                  TracedPolygon& above) {
    const int n = in.shape.n;
    const std::uint8_t cut = record_cut && lines.n < SweepLines::kMax ? std::uint8_t(lines.n) : SweepLines::kNone;
    double distance[Polygon::kMaxCorners];
    for (int c = 0; c < n; ++c) distance[c] = in.shape.p[std::size_t(c)][Axis] - at;
    int nb = 0, na = 0;
    Point lowest{}, highest{};  // of the points on the plane
    int on_plane = 0;
    const auto push = [](TracedPolygon& out, int& count, const Point& point, std::uint8_t line) {
        if (count == Polygon::kMaxCorners) return;
        out.shape.p[std::size_t(count)] = point;
        out.line[std::size_t(count++)] = line;
    };
    const auto onPlane = [&](const Point& point) {
        if (on_plane++ == 0) {
            lowest = highest = point;
        } else {
            lowest = std::min(lowest, point);
            highest = std::max(highest, point);
        }
    };
    for (int c = 0; c < n; ++c) {
        const int next = c + 1 < n ? c + 1 : 0;
        const Point& cur = in.shape.p[std::size_t(c)];
        const std::uint8_t line = in.line[std::size_t(c)];
        const double dc = distance[c], dn = distance[next];
        if (dc == 0) {
            push(below, nb, cur, dn <= 0 ? line : cut);
            push(above, na, cur, dn >= 0 ? line : cut);
            if (cut != SweepLines::kNone) onPlane(cur);
            continue;
        }
        if (dc < 0)
            push(below, nb, cur, line);
        else
            push(above, na, cur, line);
        if ((dc < 0 && dn > 0) || (dc > 0 && dn < 0)) {
            const Point& nxt = in.shape.p[std::size_t(next)];
            Point crossing;
            const double span = line != SweepLines::kNone ? lines.b[line][Axis] - lines.a[line][Axis] : 0.0;
            if (span != 0) {
                const Point& from = lines.a[line];
                const Point& to = lines.b[line];
                const double t = (at - from[Axis]) / span;
                for (std::size_t d = 0; d < 3; ++d) crossing[d] = from[d] + (to[d] - from[d]) * t;
            } else {
                const double t = dc / (dc - dn);
                for (std::size_t d = 0; d < 3; ++d) crossing[d] = cur[d] + (nxt[d] - cur[d]) * t;
            }
            crossing[Axis] = at;
            // Leaving a side, the crossing's edge runs along the plane; entering, along `line`.
            push(below, nb, crossing, dc < 0 ? cut : line);
            push(above, na, crossing, dc < 0 ? line : cut);
            if (cut != SweepLines::kNone) onPlane(crossing);
        }
    }
    below.shape.n = nb;
    above.shape.n = na;
    if (cut != SweepLines::kNone && on_plane > 0) lines.add(lowest, highest);  // else no edge took `cut`
}

// Calls visit(i, piece) for every voxel index i in [lo, hi] along Axis whose closed slab
// [i, i + 1] the polygon (n > 0) meets, in ascending order; `piece` is valid during the call.
// With `record_cuts`, the planes' cut lines are added to `lines` and taken off again at the
// end (the visits may add and take off their own after them). The slabs [skip_from, skip_to]
// are neither cut apart nor visited (the caller measures them another way): one cut at
// skip_to + 1 drops them.
template <int Axis, typename Visit>
void sweepSlabs(const TracedPolygon& polygon, int lo, int hi, SweepLines& lines, bool record_cuts, Visit&& visit,
                int skip_from = 1, int skip_to = 0) {
    const Polygon& shape = polygon.shape;
    double from = shape.p[0][Axis], to = from;
    for (int c = 1; c < shape.n; ++c) {
        from = std::min(from, shape.p[std::size_t(c)][Axis]);
        to = std::max(to, shape.p[std::size_t(c)][Axis]);
    }
    // Slab i meets [from, to] when i <= to and i + 1 >= from (clamped in double first, so
    // far-away corners cannot overflow an int).
    const double low_clamp = double(lo) - 2, high_clamp = double(hi) + 2;
    const int first = std::max(lo, int(std::ceil(std::clamp(from, low_clamp, high_clamp))) - 1);
    const int last = std::min(hi, int(std::floor(std::clamp(to, low_clamp, high_clamp))));
    if (first > last || (skip_from <= first && skip_to >= last)) return;  // nothing to visit
    const int lines_before = lines.n;
    TracedPolygon buffers[3];
    TracedPolygon* slab = &buffers[0];
    TracedPolygon* rest = &buffers[1];
    TracedPolygon* spare = &buffers[2];
    const TracedPolygon* current = &polygon;
    if (from < double(first)) {  // the part below slab `first` is another leaf's
        splitAtPlane<Axis>(*current, double(first), lines, record_cuts, *spare, *rest);
        if (rest->shape.n == 0) {
            lines.n = lines_before;
            return;
        }
        current = rest;
        std::swap(rest, spare);
    }
    for (int i = first; i <= last; ++i) {
        if (i >= skip_from && i <= skip_to) {
            if (skip_to >= last) break;
            splitAtPlane<Axis>(*current, double(skip_to) + 1.0, lines, record_cuts, *slab, *rest);
            if (rest->shape.n == 0) break;
            current = rest;
            std::swap(rest, spare);
            i = skip_to;
            continue;
        }
        const double top = double(i) + 1.0;
        if (to < top || (to == top && i == last)) {  // the slab holds all that is left
            visit(i, *current);
            break;
        }
        splitAtPlane<Axis>(*current, top, lines, record_cuts, *slab, *rest);
        if (slab->shape.n > 0) visit(i, *slab);
        if (rest->shape.n == 0 || i == last) break;
        current = rest;
        std::swap(rest, spare);
    }
    lines.n = lines_before;
}

}  // namespace hyvox::attributes
