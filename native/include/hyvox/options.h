// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The options of one voxelization as plain structs. Their names, defaults, limits, units and
// help live in one place, the schema (hyvox/option_schema.h), from which every front door
// (CLI, Python, the Blender add-on) is derived; voxelize() checks every field against it.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "hyvox/grid.h"

namespace hyvox {

// conservative: every voxel whose closed box meets the triangle (26-separating).
// thin: Schwarz & Seidel's 6-separating surface (fewer voxels, still no 6-connected leak).
// solid: the conservative surface plus every voxel whose centre is inside (InsideRule).
enum class Mode { Conservative, Thin, Solid };

// How solid mode decides that a voxel centre is inside (src/solid/).
// parity: an odd number of surface crossings on the ray from the centre along -z (exact for
// closed meshes). winding: generalized winding number >= 0.5 (holes, flipped or duplicated
// faces, nested shells). auto: the winding number, counted exactly by the signed crossings of
// the parity rays when the mesh is closed and consistently oriented (as fast as parity, and
// right where closed shells overlap), else by fast winding numbers; the finding is reported
// in Stats::solid.
enum class InsideRule { Auto, Parity, Winding };

enum class Method {
    Cpu,           // factored triangle/voxel test, multi-threaded (fallback without a GPU)
    Reference,     // brute-force double-precision SAT: the test oracle, slow on purpose
    Triangle,      // GL triangle-parallel
    Fragment,      // GL fragment-parallel
    Hybrid,        // GL hybrid (classifier + both)
    Tessellation,  // GL adaptive point tessellation (approximate, multi-valued)
};

// The schema's names of each value ("conservative", "cpu", ...), and back: parse* throws
// InvalidInput naming the choices.
const char* toString(Mode mode);
const char* toString(Method method);
const char* toString(InsideRule rule);
Mode parseMode(const std::string& text);
Method parseMethod(const std::string& text);
InsideRule parseInsideRule(const std::string& text);
std::vector<const char*> modeNames();    // in enum order
std::vector<const char*> methodNames();
std::vector<const char*> insideRuleNames();

// Whether a method computes attribute voxels (colour, normal): the exact methods (cpu and
// reference clip on the CPU, triangle/fragment/hybrid on the GPU), and the tessellation by
// averaging its points' values. Every method does now; front doors ask this, not a list.
bool computesAttributes(Method method);

struct GlOptions {
    std::string device;      // "" = auto (hardware first, then software); "software"; or an index "0", "1"...
    std::string shader_dir;  // "" = the shaders embedded in the library; else a copy of shaders/ to read
    // Largest bit-grid tile in bytes; 0 = one shader storage block (the device's limit).
    // Smaller values force tiling (tests of the tile borders).
    std::uint64_t tile_bytes = 0;
    // Largest list of (voxel, triangle) pairs, in bytes, of the triangle/fragment/hybrid
    // attribute pass (its pieces take 20 bytes each); 0 = one shader storage block. Smaller
    // values make tiles whose pairs do not fit run as halves (tests of that halving).
    std::uint64_t pair_list_bytes = 0;
    // Time GL passes by the wall clock around glFinish instead of GPU timer queries
    // (always on for Mesa's llvmpipe, whose timer queries miss compute work).
    bool wall_timing = false;
    // Tessellation: one instance per patch instead of one plain patch draw (always on for
    // llvmpipe, which assembles long patch draws wrongly).
    bool tess_instanced = false;
};

struct HybridOptions {
    // Triangles whose projected area on their dominant plane exceeds this many voxel units²
    // are rasterized (fragment-parallel); the rest are voxelized per triangle.
    // Negative = auto: a bracketing search over timed runs, cached per mesh and resolution.
    double cutoff = -1.0;
};

// A grey height image in memory: width × height values, row 0 = the image's top row (as in
// a PNG file), typically 0..1. Data, not an option: passed beside the schema's options.
struct HeightImage {
    int width = 0;
    int height = 0;
    std::vector<float> values;
    bool empty() const { return values.empty(); }
};

struct TessellationOptions {
    // Safety factor γ of Eq. 1 (edge factor = γ · the edge's largest per-axis extent in voxels).
    // 2, not the paper's 1: at γ = 1 one point per micro-triangle leaves pinholes that let a
    // flood from outside fill a closed mesh (the Buddha, armadillo and Spot at 256). From 2 on,
    // every closed mesh measured is sealed with a margin; README, "Watertight by default".
    double gamma = 2.0;
    bool pn_triangles = false;
    // Displacement (section 3.3), Blender Displace modifier semantics: each point moves along
    // the interpolated vertex normal by (texel - midlevel) * strength world units, the texel
    // sampled bilinearly (clamped at the edges) at the interpolated UV; needs MeshView::uvs.
    // Used when displacement_image (an 8/16-bit PNG path) or displacement_pixels is given.
    // The grid is laid out from the undisplaced mesh: points that leave it are dropped and
    // counted (TessellationStats::points_clipped); give GridOptions bounds or padding for room.
    std::string displacement_image;
    HeightImage displacement_pixels;  // used when displacement_image is empty
    double displacement_strength = 1.0;
    double displacement_midlevel = 0.5;
    bool counts = true;  // also fill VoxelizeResult::counts (points per voxel)
};

struct SolidOptions {
    InsideRule inside = InsideRule::Auto;
    // Fast winding numbers (Barill et al. 2018): a cluster of triangles is replaced by its
    // expansion when the query is farther than beta times the cluster's radius. Larger is
    // more accurate and slower.
    double winding_beta = 2.0;
};

// The memory budget a run has when memory_budget_mib is 0: half of this machine's physical
// memory, or of the memory limit of the cgroup this process runs in when that is smaller
// (a container's), in MiB, at least 256.
std::uint64_t defaultMemoryBudgetMib();

struct VoxelizeOptions {
    GridOptions grid;
    Mode mode = Mode::Conservative;
    Method method = Method::Cpu;
    int threads = 0;                        // CPU threads; 0 = all cores
    // What the run may hold beside the mesh it is given (MiB): every buffer of the passes it
    // runs and of the .vdb it writes; a run estimated to need more is refused before any work.
    // 0 = defaultMemoryBudgetMib().
    std::uint64_t memory_budget_mib = 0;
    // Side of the boxes the grid is voxelized in, one after the other (rounded up to a
    // multiple of 8); 0 = from the memory budget (the whole grid when it fits).
    int tile_size = 0;
    // Attribute voxels to compute beside the occupancy: a comma list of "color" and "normal"
    // (hyvox/attribute_grid.h); "" = none.
    std::string attributes;
    // Output files (.vdb, stats JSON) synced to disk before their write returns (fsync of the
    // file and its folder): they then survive a power loss too. Off: the atomic rename alone
    // (no half-written file whatever happens to hyvox), as OpenVDB and Blender write
    // (src/io/atomic_file.h says why).
    bool durable_write = false;
    GlOptions gl;
    HybridOptions hybrid;
    TessellationOptions tessellation;
    SolidOptions solid;

    std::uint64_t memoryBudgetMib() const { return memory_budget_mib ? memory_budget_mib : defaultMemoryBudgetMib(); }
    std::uint64_t memoryBudgetBytes() const { return memoryBudgetMib() << 20; }
};

}  // namespace hyvox
