// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// The options of one voxelization as plain structs. Their names, defaults, limits, units and
/// help live in one place, the schema (hyvox/option_schema.h), from which every front door
/// (CLI, Python, the Blender add-on) is derived; voxelize() checks every field against it.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "hyvox/grid.h"

namespace hyvox {

/// Which voxels a voxelization sets.
enum class Mode {
    Conservative,  ///< every voxel whose closed box meets the triangle (26-separating)
    Thin,          ///< Schwarz & Seidel's 6-separating surface (fewer voxels, still no 6-connected leak)
    Solid,         ///< the conservative surface plus every voxel whose centre is inside (InsideRule)
};

/// How solid mode decides that a voxel centre is inside (src/solid/).
/// parity: an odd number of surface crossings on the ray from the centre along -z (exact for
/// closed meshes). winding: generalized winding number >= 0.5 (holes, flipped or duplicated
/// faces, nested shells). auto: the winding number, counted exactly by the signed crossings of
/// the parity rays when the mesh is closed and consistently oriented (as fast as parity, and
/// right where closed shells overlap), else by fast winding numbers; the finding is reported
/// in Stats::solid.
enum class InsideRule {
    Auto,     ///< the winding number, by the parity rays' signed crossings where the mesh is closed
    Parity,   ///< an odd number of crossings along -z
    Winding,  ///< generalized winding number >= 0.5, by fast winding numbers
};

/// The backend that voxelizes the surface (docs/design.md, "Data flow").
enum class Method {
    Cpu,           ///< factored triangle/voxel test, multi-threaded (fallback without a GPU)
    Reference,     ///< brute-force double-precision SAT: the test oracle, slow on purpose
    Triangle,      ///< GL triangle-parallel
    Fragment,      ///< GL fragment-parallel
    Hybrid,        ///< GL hybrid (classifier + both)
    Tessellation,  ///< GL adaptive point tessellation (approximate, multi-valued)
};

/// The schema's name of a value ("conservative", "cpu", ...), a static string.
///@{
const char* toString(Mode mode);
const char* toString(Method method);
const char* toString(InsideRule rule);
///@}
/// The value of a schema name.
/// @throws InvalidInput naming the choices, for any other text
///@{
Mode parseMode(const std::string& text);
Method parseMethod(const std::string& text);
InsideRule parseInsideRule(const std::string& text);
///@}
/// Every value's schema name, in enum order.
///@{
std::vector<const char*> modeNames();
std::vector<const char*> methodNames();
std::vector<const char*> insideRuleNames();
///@}

/// What a run computes beside the occupancy: the option `attributes`, written as a comma list
/// of its names ("color,sdf"; "" = none) at the front doors.
struct AttributeSet {
    /// Per occupied voxel, the surface's linear RGB (and alpha where the colour source has
    /// it), area-weighted inside the voxel (hyvox/attribute_grid.h).
    bool color = false;
    bool normal = false;  ///< per occupied voxel, the surface's unit normal, weighted alike
    /// A narrow-band signed distance level set (hyvox/level_set.h), signed by the inside test
    /// of solid mode in every mode.
    bool sdf = false;
    bool any() const { return color || normal || sdf; }     ///< whether anything is asked for
    bool surfaceValues() const { return color || normal; }  ///< the per-voxel values of the surface
    bool operator==(const AttributeSet& other) const {      ///< the same names asked for
        return color == other.color && normal == other.normal && sdf == other.sdf;
    }
};
/// The attribute names, in the order toString writes them.
std::vector<const char*> attributeNames();
/// The comma list of the names a set asks for ("" = none).
std::string toString(const AttributeSet& set);
/// The set a comma list names (a name given twice counts once).
/// @throws InvalidInput naming the accepted names for anything else
AttributeSet parseAttributeSet(const std::string& text);

/// Options of the GL methods (the schema's "gl" group).
struct GlOptions {
    std::string device;      ///< "" = auto (hardware first, then software); "software"; or an index "0", "1"...
    std::string shader_dir;  ///< "" = the shaders embedded in the library; else a copy of shaders/ to read
    /// Largest bit-grid tile in bytes; 0 = one shader storage block (the device's limit).
    /// Smaller values force tiling (tests of the tile borders).
    std::uint64_t tile_bytes = 0;
    /// Largest list of (voxel, triangle) pairs, in bytes, of the triangle/fragment/hybrid
    /// attribute pass (its pieces take 20 bytes each); 0 = one shader storage block. Smaller
    /// values make tiles whose pairs do not fit run as halves (tests of that halving).
    std::uint64_t pair_list_bytes = 0;
    /// Time GL passes by the wall clock around glFinish instead of GPU timer queries
    /// (always on for Mesa's llvmpipe, whose timer queries miss compute work).
    bool wall_timing = false;
    /// Tessellation: one instance per patch instead of one plain patch draw (always on for
    /// llvmpipe, which assembles long patch draws wrongly).
    bool tess_instanced = false;
};

/// Options of the hybrid method.
struct HybridOptions {
    /// Triangles whose projected area on their dominant plane exceeds this many voxel units²
    /// are rasterized (fragment-parallel); the rest are voxelized per triangle.
    /// Negative = auto: a bracketing search over timed runs, cached per mesh and resolution.
    double cutoff = -1.0;
};

/// A grey height image in memory: width × height values, row 0 = the image's top row (as in
/// a PNG file), typically 0..1. Data, not an option: passed beside the schema's options.
struct HeightImage {
    int width = 0;                                 ///< values per row
    int height = 0;                                ///< rows
    std::vector<float> values;                     ///< width * height heights, rows top first
    bool empty() const { return values.empty(); }  ///< no image
};

/// Options of the tessellation method.
struct TessellationOptions {
    /// Safety factor γ of Eq. 1 (edge factor = γ · the edge's length in voxels). 2, not the
    /// paper's 1: from 2 on, the micro-triangles are small enough that one point each seals a
    /// closed mesh against a flood from outside, an argument the closed meshes measured bear
    /// out; below 2 it does not hold and a closed mesh may leak (docs/why/tessellation-gamma.md).
    double gamma = 2.0;
    bool pn_triangles = false;  ///< smooth the surface by PN-triangles (Vlachos et al.) before the points
    /// Displacement (section 3.3), Blender Displace modifier semantics: each point moves along
    /// the interpolated vertex normal by (texel - midlevel) * strength world units, the texel
    /// sampled bilinearly (clamped at the edges) at the interpolated UV; needs MeshView::uvs.
    /// Used when displacement_image (an 8/16-bit PNG path) or displacement_pixels is given.
    /// The grid is laid out from the undisplaced mesh: points that leave it are dropped and
    /// counted (TessellationStats::points_clipped); give GridOptions bounds or padding for room.
    std::string displacement_image;
    HeightImage displacement_pixels;     ///< used when displacement_image is empty
    double displacement_strength = 1.0;  ///< world units of displacement per unit of height
    double displacement_midlevel = 0.5;  ///< the height that stays in place
    bool counts = true;                  ///< also fill VoxelizeResult::counts (points per voxel)
};

/// Options of the `sdf` attribute (src/sdf/).
struct SdfOptions {
    /// The narrow band's half-width in voxels: voxels whose centre lies closer than this to the
    /// surface hold their signed distance, the others (inactive) ±band × voxel size, as
    /// OpenVDB's level sets do. The grid is padded by at least this many voxels so that the
    /// band around the mesh fits.
    int band = 3;
};

/// Options of solid mode.
struct SolidOptions {
    InsideRule inside = InsideRule::Auto;  ///< how a voxel centre is found inside
    /// Fast winding numbers (Barill et al. 2018): a cluster of triangles is replaced by its
    /// expansion when the query is farther than beta times the cluster's radius. Larger is
    /// more accurate and slower.
    double winding_beta = 2.0;
};

/// One of `count` boxes the grid is cut into along its longest side (hyvox/region.h): a run
/// voxelizes box `index` (from 0) of the whole grid only, for a farm's tasks whose .vdb files
/// `hyvox merge` joins. count 1 = the whole grid.
struct RegionOptions {
    int index = 0;                             ///< the box, from 0
    int count = 1;                             ///< the boxes the grid is cut into
    bool whole() const { return count == 1; }  ///< the whole grid
};

/// The memory budget a run has when memory_budget_mib is 0: half of this machine's physical
/// memory, or of the memory limit of the cgroup this process runs in when that is smaller
/// (a container's), in MiB, at least 256.
std::uint64_t defaultMemoryBudgetMib();

/// What decides a voxelization's voxels, and the resources it may use (threads, memory).
/// How its result is written is WriteOptions' business.
/// Every field is a schema option (hyvox/option_schema.h gives its name, limits and help);
/// voxelize() refuses a field out of its limits with the schema's message.
struct VoxelizeOptions {
    GridOptions grid;                ///< the grid's layout
    RegionOptions region;            ///< the box of the grid a farm task voxelizes (all of it by default)
    Mode mode = Mode::Conservative;  ///< which voxels are set
    Method method = Method::Cpu;     ///< which backend sets them
    int threads = 0;                 ///< CPU threads; 0 = all cores
    /// What the run may hold beside the mesh it is given (MiB): every buffer of the passes it
    /// runs and of the .vdb it writes; a run estimated to need more is refused before any work.
    /// 0 = defaultMemoryBudgetMib().
    std::uint64_t memory_budget_mib = 0;
    /// Side of the boxes the grid is voxelized in, one after the other (rounded up to a
    /// multiple of 8); 0 = from the memory budget (the whole grid when it fits).
    int tile_size = 0;
    AttributeSet attributes;           ///< what to compute beside the occupancy
    GlOptions gl;                      ///< the GL methods' options
    HybridOptions hybrid;              ///< the hybrid method's
    TessellationOptions tessellation;  ///< the tessellation's
    SolidOptions solid;                ///< solid mode's
    SdfOptions sdf;                    ///< the sdf attribute's

