// SPDX-License-Identifier: GPL-3.0-or-later
#include "sdf/band_queries.h"

#include <algorithm>
#include <cmath>

#include "core/triangle_normal.h"
#include "sdf/band_distances.h"

namespace hyvox::sdf {
namespace {

constexpr int kSide = BlockLayout::kSide;

// Cells around the block on each side: a small triangle within the band of a block's voxel
// centre has its centroid less than band + 1/2 voxels outside the block.
int marginFor(double band) { return int(std::ceil(band)) + 1; }

// Bits first..last (each clamped to 0..63) of a word.
std::uint64_t bitsBetween(int first, int last) {
    first = std::max(first, 0);
    last = std::min(last, 63);
    if (first > last) return 0;
    const std::uint64_t upto = last == 63 ? ~std::uint64_t(0) : (std::uint64_t(1) << (last + 1)) - 1;
    return upto & ~((std::uint64_t(1) << first) - 1);
}

void grow(std::array<double, 6>& box, const std::array<Vec3, 3>& corners) {
    for (const Vec3& corner : corners)
        for (int a = 0; a < 3; ++a) {
            box[std::size_t(a)] = std::min(box[std::size_t(a)], corner[a]);
            box[std::size_t(a + 3)] = std::max(box[std::size_t(a + 3)], corner[a]);
        }
}
constexpr std::array<double, 6> kEmptyBox{HUGE_VAL, HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL};

}  // namespace

bool BlockQueries::fits(double band) { return kSide + 2 * marginFor(band) <= 64; }

std::size_t BlockQueries::bytesAtMost(double band, std::size_t triangles) {
    if (!fits(band)) return 0;
    const std::size_t side = std::size_t(kSide + 2 * marginFor(band));
    // For each triangle: its corners, place and place among the taken, a whole pack (at most:
    // an octant of one triangle), a cell and an octant (at most), and its set-up while its cell
    // is packed (at most: a cell of all). Beside them the cells' slots, rows and their boxes,
    // and the reach.
    const std::size_t per_triangle = sizeof(std::array<Vec3, 3>) + 2 * sizeof(std::uint32_t) +
        sizeof(DistanceTriangles4) + 2 * sizeof(Group) + sizeof(DistanceTriangle);
    return triangles * per_triangle + side * side * side * sizeof(std::uint32_t) +
        side * side * (sizeof(std::uint64_t) + 4 * sizeof(double)) + std::size_t(kSide * kSide) * sizeof(std::uint64_t);
}

void BlockQueries::begin(const std::array<std::int32_t, 3>& origin, double band) {
    origin_ = origin;
    band_ = band;
    margin_ = marginFor(band);
    side_ = kSide + 2 * margin_;
    corners_.clear();
    places_.clear();
    placed_ = 0;
    overhang_ = 0;
    taken_.clear();
    const std::size_t side = std::size_t(side_);
    if (slot_of_key_.size() < side * side * side) slot_of_key_.resize(side * side * side);
    rows_.assign(side * side, 0);
    row_boxes_.assign(side * side, {HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL});
    cells_.clear();
}

void BlockQueries::add(const std::array<Vec3, 3>& corners) {
    corners_.push_back(corners);
    places_.push_back(kNotPlaced);
    for (int a = 0; a < 3; ++a) {
        const double lo = std::min({corners[0][a], corners[1][a], corners[2][a]});
        const double hi = std::max({corners[0][a], corners[1][a], corners[2][a]});
        if (!(hi - lo <= 1.0)) return;
    }
    const Vec3 centroid = centroidOf(corners);
    int at[3], octant = 0;
    double overhang = 0;
    for (int a = 0; a < 3; ++a) {
        const double from_origin = centroid[a] - origin_[a], cell = std::floor(from_origin);
        if (!(cell + margin_ >= 0 && cell + margin_ < side_)) return;
        at[a] = int(cell) + margin_;
        octant |= int(from_origin - cell >= 0.5) << a;  // which half of the cell along axis a
        const double cell_lo = origin_[a] + cell;
        overhang = std::max({overhang, cell_lo - std::min({corners[0][a], corners[1][a], corners[2][a]}),
                             std::max({corners[0][a], corners[1][a], corners[2][a]}) - (cell_lo + 1)});
    }
    overhang_ = std::max(overhang_, overhang);
    std::uint64_t& row = rows_[std::size_t(at[0] * side_ + at[1])];
    const std::uint32_t key = std::uint32_t((at[0] * side_ + at[1]) * side_ + at[2]);
    if (!((row >> at[2]) & 1)) {
        row |= std::uint64_t(1) << at[2];
        slot_of_key_[key] = std::uint32_t(cells_.size());
        cells_.push_back({0, 0, kEmptyBox, {}});
    }
    places_.back() = (key << 3) | std::uint32_t(octant);
    ++placed_;
}

bool BlockQueries::take(std::size_t n) {
    const std::uint32_t place = places_[n];
    if (place == kNotPlaced) return false;
    const std::uint32_t key = place >> 3;
    Group& cell = cells_[slot_of_key_[key]];
    grow(cell.box, corners_[n]);
    std::array<double, 4>& row_box = row_boxes_[key / std::uint32_t(side_)];
    for (int a = 0; a < 2; ++a) {
        row_box[std::size_t(a)] = std::min(row_box[std::size_t(a)], cell.box[std::size_t(a)]);
        row_box[std::size_t(a + 2)] = std::max(row_box[std::size_t(a + 2)], cell.box[std::size_t(a + 3)]);
    }
    taken_.push_back(std::uint32_t(n));
    return true;
}

Slab Slab::around(const DistanceTriangle* first, std::size_t count, const Vec3& centre) {
    Slab slab;
    slab.centre = centre;
    // The unit normals summed: a patch of a surface keeps its plane; triangles facing every way
    // leave it uncertain, and the box is then only as thin as they allow (any frame bounds them).
    Vec3 sum{0, 0, 0};
    for (std::size_t n = 0; n < count; ++n)
        for (std::size_t a = 0; a < 3; ++a) sum[a] += first[n].h_axis[a];
    const double length2 = dot(sum, sum);
    if (length2 > 1e-12 && std::isfinite(length2)) {
        const Vec3 h = unit(sum);
        const Vec3 other = std::fabs(h[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
        const Vec3 u = unit(triangle_normal_detail::cross(h, other));
        slab.axis = {u, unit(triangle_normal_detail::cross(h, u)), h};
    } else {
        slab.axis = {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
    }
    slab.lo = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
    slab.hi = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (std::size_t n = 0; n < count; ++n)
        for (const Vec3& corner : first[n].corner) {
            const Vec3 q{corner[0] - centre[0], corner[1] - centre[1], corner[2] - centre[2]};
            for (std::size_t a = 0; a < 3; ++a) {
                const double along = dot(q, slab.axis[a]);
                slab.lo[a] = std::min(slab.lo[a], along);
                slab.hi[a] = std::max(slab.hi[a], along);
            }
        }
    return slab;
}

void BlockQueries::sortIntoCells() {
    // A counting sort of the taken triangles by cell, then octant.
    auto slotOf = [&](std::uint32_t n) { return 8 * std::size_t(slot_of_key_[places_[n] >> 3]) + (places_[n] & 7); };
    std::vector<std::uint32_t> start(8 * cells_.size() + 1, 0);
    for (const std::uint32_t n : taken_) ++start[slotOf(n) + 1];
    for (std::size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
    std::vector<std::uint32_t> order(taken_.size());
    {
        std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
        for (const std::uint32_t n : taken_) order[fill[slotOf(n)]++] = n;
    }
    packs_.clear();
    packs_.reserve(order.size() / 2 + cells_.size());
    octants_.clear();
    std::vector<DistanceTriangle> triangles;  // one cell's, octant by octant
    auto centreOf = [](const std::array<double, 6>& box) {
        return Vec3{0.5 * (box[0] + box[3]), 0.5 * (box[1] + box[4]), 0.5 * (box[2] + box[5])};
    };
    for (std::size_t c = 0; c < cells_.size(); ++c) {
        Group& cell = cells_[c];
        triangles.clear();
        for (std::uint32_t i = start[8 * c]; i < start[8 * c + 8]; ++i) triangles.emplace_back(corners_[order[i]]);
        cell.slab = Slab::around(triangles.data(), triangles.size(), centreOf(cell.box));
        cell.first = std::uint32_t(octants_.size());
        for (std::size_t o = 8 * c; o < 8 * c + 8; ++o) {
            if (start[o] == start[o + 1]) continue;
            Group group{std::uint32_t(packs_.size()), 0, kEmptyBox, {}};
            for (std::uint32_t i = start[o]; i < start[o + 1]; ++i) grow(group.box, corners_[order[i]]);
            const DistanceTriangle* first = triangles.data() + (start[o] - start[8 * c]);
            const std::size_t count = start[o + 1] - start[o];
            group.slab = Slab::around(first, count, centreOf(group.box));
            for (std::size_t at = 0; at < count; at += DistanceTriangles4::kLanes)
                packs_.emplace_back(first + at, int(std::min<std::size_t>(DistanceTriangles4::kLanes, count - at)));
            group.end = std::uint32_t(packs_.size());
            octants_.push_back(group);
        }
        cell.end = std::uint32_t(octants_.size());
    }
}

void BlockQueries::markReached(const std::array<std::int32_t, 2>& limit) {
    // The voxels whose centres lie within the band of a cell's box (a lower bound of its
    // triangles' distances), each box's rows marked at once.
    reach_.assign(std::size_t(kSide * kSide), 0);
    const double band2 = band_ * band_;
    const int i_end = std::min(kSide, limit[0]), j_end = std::min(kSide, limit[1]);
    // Voxels [first, last] along `axis` whose centres lie within `reach` of [lo, hi], clipped.
    auto span = [&](double lo, double hi, double reach, int axis, int end, int& first, int& last) {
        first = int(std::max(std::ceil(lo - origin_[axis] - reach - 0.5), 0.0));
        last = int(std::min(std::floor(hi - origin_[axis] + reach - 0.5), double(end - 1)));
        return first <= last;
    };
    for (const Group& cell : cells_) {
        const std::array<double, 6>& box = cell.box;
        int i_first, i_last, j_first, j_last;
        if (!span(box[0], box[3], band_, 0, i_end, i_first, i_last) ||
            !span(box[1], box[4], band_, 1, j_end, j_first, j_last))
            continue;
        for (int i = i_first; i <= i_last; ++i) {
            const double gx = gap(origin_[0] + i + 0.5, box[0], box[3]);
            for (int j = j_first; j <= j_last; ++j) {
                const double gy = gap(origin_[1] + j + 0.5, box[1], box[4]);
                const double left = band2 - gx * gx - gy * gy;
                int k_first, k_last;
                if (left <= 0 || !span(box[2], box[5], std::sqrt(left), 2, kSide, k_first, k_last)) continue;
                reach_[std::size_t(i * kSide + j)] |= bitsBetween(k_first, k_last);
            }
        }
    }
}

HYVOX_AVX2_CLONES_GCC
std::uint64_t lowerVoxels(BlockQueries& queries, double* d2, std::uint64_t& evaluations) {
    const int m = queries.margin_, side = queries.side_;
    const double overhang = queries.overhang_;
    // The squared distance from (x, y, z) to the farther of a group's two boxes: a lower bound
    // of its triangles', less a rounding's slack (a triangle it rounds away could still lower
    // a distance by a rounding). The turned box is measured only when the axis-aligned one
    // comes nearer than `best`: past it, the group is out either way.
    auto boundOf = [](const BlockQueries::Group& group, double x, double y, double z, double best) {
        const std::array<double, 6>& box = group.box;
        const double dx = gap(x, box[0], box[3]), dy = gap(y, box[1], box[4]), dz = gap(z, box[2], box[5]);
        const double aligned = (dx * dx + dy * dy + dz * dz) * (1 - 1e-12);
        return aligned >= best ? aligned : std::max(aligned, group.slab.distance2(x, y, z) * (1 - 1e-12));
    };
    std::vector<BlockQueries::Near>& near = queries.near_;
    const double band2 = queries.band_ * queries.band_;
    std::uint64_t touched = 0;
    const DistanceTriangles4* seed = nullptr;  // the last triangles that lowered a distance
    for (int i = 0; i < kSide; ++i)
        for (int j = 0; j < kSide; ++j) {
            for (std::uint64_t voxels = queries.reach_[std::size_t(i * kSide + j)]; voxels; voxels &= voxels - 1) {
                const int k = __builtin_ctzll(voxels);
                double& best = d2[blockOffset(i, j, k)];
                const double x = queries.origin_[0] + i + 0.5, y = queries.origin_[1] + j + 0.5,
                             z = queries.origin_[2] + k + 0.5;
                if (seed) {
                    best = seed->minDistance2(x, y, z, best);
                    evaluations += DistanceTriangles4::kLanes;
                }
                // Cells whose box, within [c - overhang, c + 1 + overhang], may come within
                // sqrt(best) of the voxel (a rounding's width more).
                const double r = std::sqrt(best) + 1e-9 + overhang;
                const double xr = i + 0.5, yr = j + 0.5, zr = k + 0.5;
                const int x_lo = std::max(0, int(std::floor(xr - r - 1)) + m);
                const int x_hi = std::min(side - 1, int(std::floor(xr + r)) + m);
                const int y_lo = std::max(0, int(std::floor(yr - r - 1)) + m);
                const int y_hi = std::min(side - 1, int(std::floor(yr + r)) + m);
                const std::uint64_t z_bits = bitsBetween(int(std::floor(zr - r - 1)) + m, int(std::floor(zr + r)) + m);
                for (int cx = x_lo; cx <= x_hi; ++cx) {
                    for (int cy = y_lo; cy <= y_hi; ++cy) {
                        const std::array<double, 4>& row_box = queries.row_boxes_[std::size_t(cx * side + cy)];
                        const double gx_row = gap(x, row_box[0], row_box[2]), gy_row = gap(y, row_box[1], row_box[3]);
                        if (gx_row * gx_row + gy_row * gy_row >= best) continue;
                        for (std::uint64_t bits = queries.rows_[std::size_t(cx * side + cy)] & z_bits; bits;
                             bits &= bits - 1) {
                            const std::uint32_t slot =
                                queries.slot_of_key_[std::size_t((cx * side + cy) * side + __builtin_ctzll(bits))];
                            const double lower_bound = boundOf(queries.cells_[slot], x, y, z, best);
                            if (lower_bound < best) near.push_back({lower_bound, slot});
                        }
                    }
                }
                // Nearest box first: the first triangles measured then bound the rest best.
                std::sort(near.begin(), near.end(), [](const BlockQueries::Near& a, const BlockQueries::Near& b) {
                    return a.lower_bound < b.lower_bound;
                });
                for (const BlockQueries::Near& candidate : near) {
                    if (candidate.lower_bound >= best) break;
                    const BlockQueries::Group& cell = queries.cells_[candidate.slot];
                    for (std::uint32_t o = cell.first; o < cell.end; ++o) {
                        const BlockQueries::Group& octant = queries.octants_[o];
                        if (boundOf(octant, x, y, z, best) >= best) continue;
                        for (std::uint32_t p = octant.first; p < octant.end; ++p) {
                            const double before = best;
                            best = queries.packs_[p].minDistance2(x, y, z, best);
                            if (best < before) seed = &queries.packs_[p];
                        }
                        evaluations += DistanceTriangles4::kLanes * (octant.end - octant.first);
                    }
                }
                near.clear();
                if (best < band2) touched |= std::uint64_t(1) << brickBit(i >> 3, j >> 3, k >> 3);
            }
        }
    return touched;
}

// After lowerVoxels: a function built as clones is declared so before its first use (clang).
std::uint64_t BlockQueries::lower(double* d2, std::uint64_t& evaluations) {
    sortIntoCells();
    return lowerVoxels(*this, d2, evaluations);
}

}  // namespace hyvox::sdf
