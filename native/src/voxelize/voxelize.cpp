// SPDX-License-Identifier: GPL-3.0-or-later
// The dispatcher: checks the options against the schema, validates the mesh, lays out the
// grid, and runs the method's backend (core/backends.h) tile by tile into the sparse result.
#include "hyvox/voxelize.h"

#include <algorithm>
#include <cstdio>
#include <iterator>
#include <optional>
#include <string>
#if defined(__GLIBC__)
#include <malloc.h>  // malloc_trim
#endif

#include "attributes/inside_values.h"
#include "attributes/piece_attributes.h"
#include "attributes/tile_attributes.h"
#include "core/backends.h"
#include "core/gl_methods.h"
#include "core/stopwatch.h"
#include "hyvox/option_schema.h"
#include "hyvox/region.h"
#include "hyvox/texture.h"
#include "memory_estimate.h"
#include "sdf/level_set.h"
#include "solid/edge_closure.h"
#include "solid/fill_inside.h"
#include "tile_plan.h"

#include <tbb/task_arena.h>

namespace hyvox {
namespace {

std::string mib(std::uint64_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; }

// The displacement runs in single precision in voxel units on the GPU: beyond 2^24 voxels a
// point's position has no sub-voxel digits left (and 1e30 × a height overflows the grid's
// float math). Refused up front, naming the options that set it.
constexpr double kMaxDisplacementVoxels = double(1 << 24);

void checkDisplacementReach(const GridSpec& grid, const VoxelizeOptions& options, const tiling::PointReach& reach) {
    if (reach.fixed <= kMaxDisplacementVoxels) return;
    char text[400];
    std::snprintf(text, sizeof text,
                  "displacement_strength %.6g with displacement_midlevel %.6g moves points up to %.6g voxels "
                  "(%.6g world units); at most %.0f voxels can be computed: lower displacement_strength or bring "
                  "displacement_midlevel into the image's height range",
                  options.tessellation.displacement_strength, options.tessellation.displacement_midlevel,
                  reach.fixed - 1.0, (reach.fixed - 1.0) * grid.voxel_size, kMaxDisplacementVoxels);
    throw InvalidInput(text);
}

// A displaced surface none of whose points landed in the grid is not an empty result but a
// displacement that carried everything away: say so instead of returning 0 voxels.
// (A region's box may hold none of the surface: not checked there.)
void checkSomethingLanded(const Stats& stats, const tiling::PointReach& reach) {
    if (reach.fixed <= 0 || !stats.tessellation || stats.region) return;
    const TessellationStats& t = *stats.tessellation;
    if (t.points == 0 || t.points_clipped < t.points) return;
    throw InvalidInput("every one of the " + std::to_string(t.points) +
                       " displaced points left the grid (displacement moves points up to " +
                       std::to_string(std::uint64_t(reach.fixed - 1.0)) +
                       " voxels): lower displacement_strength, or give bounds or padding that hold the displaced "
                       "surface");
}

// Progress over the whole run: the backends report each tile's own 0..100.
class TileProgress final : public Interrupter {
public:
    TileProgress(Interrupter* outer, std::size_t tiles) : outer_(outer), tiles_(std::max<std::size_t>(tiles, 1)) {}
    void setTile(std::size_t done) { done_ = done; }
    bool wasInterrupted(int percent) override {
        if (!outer_) return false;
        if (percent < 0) return outer_->wasInterrupted(-1);
        return outer_->wasInterrupted(int((done_ * 100 + std::size_t(percent)) / tiles_));
    }

private:
    Interrupter* outer_;
    std::size_t tiles_;
    std::size_t done_ = 0;
};

void runBackend(const BackendJob& job, TileOutput& out, Stats& stats) {
    switch (job.options.method) {
        case Method::Cpu: runCpuBackend(job, out, stats); break;
        case Method::Reference: runReferenceBackend(job, out, stats); break;
        case Method::Triangle:
        case Method::Fragment:
        case Method::Hybrid:
            glMethods(std::string("the ") + toString(job.options.method) + " method").run_hybrid(job, out, stats);
            break;
        case Method::Tessellation: glMethods("the tessellation method").run_tessellation(job, out, stats); break;
    }
}

// The attribute evaluator when options.attributes asks for colour or normals (every method:
// the exact definition, or the tessellation's average of its points' values).
std::optional<attributes::SurfaceValues> surfaceValues(const MeshView& mesh, const VoxelizeOptions& options) {
    if (!options.attributes.surfaceValues()) return std::nullopt;
    return std::optional<attributes::SurfaceValues>(std::in_place, mesh, options.attributes);
}

// A region's tiles see the triangles that touch its voxels, which is all a surface voxel's
// values need; a solid's inside takes them from the nearest surface, layer by layer inward, and
// a whole tile region from its shell, across any cut of the grid (attributes/inside_values.h);
// the sdf's band and sign reach across the cut alike.
void checkRegionAttributes(const VoxelizeOptions& options) {
    if (options.region.whole()) return;
    if (options.attributes.sdf)
        throw InvalidInput("region " + formatRegion(options.region) +
                           ": the sdf needs the whole grid, since its band and its sign reach beyond any one region; "
                           "voxelize the whole grid for it");
    if (options.mode == Mode::Solid && options.attributes.surfaceValues())
        throw InvalidInput("region " + formatRegion(options.region) + ": solid mode with attributes (" +
                           toString(options.attributes) +
                           ") needs the whole grid, since the inside's values come from the surface around it, "
                           "beyond any one region; voxelize the regions without attributes, or in a surface mode");
}

// The grid's options: with the sdf, padded by at least its band, so that the band outside the
// mesh (and with it the level set's zero crossing) lies in the grid.
GridOptions gridOptions(const VoxelizeOptions& options) {
    GridOptions grid = options.grid;
    if (options.attributes.sdf) grid.padding = std::max(grid.padding, options.sdf.band);
    return grid;
}

// Refuse before allocating: the inside values hold every leaf voxel's channels (whole bricks
// with surface voxels included) and about 400 bytes a brick, beside the surface's values and
// the two grids.
void checkInsideValuesBudget(const SparseGrid& surface, const VoxelizeResult& result, const VoxelizeOptions& options) {
    const SparseGrid& solid = result.occupancy;
    const double tiles = double(solid.tileCount());
    const double leaf_voxels = double(solid.count()) - 512.0 * tiles +
        512.0 * std::min(tiles, double(surface.leafCount() + surface.tileCount()));
    const double bricks =
        double(solid.leafCount()) + std::min(tiles, double(surface.leafCount() + surface.tileCount()));
    const double held = double(result.attributes.values.size()) * 4.0 + double(surface.byteSize() + solid.byteSize());
    const double need = leaf_voxels * double(result.attributes.channels()) * 4.0 + bricks * 400.0;
    if (held + need > double(options.memoryBudgetBytes()))
        throw ResourceError("the inside's attribute values need about " + mib(std::uint64_t(need)) + " beside " +
                            mib(std::uint64_t(held)) + " held, more than the memory budget of " +
                            std::to_string(options.memoryBudgetMib()) + " MiB; use a larger voxel size");
}

// The bricks `grid` (finished) holds as whole tiles, ascending.
std::vector<std::uint64_t> tileBricks(const SparseGrid& grid) {
    std::vector<std::uint64_t> bricks;
    for (const SparseGrid::TileRun& run : grid.tileRuns())
        for (std::uint64_t b = run.begin; b < run.end; ++b) bricks.push_back(b);
    return bricks;
}

// The surface pass: the method's backend tile by tile into result.occupancy (not finished).
// With `values`, also each tile's attribute sums into `attribute_leaves`.
struct Surface {
    const ValidatedMesh& validated;
    const GridSpec& grid;
    const tiling::TilePlan& plan;
    Interrupter* interrupter;
    Stopwatch& watch;
    const attributes::SurfaceValues* values = nullptr;
    std::vector<AttributeLeaf>* attribute_leaves = nullptr;

