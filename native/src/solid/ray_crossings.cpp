// SPDX-License-Identifier: GPL-3.0-or-later
#include "solid/ray_crossings.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "hyvox/errors.h"

namespace hyvox::solid {
namespace {

constexpr int kFractionBits = 20;
constexpr double kScale = double(1 << kFractionBits);
constexpr double kLimit = 1099511627776.0;  // 2^40 voxels

__extension__ typedef __int128 Wide;  // exact products of two 61-bit differences

constexpr const char* kFarVertex =
    "solid mode: a vertex lies more than 2^40 voxels from the grid; use a larger voxel size";

// A coordinate within kLimit voxels of the grid, in fixed point.
std::int64_t snap(double voxel) { return std::llround(voxel * kScale); }

// Twice the signed area of (u, v, p) in xy, exactly.
Wide orient(std::int64_t ux, std::int64_t uy, std::int64_t vx, std::int64_t vy, std::int64_t px, std::int64_t py) {
    return Wide(vx - ux) * Wide(py - uy) - Wide(vy - uy) * Wide(px - ux);
}

// The side of edge u->v that p lies on: +1 left, -1 right; on the line, the side of
// p + (ε, ε²) (the derivative of orient() along x, then along y). Antisymmetric in u, v.
int side(std::int64_t ux, std::int64_t uy, std::int64_t vx, std::int64_t vy, std::int64_t px, std::int64_t py) {
    const Wide value = orient(ux, uy, vx, vy, px, py);
    if (value != 0) return value > 0 ? 1 : -1;
    if (vy != uy) return vy < uy ? 1 : -1;  // d/dpx of orient = -(vy - uy)
    return vx > ux ? 1 : -1;                // d/dpy of orient = vx - ux (u != v here)
}

// Ray i's fixed-point coordinate: the middle of voxel column i.
std::int64_t rayAt(int i) { return (std::int64_t(2 * i + 1)) << (kFractionBits - 1); }
// The first ray at or after fixed-point coordinate `lo`, and the last at or before `hi`.
std::int64_t firstRay(std::int64_t lo) {
    const std::int64_t half = std::int64_t(1) << (kFractionBits - 1);
    return (lo - half + (std::int64_t(1) << kFractionBits) - 1) >> kFractionBits;
}
std::int64_t lastRay(std::int64_t hi) {
    const std::int64_t half = std::int64_t(1) << (kFractionBits - 1);
    return (hi - half) >> kFractionBits;
}

}  // namespace

RayCrossings::RayCrossings(const ValidatedMesh& mesh, const GridSpec& grid) {
    columns_ = {(grid.dims[0] + 7) / 8, (grid.dims[1] + 7) / 8};
    const MeshView& view = mesh.view;
    // Snapped per vertex, so all triangles sharing a vertex share its snapped position; those
    // past the snapping's range marked far.
    std::vector<std::array<std::int64_t, 2>> snapped(view.vertex_count);
    std::vector<double> heights(view.vertex_count);
    std::vector<char> far(view.vertex_count);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, view.vertex_count, 16384), [&](const auto& range) {
        for (std::size_t v = range.begin(); v != range.end(); ++v) {
            const float* position = view.positions + 3 * v;
            const std::array<double, 3> p = grid.toVoxel(std::array<float, 3>{position[0], position[1], position[2]});
            far[v] = !(std::fabs(p[0]) < kLimit && std::fabs(p[1]) < kLimit);
            snapped[v] =
                far[v] ? std::array<std::int64_t, 2>{0, 0} : std::array<std::int64_t, 2>{snap(p[0]), snap(p[1])};
            heights[v] = p[2];
        }
    });
    const std::int64_t grid_x = std::int64_t(grid.dims[0]) << kFractionBits;
    const std::int64_t grid_y = std::int64_t(grid.dims[1]) << kFractionBits;
    // Every triangle, the zero-area ones included: the closure check counts their edges, and
    // snapped they may cover a sliver of the plane that closes the count. In chunks side by
    // side, each writing the triangles it keeps from its own first one on; the gaps closed
    // after, so the list holds the triangles in the mesh's order (voxelize/memory_estimate.cpp
    // counts it once, at the mesh's triangle count).
    constexpr std::size_t kChunk = 16384;
    const std::size_t chunks = (view.triangle_count + kChunk - 1) / kChunk;
    std::vector<std::size_t> kept(chunks, 0);
    std::vector<char> refused(chunks, 0);
    triangles_.resize(view.triangle_count);
    tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t chunk) {
        const std::size_t begin = chunk * kChunk, end = std::min(view.triangle_count, begin + kChunk);
        // mesh.usable is ascending.
        auto next_usable = std::lower_bound(mesh.usable.begin(), mesh.usable.end(), std::uint32_t(begin));
        for (std::size_t t = begin; t < end; ++t) {
            const bool usable = next_usable != mesh.usable.end() && *next_usable == t;
            next_usable += usable ? 1 : 0;
            const std::uint32_t* corners = view.triangles + 3 * t;
            // The grid bounds only the usable triangles' vertices: a degenerate one may reach far
            // past it (a needle to 1e30). Past the snapping's range it is left out rather than
            // the mesh refused: it has no area (a usable triangle at that vertex is refused).
            if (far[corners[0]] || far[corners[1]] || far[corners[2]]) {
                if (usable) refused[chunk] = 1;
                continue;
            }
            Triangle tri{};
            for (int c = 0; c < 3; ++c) {
                const std::uint32_t v = corners[c];
                tri.x[c] = snapped[v][0];
                tri.y[c] = snapped[v][1];
                tri.z[c] = heights[v];
            }
            const Wide area = orient(tri.x[0], tri.y[0], tri.x[1], tri.y[1], tri.x[2], tri.y[2]);
            if (area == 0) continue;  // seen edge-on
            tri.sign = area < 0 ? 1 : -1;
            tri.x_lo = std::min({tri.x[0], tri.x[1], tri.x[2]});
            tri.x_hi = std::max({tri.x[0], tri.x[1], tri.x[2]});
            tri.y_lo = std::min({tri.y[0], tri.y[1], tri.y[2]});
            tri.y_hi = std::max({tri.y[0], tri.y[1], tri.y[2]});
            if (tri.x_hi < 0 || tri.y_hi < 0 || tri.x_lo > grid_x || tri.y_lo > grid_y) continue;  // misses every ray
            triangles_[begin + kept[chunk]++] = tri;
        }
    });
    for (const char refuse : refused)
        if (refuse) throw InvalidInput(kFarVertex);
    std::size_t size = 0;
    for (std::size_t chunk = 0; chunk < chunks; ++chunk) {
        if (size != chunk * kChunk)
            std::copy(triangles_.begin() + long(chunk * kChunk),
                      triangles_.begin() + long(chunk * kChunk + kept[chunk]), triangles_.begin() + long(size));
        size += kept[chunk];
    }
    triangles_.resize(size);
    // Each column of 8×8 rays lists the triangles whose xy box meets its rays' range.
    auto columnRange = [&](const Triangle& tri, std::array<std::int32_t, 4>& r) {
        const std::int64_t half = std::int64_t(1) << (kFractionBits - 1);
        auto first = [&](std::int64_t lo, std::int32_t n) {
            return std::int32_t(std::clamp<std::int64_t>(
                (lo - half + (std::int64_t(1) << kFractionBits) - 1) >> kFractionBits >> 3, 0, n - 1));
        };
        auto last = [&](std::int64_t hi, std::int32_t n) {
            return std::int32_t(std::clamp<std::int64_t>(((hi - half) >> kFractionBits) >> 3, 0, n - 1));
        };
        r = {first(tri.x_lo, columns_[0]), last(tri.x_hi, columns_[0]), first(tri.y_lo, columns_[1]),
             last(tri.y_hi, columns_[1])};
    };
    const std::size_t column_count = std::size_t(columns_[0]) * std::size_t(columns_[1]);
    column_start_.assign(column_count + 1, 0);
    std::array<std::int32_t, 4> r{};
    for (const Triangle& tri : triangles_) {
        columnRange(tri, r);
        for (std::int32_t cx = r[0]; cx <= r[1]; ++cx)
            for (std::int32_t cy = r[2]; cy <= r[3]; ++cy)
                ++column_start_[std::size_t(cx) * std::size_t(columns_[1]) + std::size_t(cy) + 1];
    }
    for (std::size_t c = 0; c < column_count; ++c) column_start_[c + 1] += column_start_[c];
    column_triangles_.resize(column_start_.back());
    column_rays_.resize(column_start_.back());
    std::vector<std::uint32_t> fill(column_start_.begin(), column_start_.end() - 1);
    for (std::uint32_t n = 0; n < triangles_.size(); ++n) {
        const Triangle& tri = triangles_[n];
        columnRange(tri, r);
        const std::int64_t rays_x[2] = {firstRay(tri.x_lo), lastRay(tri.x_hi)};
        const std::int64_t rays_y[2] = {firstRay(tri.y_lo), lastRay(tri.y_hi)};
        for (std::int32_t cx = r[0]; cx <= r[1]; ++cx)
            for (std::int32_t cy = r[2]; cy <= r[3]; ++cy) {
                const std::uint32_t slot = fill[std::size_t(cx) * std::size_t(columns_[1]) + std::size_t(cy)]++;
                column_triangles_[slot] = n;
                // The bucket's rays in the triangle's box, as offsets 0..7 (first > last: none).
                auto offset = [](std::int64_t ray, std::int32_t bucket) {
                    return std::uint8_t(std::clamp<std::int64_t>(ray - 8 * std::int64_t(bucket), -1, 8) + 1);
                };
                column_rays_[slot] = {offset(rays_x[0], cx), offset(rays_x[1], cx), offset(rays_y[0], cy),
                                      offset(rays_y[1], cy)};
            }
    }
}