    /// The budget in MiB, 0 resolved to defaultMemoryBudgetMib().
    std::uint64_t memoryBudgetMib() const { return memory_budget_mib ? memory_budget_mib : defaultMemoryBudgetMib(); }
    std::uint64_t memoryBudgetBytes() const { return memoryBudgetMib() << 20; }  ///< the budget in bytes
};

/// How writeVdb (hyvox/vdb.h) writes a result: output policy, which never changes the voxels.
/// Schema options too: "threads" and "memory_budget_mib" are a voxelization's and a write's,
/// "durable_write" a write's alone.
struct WriteOptions {
    int threads = 0;  ///< CPU threads building and serializing the grids; 0 = all cores
    /// Output files (.vdb, stats JSON) synced to disk before their write returns (fsync of the
    /// file and its folder): they then survive a power loss too. Off: the atomic rename alone
    /// (no half-written file whatever happens to hyvox), as OpenVDB and Blender write
    /// (src/os/atomic_file.h says why).
    bool durable = false;
    /// What the grids being built may hold beside the result they are made from (MiB);
    /// 0 = defaultMemoryBudgetMib().
    std::uint64_t memory_budget_mib = 0;

    /// The budget in MiB, 0 resolved to defaultMemoryBudgetMib().
    std::uint64_t memoryBudgetMib() const { return memory_budget_mib ? memory_budget_mib : defaultMemoryBudgetMib(); }
    std::uint64_t memoryBudgetBytes() const { return memoryBudgetMib() << 20; }  ///< the budget in bytes
};

}  // namespace hyvox