    void run(const VoxelizeOptions& options, VoxelizeResult& result, Stats& stats) const {
        result.occupancy = SparseGrid(grid.dims);
        std::vector<std::vector<std::uint32_t>> bins;
        // The reach of this pass's method: the solid barrier's cpu pass bins without the
        // tessellation's displacement and patch bulge.
        if (!plan.whole())
            bins = tiling::binTriangles(validated, grid, plan, tiling::pointReach(grid, options), interrupter);
        stats.addTiming("tiles", watch.restart());

        // The tessellation averages its own points' values; the GL methods clip their pieces on
        // the GPU and the cpu and reference methods clip here, both summed after.
        const bool own_attributes = values && options.method == Method::Tessellation;
        const bool gl_pieces = values &&
            (options.method == Method::Triangle || options.method == Method::Fragment ||
             options.method == Method::Hybrid);
        TileProgress progress(interrupter, plan.total());
        for (std::size_t t = 0; t < plan.total(); ++t) {
            if (!plan.whole() && bins[t].empty()) continue;
            const Tile tile = plan.tile(t);
            ValidatedMesh part;
            if (!plan.whole())
                part = ValidatedMesh{validated.view, std::move(bins[t]), validated.degenerate_count, validated.bounds};
            const ValidatedMesh& tile_mesh = plan.whole() ? validated : part;
            progress.setTile(t);
            TileOutput out{BitGrid(tile.dims), {}, {}, 0, {}};
            stats.addTiming("allocate", watch.restart());
            const BackendJob job{
                tile_mesh, validated, grid, tile, options, &progress, own_attributes ? values : nullptr, gl_pieces};
            runBackend(job, out, stats);
            watch.restart();
            if (own_attributes) {
                std::move(out.attributes.begin(), out.attributes.end(), std::back_inserter(*attribute_leaves));
                stats.attribute_voxels_unreached += out.attribute_voxels_unreached;
            } else if (gl_pieces) {
                const auto counted =
                    attributes::computePieceAttributes(job, out.bits, *values, out.pieces, *attribute_leaves);
                std::vector<VoxelPiece>().swap(out.pieces);
                stats.attribute_pieces += counted.pieces;
                stats.attribute_voxels_unreached += counted.voxels_unreached;
                stats.attribute_leaves_rounded += counted.leaves_rounded;
                stats.addTiming("attributes", watch.restart());
            } else if (values) {
                const auto counted = attributes::computeTileAttributes(
                    job, out.bits, *values, options.method == Method::Reference, *attribute_leaves);
                stats.attribute_pieces += counted.pieces;
                stats.attribute_voxels_unreached += counted.voxels_unreached;
                stats.attribute_leaves_rounded += counted.leaves_rounded;
                stats.addTiming("attributes", watch.restart());
            }
            result.occupancy.addTile(out.bits, tile.offset);
            result.counts.insert(result.counts.end(), out.counts.begin(), out.counts.end());
            ++stats.tiles;
            const std::uint64_t held = plan.tileBytes() + result.occupancy.byteSize();
            if (held > options.memoryBudgetBytes())
                throw ResourceError("the surface needs more than the memory budget of " +
                                    std::to_string(options.memoryBudgetMib()) + " MiB (" +
                                    std::to_string(result.occupancy.leafCount()) + " leaves after " +
                                    std::to_string(stats.tiles) + " tiles); use a larger voxel size");
            stats.addTiming("compact", watch.restart());
            throwIfInterrupted(interrupter, int(100 * (t + 1) / plan.total()));
        }
    }
};

// The inside test (src/solid/): solid mode's inside voxels, and the sign of the sdf. It needs
// the exact conservative surface as its barrier: the tessellation's approximate one and thin
// mode's get the cpu method's conservative one beside them.
struct InsidePass {
    VoxelizeResult exact;       // that barrier, when the run's own surface is not it
    SparseGrid inside;          // voxels off the barrier whose centre is inside
    SparseGrid surface_inside;  // with the sdf: the barrier's voxels whose centre is inside
    bool own_barrier = false;   // `exact` holds it