int RayCrossings::at(int i, int j, int k) const {
    const double pz = k + 0.5;
    int crossings = 0;
    forEachCrossing(i, j, [&](double z, int sign) {
        if (z < pz) crossings += sign;
    });
    return crossings;
}

void RayCrossings::column(int i, int j, std::vector<Crossing>& out) const {
    out.clear();
    forEachCrossing(i, j, [&](double z, int sign) { out.push_back({z, sign}); });
}

template <typename Visit>
void RayCrossings::crossing(const Triangle& t, std::int64_t px, std::int64_t py, Visit visit) {
    const int s0 = side(t.x[1], t.y[1], t.x[2], t.y[2], px, py);
    const int s1 = side(t.x[2], t.y[2], t.x[0], t.y[0], px, py);
    const int s2 = side(t.x[0], t.y[0], t.x[1], t.y[1], px, py);
    if (s0 != s1 || s1 != s2) return;
    // The crossing's height from the barycentric weights (in double: the centre is at least
    // half a voxel from the surface, far beyond this rounding).
    const double w0 = double(orient(t.x[1], t.y[1], t.x[2], t.y[2], px, py));
    const double w1 = double(orient(t.x[2], t.y[2], t.x[0], t.y[0], px, py));
    const double w2 = double(orient(t.x[0], t.y[0], t.x[1], t.y[1], px, py));
    const double total = w0 + w1 + w2;
    visit((w0 * t.z[0] + w1 * t.z[1] + w2 * t.z[2]) / total, t.sign);
}

