// SPDX-License-Identifier: GPL-3.0-or-later
#include "memory_estimate.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>

#include "core/backends.h"
#include "hyvox/bit_grid.h"
#include "hyvox/errors.h"
#include "hyvox/sparse_grid.h"
#include "hyvox/zero_page_allocator.h"
#include "solid/fast_winding.h"
#include "solid/fill_inside.h"
#include "vdb/vdb_direct_writer.h"

namespace hyvox::memory {
namespace {

// A leaf of a SparseGrid (brick index and 64 bytes of bits), and what a vector of them holds at
// most while it grows by doubling (the old buffer and the new one twice its size): the bound
// the passes whose lists are estimated loosely take (the surface's list has its own model,
// surfaceListBytes).
constexpr double kLeaf = double(SparseGrid::kLeafBytes);
constexpr double kGrowing = 3.0;
// glibc maps every block of 32 MiB or more on its own and unmaps it when freed; a freed smaller
// block can stay in the heap, resident (its mmap threshold rises up to that size as blocks are
// freed).
constexpr double kHeapKeptBelow = 32.0 * (1 << 20);
// A margin for what the surface pass holds beyond its tile and its list of leaves (the tiles'
// triangle lists, the allocator's partly used pages), which the model leaves out
// (docs/why/memory-estimate.md).
constexpr double kSurfaceMargin = 1.02;
// The solid pass (solid/): the edge check's sort (every edge once with its vertices); the ray
// columns (a snapped triangle, and per 8×8 column its box reaches an entry and its rays'
// offsets, beside a snapped position per vertex); the fast winding numbers' tree over the
// triangles cut into pieces (the triangles and longest edges read, the pieces twice, a node
// per two pieces at most: its build record beside what the traversal keeps); the inside
// found, per leaf of surface (the threads' leaves and their gather; an open mesh's winding
// numbers near its open edges take more: docs/why/memory-estimate.md).
constexpr double kEdgesPerTriangle = 48;
constexpr double kRayTriangle = 112, kRayEntry = 8, kRayVertex = 25;
constexpr double kWholeTriangle = 80, kPiece = 72, kNodeBuild = double(solid::FastWinding::kBuildNodeBytes) + 48 + 104,
                 kNodeKept = 48 + 104 + 4;
constexpr double kInsidePerLeaf = kGrowing * kLeaf + 24, kOpenInsidePerLeaf = 600;
// The attribute evaluator's per-triangle data and a leaf's record of its values (with what
// gathering the values beside them holds); in solid mode the inside voxels of a surface brick
// that take values beyond its surface voxels (the surface cuts a brick about in half), a leaf
// brick's record while they are valued (attributes/inside_values.cpp: its masks, neighbours
// and offsets), and a tile region's (its box, value, layer and sums: 112 bytes and 8 a
// channel). Regions of one brick lie within a 128³ node of the surface: at most about 8 per
// leaf of surface. The measured counts these rest on: docs/why/memory-estimate.md.
constexpr double kAttributesPerTriangle = 64, kAttributeLeaf = 96, kInsideValuedPerLeaf = 256;
constexpr double kInsideValuingLeaf = 400, kRegion = 112, kRegionChannel = 8, kRegionsPerLeaf = 8;
// fast_winding.cpp's cut: pieces of at most 4 voxels, at most 3 a triangle plus 100000.
constexpr double kPieceVoxels = 4, kPieceBudget = 3, kPieceFloor = 100000;

struct Measures {
    double crossed_area = 0;   // each triangle's area times its normal's L1 norm: a plane of
                               // area A crosses A·|n|₁/s² cells of side s (voxel units²)
    double signed_volume = 0;  // voxel units³ (the divergence theorem over the triangles)
    double ray_entries = 0;    // the 8×8 ray columns each triangle's xy box reaches
    double pieces = 0;         // the fast winding numbers' pieces (cut to kPieceVoxels)
};

// What depends on the grid only through its scale and origin comes from validate()'s sums
// (TriangleSums): a surface-only run reads no triangle here. A region's run (plan.region)
// holds the surface of its box only: the triangles whose bounding box, one voxel wider, misses
// the box add no surface, so its crossed area is summed over the triangles again; the inside
// pass (`inside`: solid mode, the sdf's sign) needs the ray columns and winding pieces, which
// depend on where the triangles fall in the grid. The solid pass's trees and rays take every
// triangle, so the volume stays the whole mesh's.
Measures measure(const ValidatedMesh& mesh, const GridSpec& grid, const tiling::TilePlan& plan, bool inside) {
    const double s = grid.voxel_size;
    Measures whole;
    whole.crossed_area = mesh.sums.crossed_area / (s * s);
    double apex_shift = 0;  // (origin - bounds.min) · normal
    for (int a = 0; a < 3; ++a) apex_shift += (grid.origin[a] - mesh.bounds.min[a]) * mesh.sums.normal[a];
    whole.signed_volume = (mesh.sums.volume - apex_shift) / (s * s * s);
    if (!plan.region && !inside) return whole;
    Measures passed = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, mesh.usable.size(), 1 << 14), Measures{},
        [&](const tbb::blocked_range<std::size_t>& range, Measures m) {
            for (std::size_t n = range.begin(); n != range.end(); ++n) {
                const std::uint32_t t = mesh.usable[n];
                const std::array<std::array<double, 3>, 3> p{
                    grid.toVoxel(mesh.vertex(t, 0)), grid.toVoxel(mesh.vertex(t, 1)), grid.toVoxel(mesh.vertex(t, 2))};
                if (plan.region) {
                    bool in_box = true;
                    for (int a = 0; a < 3; ++a)
                        in_box = in_box && std::max({p[0][a], p[1][a], p[2][a]}) >= plan.lo[a] - 1 &&
                            std::min({p[0][a], p[1][a], p[2][a]}) <= plan.hi[a];
                    if (in_box) {
                        const double e0[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
                        const double e1[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
                        m.crossed_area += 0.5 *
                            (std::fabs(e0[1] * e1[2] - e0[2] * e1[1]) + std::fabs(e0[2] * e1[0] - e0[0] * e1[2]) +
                             std::fabs(e0[0] * e1[1] - e0[1] * e1[0]));
                    }
                }
                if (!inside) continue;
                double span[2], longest2 = 0;
                for (int a = 0; a < 2; ++a)
                    span[a] = std::floor(std::max({p[0][a], p[1][a], p[2][a]}) / 8) -
                        std::floor(std::min({p[0][a], p[1][a], p[2][a]}) / 8) + 1;
                m.ray_entries += span[0] * span[1];
                for (int e = 0; e < 3; ++e) {
                    const auto& u = p[std::size_t(e)];
                    const auto& v = p[std::size_t((e + 1) % 3)];
                    longest2 = std::max(
                        longest2,
                        (u[0] - v[0]) * (u[0] - v[0]) + (u[1] - v[1]) * (u[1] - v[1]) + (u[2] - v[2]) * (u[2] - v[2]));
                }
                // Halving the longest edge until it is short: pieces come in powers of two,
                // about (l / kPieceVoxels)² of them, up to twice that.
                m.pieces += std::max(1.0, 2.0 * longest2 / (kPieceVoxels * kPieceVoxels));
            }
            return m;
        },
        [](Measures a, const Measures& b) {
            a.crossed_area += b.crossed_area;
            a.ray_entries += b.ray_entries;
            a.pieces += b.pieces;
            return a;
        });
    if (!plan.region) passed.crossed_area = whole.crossed_area;
    passed.signed_volume = whole.signed_volume;
    return passed;
}

// The fast winding numbers' build at its fullest (fast_winding.cpp): the triangles read, the
// pieces (grown past their reservation when there are more than triangles), the nodes.
double windingBytes(double triangles, double pieces) {
    const double nodes = pieces / 2;
    // The pieces' list is reserved for the triangles; past that it doubles, and holds its old
    // buffer and the new one (1.5 times the new) while it moves.
    const double capacity =
        pieces > triangles ? triangles * std::exp2(std::ceil(std::log2(pieces / triangles))) : pieces;
    const double cut = kPiece * (pieces > triangles ? 1.5 * capacity : pieces);
    return kWholeTriangle * triangles +
        std::max({cut, kPiece * pieces + kNodeBuild * nodes, 2 * kPiece * pieces + kNodeKept * nodes});
}

// The most the surface's leaves hold resident while SparseGrid::addTile appends them, one
// push_back at a time from empty (capacities 1, 2, 4, ...), and once SparseGrid::finish has
// shrunk the list to its size (a copy beside the old one; the tile is freed by then). At each
// doubling the old buffer and its copy are resident, beside the old buffers the heap kept; the
// new buffer's untouched pages are not. `leaves` is taken 10% over the estimate, which is close
// for conservative surfaces (docs/why/memory-estimate.md): a count just past a power of two
// doubles once more.
struct ListBytes {
    double growing = 0, shrinking = 0;
};
ListBytes surfaceListBytes(double leaves) {
    const double count = 1.1 * leaves;
    double kept = 0, growing = 0;
    for (double capacity = 1; capacity < count; capacity *= 2) {
        growing = std::max(growing, 2 * kLeaf * capacity + kept);
        if (kLeaf * capacity < kHeapKeptBelow) kept += kLeaf * capacity;
    }
    growing = std::max(growing, kLeaf * count + kept);
    return {growing, 2 * kLeaf * count + kept};
}

// The surface's leaves counted, not modelled, for grids of more than kCountFromBricks bricks
// whose count takes at most kCountBitsMax bytes of bits (to 4096³): the mesh voxelized
// (conservative, cpu) on the grid of the bricks themselves, voxels 8 wide, whose set voxels
// are the bricks that some triangle meets, which are the leaves of the conservative surface.
// The area model (A·|n|₁/64) counts a brick once for every sheet of surface through it, so
// it overcounts where surfaces crowd within a brick; smaller grids keep it, their passes being
// small and their runs short. The count costs what a surface at an eighth of the resolution
// does, a small part of a large run (docs/why/memory-estimate.md).
constexpr double kCountFromBricks = double(1 << 18), kCountBitsMax = double(32 << 20);
std::optional<double> countedLeaves(const ValidatedMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options) {
    const BrickLayout bricks = grid.bricks();
    if (double(bricks.total()) <= kCountFromBricks || double(bricks.total()) / 8.0 > kCountBitsMax) return std::nullopt;
    GridSpec brick_grid;
    brick_grid.origin = grid.origin;
    brick_grid.voxel_size = grid.voxel_size * 8;
    brick_grid.dims = bricks.counts;
    VoxelizeOptions conservative;
    conservative.mode = Mode::Conservative;
    conservative.threads = options.threads;
    const Tile tile{{0, 0, 0}, brick_grid.dims};
    TileOutput out{BitGrid(brick_grid.dims), {}, {}, 0, {}};
    Stats stats;
    runCpuBackend({mesh, mesh, brick_grid, tile, conservative, nullptr}, out, stats);
    return double(out.bits.count());
}

std::string mib(double bytes) { return std::to_string(std::uint64_t(std::ceil(bytes / double(1 << 20)))) + " MiB"; }

}  // namespace

double Estimate::peak() const { return std::max({surface, solid, attributes, write, sdf}); }

const char* Estimate::largest() const {
    const double p = peak();
    if (p == surface) return "the surface pass";
    if (p == solid) return "the solid pass";
    if (p == attributes) return "the attribute values";
    if (p == sdf) return "the sdf (its band's leaves and distances)";
    return "the .vdb file";
}

Estimate estimate(const ValidatedMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options,
                  const tiling::TilePlan& plan, int attribute_channels, const solid::EdgeClosure* closure) {
    Estimate e;
    tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
    const bool inside = (options.mode == Mode::Solid || options.attributes.sdf) && closure;
    const Measures m = arena.execute([&] { return measure(mesh, grid, plan, inside); });
    const double triangles = double(mesh.usable.size());
    const double bricks = double(plan.region ? BrickLayout::over(plan.boxDims()).total() : grid.bricks().total());
    // A surface of area A crosses A·|n|₁/64 leaves (bricks of 8³) and sets about A·|n|₁ voxels
    // (conservative: every voxel it meets), every triangle at least one.
    const std::optional<double> counted = plan.region ? std::nullopt : countedLeaves(mesh, grid, options);
    e.surface_leaves =
        counted ? *counted : std::min(std::max(m.crossed_area / 64.0, triangles > 0 ? 1.0 : 0.0), bricks);
    e.surface_voxels = std::min(std::max(m.crossed_area, triangles), 512.0 * e.surface_leaves);
    const double L = e.surface_leaves, V = e.surface_voxels;
    const double channels = attribute_channels;

    // The surface pass: one tile's bits (whole pages of them: a surface crosses nearly every
    // one), the triangles binned to the tiles, the leaves growing, and with attributes each
    // leaf's values (in one block a tile) and the evaluator.
    const double bins = plan.whole() ? 0.0 : 4.0 * triangles * 1.5;
    const ListBytes list = surfaceListBytes(L);
    e.surface =
        kSurfaceMargin * std::max(double(zeroPagesMapped(plan.tileBytes())) + bins + list.growing, list.shrinking);
    if (channels > 0) e.surface += triangles * kAttributesPerTriangle + L * kAttributeLeaf + V * channels * 4.0;

    // The attribute values of the surface, gathered once the surface pass is done (the leaves'
    // values and the result's array side by side).
    const double values = V * channels * 4.0;
    if (channels > 0) e.attributes = kLeaf * L + 2.0 * values + L * kAttributeLeaf;

    const double leaves = L;
    double voxels = V, tile_bricks = 0;
    // The inside pass: solid mode's inside, and the sdf's sign.
    if (inside) {
        // The inside: about as many leaves as the surface (its inner side), and the bricks of the
        // enclosed volume as tiles (runs of bricks: 16 bytes a run, at most two per brick row).
        e.inside_bricks = std::min(std::fabs(m.signed_volume) / 512.0, bricks);
        const double inside_leaves = L;
        const double rows = double(grid.bricks().counts[1]) * double(grid.bricks().counts[2]);
        const double runs = std::min(2.0 * rows, e.inside_bricks);
        const bool by_rays = solid::insideByRays(*closure, options);
        const double all_triangles = double(mesh.view.triangle_count), vertices = double(mesh.view.vertex_count);
        const double rays_held = kRayTriangle * all_triangles + kRayEntry * m.ray_entries;
        const double rays = rays_held + kRayVertex * vertices;
        const double pieces = std::min(m.pieces, kPieceBudget * triangles + kPieceFloor);
        // The trees are built side by side, then the inside is found with them held.
        const double trees = by_rays ? rays : rays + windingBytes(triangles, pieces);
        const double trees_held = by_rays ? rays_held : rays_held + 2 * kPiece * pieces + kNodeKept * pieces / 2;
        const double found =
            (by_rays ? kInsidePerLeaf : kOpenInsidePerLeaf) * inside_leaves + 24.0 * L + 16.0 * kGrowing * runs;
        const double held = kLeaf * L + (channels > 0 ? kLeaf * L + values : 0.0);
        e.solid = held + std::max({kEdgesPerTriangle * triangles, trees, trees_held + found});
        // The inside merged into the surface: both sets of leaves while the result grows; after,
        // most inside leaves are the surface's bricks again (their voxels ORed together).
        e.solid = std::max(e.solid, held + kGrowing * kLeaf * (L + inside_leaves) + 16.0 * kGrowing * runs);
        tile_bricks = e.inside_bricks;
        if (channels > 0) {
            // The inside's voxels in the surface's bricks take the surface's values layer by
            // layer inward (attributes/inside_values.h): about the inner half of each brick,
            // the surface's own voxels counted once; each leaf's and region's record beside them.
            voxels = std::min(512.0 * L, V + kInsideValuedPerLeaf * L);
            const double regions = std::min(tile_bricks, kRegionsPerLeaf * L);
            e.attributes = std::max(e.attributes,
                                    kLeaf * 2 * L + values + voxels * channels * 4.0 + kInsideValuingLeaf * L +
                                        (kRegion + kRegionChannel * channels) * regions);
        }
    }

    // The sdf (sdf/level_set.h): the band reaches `band` voxels each side of the surface, so
    // its leaves are the surface's and their neighbours that far, each holding its masks and,
    // for the .vdb, all 512 values; the band's voxels' distances grow as a vector does. It is
    // made with the inside pass's result held.
    if (options.attributes.sdf) {
        const double band = options.sdf.band;
        const double band_leaves = std::min(L * (1.0 + 2.0 * std::ceil(band / 8.0)), bricks);
        const double band_voxels = std::min(V * (2.0 * band + 1.0), 512.0 * band_leaves);
        e.sdf = e.solid + kGrowing * (band_leaves * (2 * kLeaf + 8) + band_voxels * 4.0) +
            vdb::vdbWriterBytes(band_leaves, 0, 512.0 * band_leaves, 1.0);
    }

    // The .vdb writer beside the result (its leaves, tile runs and values).
    // The attribute values beside the writer's own bytes: the result's, and a part of them again
    // while a grid's leaves are filled (docs/why/memory-estimate.md).
    e.write = kLeaf * leaves + 16.0 * tile_bricks / 64.0 + 1.15 * voxels * channels * 4.0 +
        vdb::vdbWriterBytes(leaves, tile_bricks, voxels, channels);
    return e;
}

void checkBudget(const Estimate& estimate, const GridSpec& grid, const VoxelizeOptions& options) {
    if (estimate.peak() <= double(options.memoryBudgetBytes())) return;
    throw ResourceError("a " + grid.dimsText() + " grid needs about " + mib(estimate.peak()) + " for " +
                        estimate.largest() + " (about " + std::to_string(std::uint64_t(estimate.surface_leaves)) +
                        " leaves of surface), more than the memory budget of " +
                        std::to_string(options.memoryBudgetMib()) +
                        " MiB; use a larger voxel size or raise the budget (memory_budget_mib; in Blender: "
                        "Preferences > Add-ons > hyvox > Memory Budget)");
}

}  // namespace hyvox::memory
