// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// What voxelize() returns: the grid, the voxels (and their counts and attributes where asked
/// for) and the stats of the run. A result is a plain value: copy, move and read it from any
/// thread.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "hyvox/attribute_grid.h"
#include "hyvox/grid.h"
#include "hyvox/level_set.h"
#include "hyvox/options.h"
#include "hyvox/region.h"
#include "hyvox/sparse_grid.h"

namespace hyvox {

// Each backend's own figures, one typed section per backend. `visit(f)` calls
// f(name, value) for every field: the JSON writer (and through it the Python dict and the
// CLI's --stats-json) takes the names from there, so a new figure is one field and one line.

/// The cpu method's figures.
struct CpuStats {
    std::uint64_t split_triangles = 0;  ///< large triangles cut into pieces for the thread pool
    /// Small triangles not set up: every candidate voxel was set already (by their neighbours;
    /// depends on the order the threads reach them).
    std::uint64_t triangles_already_covered = 0;
    /// Calls f(name, value) for every figure, in declaration order.
    template <typename F>
    void visit(F&& f) const {
        f("split_triangles", split_triangles);
        f("triangles_already_covered", triangles_already_covered);
    }
};

/// The reference method's figures.
struct ReferenceStats {
    std::uint64_t voxel_tests = 0;  ///< triangle/box tests run
    /// Calls f(name, value) for every figure, in declaration order.
    template <typename F>
    void visit(F&& f) const {
        f("voxel_tests", voxel_tests);
    }
};

/// Methods triangle, fragment and hybrid (JCGT 2013: Pass 1 = compute, Pass 2 = raster).
struct HybridStats {
    double pass1_gpu_ms = 0;               ///< triangle-parallel compute, or hybrid classify + small triangles
    double pass2_gpu_ms = 0;               ///< fragment-parallel raster, or hybrid's large triangles
    double upload_ms = 0;                  ///< the mesh to the GPU, milliseconds
    double readback_ms = 0;                ///< the bits back from the GPU, milliseconds
    std::uint64_t tiles = 0;               ///< slabs the grid ran in
    double cutoff = 0;                     ///< voxel units² used (triangle: inf, fragment: 0)
    std::uint64_t large_triangles = 0;     ///< hybrid: triangles sent to pass 2 (summed over tiles)
    std::uint64_t cutoff_search_runs = 0;  ///< timed runs of the auto-cutoff search (0: given or cached)
    /// Calls f(name, value) for every figure, in declaration order.
    template <typename F>
    void visit(F&& f) const {
        f("pass1_gpu_ms", pass1_gpu_ms);
        f("pass2_gpu_ms", pass2_gpu_ms);
        f("upload_ms", upload_ms);
        f("readback_ms", readback_ms);
        f("tiles", tiles);
        f("cutoff", cutoff);
        f("large_triangles", large_triangles);
        f("cutoff_search_runs", cutoff_search_runs);
    }
};

/// The tessellation method's figures.
struct TessellationStats {
    double gamma = 0;  ///< the safety factor γ used
    /// Summed over tiles (a triangle reaching k tiles is drawn in each): points - points_clipped
    /// is the number of points that landed in the grid.
    std::uint64_t points = 0;           ///< micro-triangles drawn, one point each
    std::uint64_t points_clipped = 0;   ///< of which outside the tile they were drawn for
    std::uint64_t triangles_whole = 0;  ///< small enough for one point (compute pass)
    std::uint64_t patches_direct = 0;   ///< tessellated as they are
    std::uint64_t patches_split = 0;    ///< pieces of pre-split triangles
    std::uint64_t split_triangles = 0;  ///< triangles pre-split (factor over the GL limit)
    std::uint64_t largest_split = 0;    ///< most pieces one triangle was cut into
    std::uint64_t max_tess_level = 0;   ///< GL_MAX_TESS_GEN_LEVEL
    double pass0_gpu_ms = 0;            ///< whole triangles (compute)
    double pass1_gpu_ms = 0;            ///< tessellated triangles
    double pass2_gpu_ms = 0;            ///< pre-split triangles
    std::uint64_t gpu_runs = 0;         ///< 2 when the count pool had to grow
    /// Calls f(name, value) for every figure, in declaration order.
    template <typename F>
    void visit(F&& f) const {
        f("gamma", gamma);
        f("points", points);
        f("points_clipped", points_clipped);
        f("triangles_whole", triangles_whole);
        f("patches_direct", patches_direct);
        f("patches_split", patches_split);
        f("split_triangles", split_triangles);
        f("largest_split", largest_split);
        f("max_tess_level", max_tess_level);
        f("pass0_gpu_ms", pass0_gpu_ms);
        f("pass1_gpu_ms", pass1_gpu_ms);
        f("pass2_gpu_ms", pass2_gpu_ms);
        f("gpu_runs", gpu_runs);
    }
};

/// What the run was estimated to hold beside its mesh before any work, pass by pass (bytes;
/// src/voxelize/memory_estimate.h), and the surface and inside it was estimated from. The run
/// is refused when the largest exceeds the memory budget.
struct MemoryEstimateStats {
    std::uint64_t surface_pass = 0;      ///< the surface pass's buffers
    std::uint64_t solid_pass = 0;        ///< the solid pass's
    std::uint64_t attribute_values = 0;  ///< the attribute values'
    std::uint64_t vdb_write = 0;         ///< the .vdb write's grids
    std::uint64_t peak = 0;              ///< the largest of them, held at once
    std::uint64_t surface_leaves = 0;    ///< the surface's estimated 8³ leaves
    std::uint64_t surface_voxels = 0;    ///< and voxels
    std::uint64_t inside_bricks = 0;     ///< the inside's estimated bricks (solid mode)
    /// Calls f(name, value) for each field, as the stats JSON names them.
    template <typename F>
    void visit(F&& f) const {
        f("surface_pass", surface_pass);
        f("solid_pass", solid_pass);
        f("attribute_values", attribute_values);
        f("vdb_write", vdb_write);
        f("peak", peak);
        f("surface_leaves", surface_leaves);
        f("surface_voxels", surface_voxels);
        f("inside_bricks", inside_bricks);
    }
};

/// Solid mode (src/solid/): what the closedness check found, the rule it led to, and how much
/// of the grid was decided per region instead of per voxel.
struct SolidStats {
    std::string inside_rule;  ///< "parity" or "winding": the rule that ran
    /// "ray crossings" (parity, or the winding number of a closed mesh as their signed sum),
    /// "fast winding numbers" (Barill et al. 2018), or "sheets of the open edges" (an open
    /// mesh's winding numbers as its ray crossings less the open edges' sheets: few open edges)
    std::string evaluation;
    std::string reason;  ///< why (the option, or auto's finding)
    /// Edges after welding identical positions: used by one triangle, by more than two, or by
    /// two triangles running the same way. All 0 = closed and consistently oriented.
    std::uint64_t boundary_edges = 0;
    std::uint64_t nonmanifold_edges = 0;    ///< edges of more than two triangles
    std::uint64_t misoriented_edges = 0;    ///< edges two triangles run the same way
    std::uint64_t inside_voxels = 0;        ///< set for being inside, not already on the surface
    std::uint64_t tile_bricks = 0;          ///< 8³ bricks of the result held as whole active tiles
    std::uint64_t uniform_regions = 0;      ///< surface-free boxes decided by one evaluation
    std::uint64_t component_decisions = 0;  ///< connected empty parts of surface bricks decided by one evaluation
    std::uint64_t point_evaluations = 0;    ///< inside tests run (winding numbers or ray parities)
    std::uint64_t interpolated_voxels =
        0;  ///< open meshes: voxels decided from the winding number's interpolated smooth part
    /// With attributes (attributes/inside_values.h): inside voxels held in leaves valued by layers
    /// from the surface, the layers that took; tile regions (one value each) and the region
    /// layers after those valued from their shell; leaf voxels valued beside regions; voxels and
    /// regions left to the mesh's mean (0 for a connected inside).
    std::uint64_t attribute_inside_voxels = 0;    ///< inside voxels valued in leaves
    std::uint64_t attribute_layers = 0;           ///< the layers that took
    std::uint64_t attribute_tile_regions = 0;     ///< tile regions, one value each
    std::uint64_t attribute_region_layers = 0;    ///< region layers after those valued from their shell
    std::uint64_t attribute_through_regions = 0;  ///< leaf voxels valued beside regions
    std::uint64_t attribute_fallback = 0;         ///< voxels and regions left to the mesh's mean
    /// Calls f(name, value) for every figure, in declaration order.
    template <typename F>
    void visit(F&& f) const {
        f("inside_rule", inside_rule);
        f("evaluation", evaluation);
        f("reason", reason);
        f("boundary_edges", boundary_edges);
        f("nonmanifold_edges", nonmanifold_edges);
        f("misoriented_edges", misoriented_edges);
        f("inside_voxels", inside_voxels);
        f("tile_bricks", tile_bricks);
        f("uniform_regions", uniform_regions);
        f("component_decisions", component_decisions);
        f("point_evaluations", point_evaluations);
        f("interpolated_voxels", interpolated_voxels);
        f("attribute_inside_voxels", attribute_inside_voxels);
        f("attribute_layers", attribute_layers);
        f("attribute_tile_regions", attribute_tile_regions);
        f("attribute_region_layers", attribute_region_layers);
        f("attribute_through_regions", attribute_through_regions);
        f("attribute_fallback", attribute_fallback);
    }
};

/// The sdf attribute (src/sdf/): its band and the work its distances took.
struct SdfStats {
    double background = 0;                   ///< the band's half-width, world units
    std::uint64_t active_voxels = 0;         ///< voxels within the band
    std::uint64_t leaves = 0;                ///< 8³ leaves of the level set
    std::uint64_t inside_tile_bricks = 0;    ///< bricks held as inside tiles (inactive, -background)
    std::uint64_t triangle_blocks = 0;       ///< (triangle, 32³ block) pairs measured
    std::uint64_t distance_evaluations = 0;  ///< point-triangle distances computed
    /// Calls f(name, value) for each field, as the stats JSON names them.
    template <typename F>
    void visit(F&& f) const {
        f("background", background);
        f("active_voxels", active_voxels);
        f("leaves", leaves);
        f("inside_tile_bricks", inside_tile_bricks);
        f("triangle_blocks", triangle_blocks);
        f("distance_evaluations", distance_evaluations);
    }
};

/// The figures of one run: counts, stage timings (milliseconds), the options it used and the
/// backend's own section.
struct Stats {
    std::string method;                      ///< the schema name of the method that ran
    std::string mode;                        ///< the schema name of the mode
    std::uint64_t triangles_input = 0;       ///< triangles of the mesh
    std::uint64_t triangles_used = 0;        ///< of which voxelized
    std::uint64_t triangles_degenerate = 0;  ///< skipped
    std::uint64_t voxel_count = 0;           ///< set voxels of the result
    /// Stage name -> milliseconds, in the order the stages first ran (validate, voxelize, ...),
    /// summed over the tiles of a tiled run.
    std::vector<std::pair<std::string, double>> timings_ms;
    std::uint64_t tiles = 0;      ///< boxes of the grid voxelized one after the other
    std::uint64_t leaves = 0;     ///< non-empty, not wholly set 8³ leaves of the result (tiles apart)
    std::uint64_t vdb_bytes = 0;  ///< the OpenVDB grids' memory, when a front door wrote them
    /// Attribute voxels (options.attributes): clipped (triangle, voxel) pieces averaged; leaves
    /// where a set voxel's touch was lost to rounding in the clip and found again with a 1e-9
    /// voxel margin; set voxels no piece reached even so (their values are 0).
    std::uint64_t attribute_pieces = 0;            ///< clipped (triangle, voxel) pieces averaged
    std::uint64_t attribute_leaves_rounded = 0;    ///< leaves where a touch was found with the margin
    std::uint64_t attribute_voxels_unreached = 0;  ///< set voxels no piece reached (valued 0)
    /// The options the run used (after the front door read its environment variables).
    VoxelizeOptions options;
    /// A region's run (options.region): the box of the grid it voxelized; the rest is empty.
    std::optional<RegionBox> region;
    /// The section of the backend that ran; the others stay empty.
    std::optional<CpuStats> cpu;                    ///< the cpu method
    std::optional<ReferenceStats> reference;        ///< the reference method
    std::optional<HybridStats> hybrid;              ///< triangle, fragment and hybrid
    std::optional<TessellationStats> tessellation;  ///< the tessellation method
    /// Solid mode, and any mode with the sdf attribute (its sign is the inside test), beside
    /// the backend's section.
    std::optional<SolidStats> solid;
    std::optional<SdfStats> sdf;                         ///< with the sdf attribute
    std::optional<MemoryEstimateStats> memory_estimate;  ///< every run of voxelize()