template <typename Visit>
void RayCrossings::forEachCrossing(int i, int j, Visit visit) const {
    const std::int64_t px = rayAt(i), py = rayAt(j);
    const std::size_t column = std::size_t(i >> 3) * std::size_t(columns_[1]) + std::size_t(j >> 3);
    // The ray's offsets in its bucket, plus 1, as column_rays_ keeps the rays of each triangle's
    // box: a triangle whose box misses the ray is skipped without reading it.
    const int ray_i = (i & 7) + 1, ray_j = (j & 7) + 1;
    for (std::uint32_t n = column_start_[column]; n < column_start_[column + 1]; ++n) {
        const std::array<std::uint8_t, 4>& rays = column_rays_[n];
        if (ray_i < rays[0] || ray_i > rays[1] || ray_j < rays[2] || ray_j > rays[3]) continue;
        crossing(triangles_[column_triangles_[n]], px, py, visit);
    }
}

void RayCrossings::columns(int i0, int j0, int ni, int nj, std::vector<Crossing>* out) const {
    for (int n = 0; n < ni * nj; ++n) out[n].clear();
    // Each bucket of 8×8 rays the block meets, once: its triangles against its own rays of the
    // block that lie in the triangle's xy box (a triangle listed in several buckets is seen
    // once per ray). The rays in the box come from the bucket's compact list, so a triangle
    // none of whose rays is wanted (most, in the buckets a block touches with one row) is
    // skipped without reading it.
    for (int bx = i0 >> 3; bx <= (i0 + ni - 1) >> 3; ++bx)
        for (int by = j0 >> 3; by <= (j0 + nj - 1) >> 3; ++by) {
            const int i_lo = std::max(i0, 8 * bx), i_hi = std::min(i0 + ni - 1, 8 * bx + 7);
            const int j_lo = std::max(j0, 8 * by), j_hi = std::min(j0 + nj - 1, 8 * by + 7);
            const std::size_t column = std::size_t(bx) * std::size_t(columns_[1]) + std::size_t(by);
            for (std::uint32_t n = column_start_[column]; n < column_start_[column + 1]; ++n) {
                const std::array<std::uint8_t, 4>& rays = column_rays_[n];
                const int first_i = std::max(i_lo, 8 * bx + rays[0] - 1), last_i = std::min(i_hi, 8 * bx + rays[1] - 1);
                const int first_j = std::max(j_lo, 8 * by + rays[2] - 1), last_j = std::min(j_hi, 8 * by + rays[3] - 1);
                if (first_i > last_i || first_j > last_j) continue;
                const Triangle& t = triangles_[column_triangles_[n]];
                for (int i = first_i; i <= last_i; ++i)
                    for (int j = first_j; j <= last_j; ++j) {
                        std::vector<Crossing>& list = out[(i - i0) * nj + (j - j0)];
                        crossing(t, rayAt(i), rayAt(j), [&](double z, int sign) { list.push_back({z, sign}); });
                    }
            }
        }
}

}  // namespace hyvox::solid
