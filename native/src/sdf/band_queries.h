// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A block's distances to its small triangles by nearest-triangle queries, for blocks crowded
// with triangles smaller than a voxel (several for each voxel of the band on a fine scan).
// Sweeping such a triangle costs the ~150 voxels within the band of it, nearly all of which a
// nearer triangle claims; a query measures only the triangles that may be nearer
// (docs/why/sdf.md).
//
// The small triangles (each no wider than a voxel along every axis) are sorted into the unit
// cells of their centroids, each cell with the box of its triangles; a triangle's box then lies
// within its cell grown on every side by the block's overhang (how far its triangles reach past
// their cells: less than a voxel), which bounds the cells a voxel scans. Within a cell they are grouped by the
// octant of the cell their centroids lie in, each octant with its box, and packed four to a
// vector (DistanceTriangles4). The voxels visited are those within the band of a cell's box.
// For each, its bound starts as the least of its distance so far and its distance to the
// triangles that last lowered one (a neighbour's nearest); the cells whose bounds come nearer
// than the bound are measured nearest first, an octant only when its bound still does, and
// the bound shrinks as they are. The result is the least distance over the same triangles as
// a sweep's (to a rounding error).
//
// A cell's or an octant's bound is the farther of two boxes around its triangles: the
// axis-aligned one, and one turned to their summed normal (a Slab). On a patch of a smooth
// surface the turned box is thin where the axis-aligned one is as thick as it is wide, so a
// voxel above a crowded surface measures the triangles near the point below it, not all within
// its distance's reach. A cell's turned box is measured only when its axis-aligned one comes
// near enough: most of the cells a voxel scans fail that first, cheaper check
// (docs/why/sdf.md).
#include <array>
#include <cstdint>
#include <vector>

#include "hyvox/grid.h"
#include "sdf/point_triangle.h"

namespace hyvox::sdf {

// A box around triangles in a frame of their own: axis (u, v, h), h along their summed normal,
// and along each axis the span [lo, hi] of their corners, measured from `centre`.
struct Slab {
    Vec3 centre;
    std::array<Vec3, 3> axis;
    std::array<double, 3> lo, hi;

    // Around `count` triangles from `first`, measured from `centre`.
    static Slab around(const DistanceTriangle* first, std::size_t count, const Vec3& centre);
    // The squared distance from (x, y, z) to the box (exact up to rounding: the axes are
    // orthonormal up to rounding).
    double distance2(double x, double y, double z) const {
        const Vec3 q{x - centre[0], y - centre[1], z - centre[2]};
        double sum = 0;
        for (std::size_t a = 0; a < 3; ++a) {
            const double g = gap(dot(q, axis[a]), lo[a], hi[a]);
            sum += g * g;
        }
        return sum;
    }
};

// The queries' working memory, reused from block to block by one thread.
class BlockQueries {
public:
    // Whether `band` leaves the cells around a block narrow enough (a row of them one word).
    static bool fits(double band);
    // What one thread's queries hold at most for a block of `triangles` triangles (0 when the
    // band does not fit).
    static std::size_t bytesAtMost(double band, std::size_t triangles);

    // Starts a block: `origin` its first voxel, `band` the band's half-width (fits(band)).
    void begin(const std::array<std::int32_t, 3>& origin, double band);
    // Keeps the block's next triangle, of voxel-space `corners`, and places it in its cell
    // when the queries can take it: no wider than a voxel along any axis, its centroid within
    // the cells around the block.
    void add(const std::array<Vec3, 3>& corners);
    std::size_t triangles() const { return corners_.size(); }
    const std::array<Vec3, 3>& corners(std::size_t n) const { return corners_[n]; }
    // The triangles placed in cells, and the cells they occupy.
    std::size_t placedTriangles() const { return placed_; }
    std::size_t occupiedCells() const { return cells_.size(); }
    // Takes triangle n into the queries; false when it was not placed (it is to be swept).
    bool take(std::size_t n);
    std::size_t taken() const { return taken_.size(); }

    // Marks the voxels (within the grid's first `limit` voxels along x and y, where it ends)
    // that may lie within the band of an added triangle: those `lower` visits. Call once all
    // are added.
    void markReached(const std::array<std::int32_t, 2>& limit);

    // Lowers `d2` (the block's squared distances, blockOffset order, each already at most
    // band²) to the least over the added triangles at the voxels markReached marked.
    // Returns the bricks where a distance fell below band²; adds the distances computed to
    // `evaluations` (four for each group of up to four triangles measured at once).
    std::uint64_t lower(double* d2, std::uint64_t& evaluations);

private:
    // Triangles with boxes around them (box: lo xyz, hi xyz; voxel space): an octant, its
    // packs [first, end) of `packs_`, or a unit cell, its octants [first, end) of `octants_`
    // (a cell's triangles split by the octant of the cell their centroids lie in: the octants'
    // boxes hold fewer triangles' worth of empty space).
    struct Group {
        std::uint32_t first, end;
        std::array<double, 6> box;
        Slab slab;
    };
    std::array<std::int32_t, 3> origin_{0, 0, 0};
    double band_ = 0;
    int margin_ = 0, side_ = 0;
    static constexpr std::uint32_t kNotPlaced = ~std::uint32_t(0);
    std::vector<std::array<Vec3, 3>> corners_;  // the block's triangles
    std::vector<std::uint32_t> places_;         // each one's (cell key << 3) | octant, or kNotPlaced
    std::size_t placed_ = 0;
    double overhang_ = 0;               // how far past its cell a placed triangle reaches, at most (below 1)
    std::vector<std::uint32_t> taken_;  // the triangles taken
    // side³ entries, cell (x, y, z) at (x * side + y) * side + z, the cells counted from
    // origin - margin along each axis; valid where the cell is occupied.
    std::vector<std::uint32_t> slot_of_key_;
    std::vector<std::uint64_t> rows_;               // side² words: bit z set where cell (x, y, z) is occupied
    std::vector<std::array<double, 4>> row_boxes_;  // side² boxes (lo xy, hi xy) of each row's cells
    std::vector<std::uint64_t> reach_;              // 32² words: bit z of voxel row (x, y) set where lower visits
    std::vector<Group> cells_;
    std::vector<Group> octants_;
    std::vector<DistanceTriangles4> packs_;
    // A cell whose box comes nearer a voxel than its bound, by that box's squared distance.
    struct Near {
        double lower_bound;
        std::uint32_t slot;
    };
    std::vector<Near> near_;

    void sortIntoCells();
    // lower's voxels, a free function: compilers build target clones of those (point_triangle.h).
    friend std::uint64_t lowerVoxels(BlockQueries& queries, double* d2, std::uint64_t& evaluations);
};

}  // namespace hyvox::sdf