    void run(const ValidatedMesh& validated, const GridSpec& grid, const Surface& surface,
             const VoxelizeOptions& options, const solid::EdgeClosure& closure, VoxelizeResult& result, Stats& stats,
             Interrupter* interrupter, Stopwatch& watch) {
        result.occupancy.finish();
        SolidStats& solid = stats.solid.emplace();
        own_barrier = options.method == Method::Tessellation || options.mode == Mode::Thin;
        if (own_barrier) {
            VoxelizeOptions cpu = options;
            cpu.mode = Mode::Conservative;
            cpu.method = Method::Cpu;
            Stats ignored;
            surface.run(cpu, exact, ignored);
            exact.occupancy.finish();
            stats.addTiming("solid_barrier", watch.restart());
        }
        inside = solid::fillInside(validated, grid, barrier(result), options, closure, interrupter, solid,
                                   options.attributes.sdf ? &surface_inside : nullptr);
        stats.addTiming("solid_inside", watch.restart());
    }
    const SparseGrid& barrier(const VoxelizeResult& result) const {
        return own_barrier ? exact.occupancy : result.occupancy;
    }
    std::uint64_t byteSize() const {
        return exact.occupancy.byteSize() + inside.byteSize() + surface_inside.byteSize();
    }
};
}  // namespace

ValidatedMesh validate(const MeshView& mesh, const VoxelizeOptions& options, Interrupter* interrupter) {
    tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
    return arena.execute([&] { return validate(mesh, interrupter); });
}

namespace {

// The options the passes run with: a displacement image file read into its pixels by io's PNG
// reader (one reader and one set of limits for every image; the backends never open files).
// Only the tessellation method displaces: the other methods ignore the option (with a warning
// at the front doors), so they must not fail on an image they never use.
VoxelizeOptions withImagesRead(const VoxelizeOptions& given) {
    VoxelizeOptions options = given;
    TessellationOptions& tess = options.tessellation;
    if (options.method == Method::Tessellation && !tess.displacement_image.empty()) {
        tess.displacement_pixels = readPngHeight(tess.displacement_image);
        tess.displacement_image.clear();
    }
    return options;
}

// voxelize() after its options were checked and its interrupter started.
VoxelizeResult voxelizeValidated(const ValidatedMesh& validated, const VoxelizeOptions& given, Interrupter* interrupter,
                                 double validate_ms) {
    const MeshView& mesh = validated.view;
    const VoxelizeOptions options = withImagesRead(given);

    VoxelizeResult result;
    Stats& stats = result.stats;
    stats.options = given;  // as asked (the image's path, not its pixels)
    Stopwatch watch;
    stats.addTiming("validate", validate_ms);
    const std::optional<attributes::SurfaceValues> surface = surfaceValues(mesh, options);
    std::vector<AttributeLeaf> attribute_leaves;
    result.grid = makeGrid(validated.bounds, gridOptions(options));
    const GridSpec& grid = result.grid;
    // The tessellation holds a tile's bits in one storage buffer (the hybrid methods cut theirs
    // into slabs themselves), and its attribute sums take a block per brick the points reach:
    // its tiles also follow the device's limit.
    const std::uint64_t device_limit = options.method == Method::Tessellation
        ? glMethods("the tessellation method")
              .tessellation_tile_bytes(options.gl.device, options.memoryBudgetBytes() / 2,
                                       surface ? surface->channels() : 0)
        : 0;
    const tiling::TilePlan plan = tiling::planTiles(grid, options, device_limit);
    if (plan.region) stats.region = regionBox(grid, options.region);
    // The inside test's edge check first (solid mode, and the sdf's sign): it decides the solid
    // pass's trees, and so its memory.
    std::optional<solid::EdgeClosure> closure;
    if (options.mode == Mode::Solid || options.attributes.sdf) {
        tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
        closure = arena.execute([&] { return solid::checkEdges(validated, grid); });
    }
    const memory::Estimate need = memory::estimate(validated, grid, options, plan, surface ? surface->channels() : 0,
                                                   closure ? &*closure : nullptr);
    stats.memory_estimate = MemoryEstimateStats{std::uint64_t(need.surface),        std::uint64_t(need.solid),
                                                std::uint64_t(need.attributes),     std::uint64_t(need.write),
                                                std::uint64_t(need.peak()),         std::uint64_t(need.surface_leaves),
                                                std::uint64_t(need.surface_voxels), std::uint64_t(need.inside_bricks)};
    memory::checkBudget(need, grid, options);
    const tiling::PointReach reach = tiling::pointReach(grid, options);
    checkDisplacementReach(grid, options, reach);
    stats.addTiming("validate", watch.restart());
    throwIfInterrupted(interrupter, 0);

    stats.method = toString(options.method);
    stats.mode = toString(options.mode);
    stats.triangles_input = mesh.triangle_count;
    stats.triangles_used = validated.usable.size();
    stats.triangles_degenerate = validated.degenerate_count;

    // Solid mode: the backends draw the conservative surface; the inside is added after.
    const bool solid = options.mode == Mode::Solid;
    VoxelizeOptions surface_options = options;
    if (solid) surface_options.mode = Mode::Conservative;
    Surface surface_pass{validated, grid, plan, interrupter, watch};
    if (surface) {
        surface_pass.values = &*surface;
        surface_pass.attribute_leaves = &attribute_leaves;
    }
    surface_pass.run(surface_options, result, stats);
    // Solid with attributes: the surface's voxels and values are kept apart, the inside's
    // values are derived from them once the inside is known (attributes/inside_values.h).
    SparseGrid solid_surface;
    if (surface) {
        result.occupancy.finish();
        result.attributes = surface->layout();
        attributes::assembleAttributes(attribute_leaves, result.attributes, options.threads);
        result.attributes.valued_tile_bricks = tileBricks(result.occupancy);
        if (solid) solid_surface = result.occupancy;
    }
    if (solid || options.attributes.sdf) {
        surface_pass.values = nullptr;  // the barrier pass computes no attributes
        InsidePass inside;
        inside.run(validated, grid, surface_pass, options, *closure, result, stats, interrupter, watch);
        if (options.attributes.sdf) {
            const std::uint64_t held = result.occupancy.byteSize() + inside.byteSize() + solid_surface.byteSize() +
                result.attributes.values.size() * sizeof(float);
            const sdf::InsideCentres centres{inside.barrier(result), inside.surface_inside, inside.inside};
            result.sdf = sdf::makeLevelSet(validated, grid, centres, options, held, interrupter, stats.sdf.emplace());
            stats.addTiming("sdf", watch.restart());
        }
        if (solid) result.occupancy.merge(inside.inside);
    }
    throwIfInterrupted(interrupter, 100);
    checkSomethingLanded(stats, reach);
    result.occupancy.finish();
    if (surface && solid) {
        checkInsideValuesBudget(solid_surface, result, options);
        attributes::InsideValueCounts counted;
        result.attributes =
            attributes::valueInside(solid_surface, result.attributes, result.occupancy,
                                    attributes::meshMeanValue(validated, *surface), options.threads, counted);
        SolidStats& s = *stats.solid;
        s.attribute_inside_voxels = counted.voxels;
        s.attribute_layers = counted.layers;
        s.attribute_tile_regions = counted.regions;
        s.attribute_region_layers = counted.region_layers;
        s.attribute_through_regions = counted.through_regions;
        s.attribute_fallback = counted.fallback;
        stats.addTiming("attributes_inside", watch.restart());
    }
    stats.voxel_count = result.occupancy.count();
    stats.leaves = result.occupancy.leafCount();
    if (stats.solid) stats.solid->tile_bricks = result.occupancy.tileCount();
    stats.addTiming("count", watch.restart());
    return result;
}

// glibc keeps what the passes freed (the solid pass's trees and leaf lists) in its heap, where
// the .vdb writer's buffers, made on other threads' heaps, do not go: without this the write's
// memory comes on top of it, past the estimate, and in Blender the artist's session keeps it.
// Only for runs estimated at 64 MiB or more: handing memory back walks the heap, and the next
// run faults to take it again, which Live's small repeated runs would pay
// (docs/why/memory-estimate.md).
void returnFreedMemory(const VoxelizeResult& result) {
    constexpr std::uint64_t kLargeRun = std::uint64_t(64) << 20;
    if (!result.stats.memory_estimate || result.stats.memory_estimate->peak < kLargeRun) return;
#if defined(__GLIBC__)
    malloc_trim(0);
#endif
}

}  // namespace

VoxelizeResult voxelize(const MeshView& mesh, const VoxelizeOptions& options, Interrupter* interrupter) {
    checkOptions(options);
    checkRegionAttributes(options);
    const InterrupterRun run(interrupter, "hyvox voxelize");
    Stopwatch watch;
    const ValidatedMesh validated = validate(mesh, options, interrupter);
    VoxelizeResult result = voxelizeValidated(validated, options, interrupter, watch.elapsedMs());
    returnFreedMemory(result);
    return result;
}

VoxelizeResult voxelize(const ValidatedMesh& validated, const VoxelizeOptions& options, Interrupter* interrupter,
                        double validate_ms) {
    checkOptions(options);
    checkRegionAttributes(options);
    const InterrupterRun run(interrupter, "hyvox voxelize");
    VoxelizeResult result = voxelizeValidated(validated, options, interrupter, validate_ms);
    returnFreedMemory(result);
    return result;
}

}  // namespace hyvox