    /// Adds `ms` milliseconds to `stage` (a new stage goes last).
    void addTiming(const std::string& stage, double ms) {
        for (auto& [name, total] : timings_ms)
            if (name == stage) {
                total += ms;
                return;
            }
        timings_ms.emplace_back(stage, ms);
    }
    /// Milliseconds of every stage together.
    double totalMs() const {
        double total = 0;
        for (const auto& stage : timings_ms) total += stage.second;
        return total;
    }
    /// Milliseconds of one stage, 0 when it did not run.
    double timingMs(const std::string& stage) const {
        for (const auto& [name, ms] : timings_ms)
            if (name == stage) return ms;
        return 0.0;
    }
    /// Calls f(section name, section) for the section that is set.
    template <typename F>
    void visitSections(F&& f) const {
        if (cpu) f("cpu", *cpu);
        if (reference) f("reference", *reference);
        if (hybrid) f("hybrid", *hybrid);
        if (tessellation) f("tessellation", *tessellation);
        if (solid) f("solid", *solid);
        if (sdf) f("sdf", *sdf);
        if (memory_estimate) f("memory_estimate", *memory_estimate);
    }
};

/// A voxel with a value (multi-valued output such as the tessellation method's point counts).
struct VoxelCount {
    std::int32_t i;       ///< the voxel's x index
    std::int32_t j;       ///< y index
    std::int32_t k;       ///< z index
    std::uint32_t count;  ///< its value (points that landed in it)
};

/// The result of voxelize().
struct VoxelizeResult {
    GridSpec grid;                   ///< the grid laid out (world units)
    SparseGrid occupancy;            ///< the set voxels as OpenVDB-layout leaves
    std::vector<VoxelCount> counts;  ///< empty unless the method is multi-valued
    AttributeGrid attributes;        ///< empty unless options.attributes asked for color or normal
    LevelSetGrid sdf;                ///< empty unless options.attributes asked for sdf
    Stats stats;                     ///< the run's figures
};

}  // namespace hyvox
