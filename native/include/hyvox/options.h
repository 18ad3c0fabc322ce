// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "hyvox/grid.h"

namespace hyvox {

// conservative: every voxel whose closed box meets the triangle (26-separating).
// thin: Schwarz & Seidel's 6-separating surface (fewer voxels, still no 6-connected leak).
enum class Mode { Conservative, Thin };

enum class Method {
    Cpu,           // factored triangle/voxel test, multi-threaded (fallback without a GPU)
    Reference,     // brute-force double-precision SAT: the test oracle, slow on purpose
    Triangle,      // GL triangle-parallel
    Fragment,      // GL fragment-parallel
    Hybrid,        // GL hybrid (classifier + both)
    Tessellation,  // GL adaptive point tessellation (approximate, multi-valued)
};

const char* toString(Mode mode);
const char* toString(Method method);
// Parse "conservative"/"thin" and "cpu"/"reference"/...; throw InvalidInput naming the choices.
Mode parseMode(const std::string& text);
Method parseMethod(const std::string& text);

struct GlOptions {
    std::string device;  // "" = auto (hardware first, then software); "software"; or an index "0", "1"...
    std::string shader_dir;  // "" = embedded shaders (HYVOX_SHADER_DIR env var also overrides)
};

struct HybridOptions {
    // Triangles whose projected area on their dominant plane exceeds this many voxel units²
    // are rasterized (fragment-parallel); the rest are voxelized per triangle.
    // Negative = auto: a bracketing search over timed runs, cached per mesh and resolution.
    double cutoff = -1.0;
};

// A grey height image in memory: width × height values, row 0 = the image's top row (as in
// a PNG file), typically 0..1.
struct HeightImage {
    int width = 0;
    int height = 0;
    std::vector<float> values;
    bool empty() const { return values.empty(); }
};

struct TessellationOptions {
    double gamma = 1.0;  // safety factor γ of Eq. 1
    bool pn_triangles = false;
    // Displacement (section 3.3), Blender Displace modifier semantics: each point moves along
    // the interpolated vertex normal by (texel - midlevel) * strength world units, the texel
    // sampled bilinearly (clamped at the edges) at the interpolated UV; needs MeshView::uvs.
    // Used when displacement_image (an 8/16-bit PNG path) or displacement_pixels is given.
    // The grid is laid out from the undisplaced mesh: points that leave it are dropped and
    // counted (stats.metrics["points_clipped"]); give GridOptions bounds or padding for room.
    std::string displacement_image;
    HeightImage displacement_pixels;  // used when displacement_image is empty
    double displacement_strength = 1.0;
    double displacement_midlevel = 0.5;
    bool counts = true;               // also fill VoxelizeResult::counts (points per voxel)
    // Also voxelize with the exact cpu method and report bias / false voxels / watertightness
    // in stats.metrics (slow: for tests and benchmarks).
    bool measure_accuracy = false;
};

struct VoxelizeOptions {
    GridOptions grid;
    Mode mode = Mode::Conservative;
    Method method = Method::Cpu;
    int threads = 0;                                 // CPU threads; 0 = all cores
    std::uint64_t memory_budget = 4ull << 30;        // bytes for the bit grid; bigger grids are refused
    GlOptions gl;
    HybridOptions hybrid;
    TessellationOptions tessellation;
};

}  // namespace hyvox
