// SPDX-License-Identifier: GPL-3.0-or-later
#include "hyvox/grid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "hyvox/errors.h"
#include "hyvox/option_schema.h"

namespace hyvox {
namespace {

// makeGrid is public on its own: its options get the schema's checks and messages, the same
// voxelize() applies to every option (limits are declared there only).
void checkGridOptions(const GridOptions& grid) {
    VoxelizeOptions options;
    options.grid = grid;
    for (const OptionSpec& spec : optionSchema())
        if (std::strcmp(spec.group, "grid") == 0) checkOption(spec, spec.get(options));
}

// A number for a message: "2.56e+302", not the 300 digits std::to_string writes.
std::string shortNumber(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", value);
    return text;
}

// The GL methods compute in single precision in voxel units: a mesh that is a speck inside
// one voxel (below ~1e-19 voxels, where squares of its coordinates underflow) vanishes there
// while the CPU methods still mark its voxel. Far above any meaningful use (the whole mesh in
// one voxel already at ratio 1), this bound keeps every method's answer the same.
constexpr double kMaxVoxelsPerMeshSide = 1e6;

void refuseSpeckMesh(double longest_mesh_side, double voxel_size, bool from_bounds) {
    if (!(longest_mesh_side > 0.0) || voxel_size <= kMaxVoxelsPerMeshSide * longest_mesh_side) return;
    const std::string why = from_bounds ? "bounds (a voxel size of " + shortNumber(voxel_size) + " at this resolution)"
                                        : "voxel_size " + shortNumber(voxel_size);
    throw InvalidInput(why + " is more than " + shortNumber(kMaxVoxelsPerMeshSide) +
                       " times the mesh's longest side (" + shortNumber(longest_mesh_side) +
                       "): the mesh would be a speck in one voxel, below what the GPU methods resolve; use a "
                       "voxel size of at most " +
                       shortNumber(kMaxVoxelsPerMeshSide * longest_mesh_side));
}

// A whole multiple of s at or below x: floor(x / s) · s, one lower where x / s rounded up to
// the next whole number (0.7 / 0.1 is 6.999999999999999, but 0.3 / 0.1 rounds the other way)
// and the product lands above x. (A quotient that rounded down floors one voxel lower: still
// on the lattice, with one more empty layer.)
double snapDown(double x, double s) {
    double k = std::floor(x / s);
    if (k * s > x) k -= 1;
    return k * s;
}

}  // namespace

std::string GridSpec::dimsText() const {
    return std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" + std::to_string(dims[2]);
}

GridSpec makeGrid(const Bounds& mesh_bounds, const GridOptions& options) {
    checkGridOptions(options);
    const Bounds bounds = options.bounds.value_or(mesh_bounds);
    std::array<double, 3> extent{};
    for (int a = 0; a < 3; ++a) extent[a] = bounds.max[a] - bounds.min[a];
    const double longest = std::max({extent[0], extent[1], extent[2]});
    // Finite corners can still be farther apart than a double holds (-1e308 .. 1e308).
    if (!std::isfinite(longest))
        throw InvalidInput("bounds span more than a double can hold (a side of " + shortNumber(longest) +
                           "); give a smaller box");
    GridSpec grid;
    if (options.voxel_size) {
        grid.voxel_size = *options.voxel_size;
    } else {
        if (!(longest > 0.0)) throw InvalidInput("the mesh has zero extent; give a voxel size instead of a resolution");
        grid.voxel_size = longest / options.resolution;
    }
    double longest_mesh_side = 0;
    for (int a = 0; a < 3; ++a)
        longest_mesh_side = std::max(longest_mesh_side, mesh_bounds.max[a] - mesh_bounds.min[a]);
    refuseSpeckMesh(longest_mesh_side, grid.voxel_size, !options.voxel_size);
    std::array<double, 3> origin = options.origin.value_or(bounds.min);
    if (options.snap_origin && !options.origin)
        for (int a = 0; a < 3; ++a) origin[a] = snapDown(origin[a], grid.voxel_size);
    for (int a = 0; a < 3; ++a) {
        // The grid starts at the origin and must reach the bounds max; ceil of the exact ratio,
        // so a box whose size is a multiple of the voxel size gets exactly that many voxels.
        const double span = std::max(0.0, bounds.max[a] - origin[a]);
        const double cells = std::ceil(span / grid.voxel_size);
        if (cells > double(kMaxResolution))
            throw InvalidInput("the grid would need " + shortNumber(cells) + " voxels along an axis; at most " +
                               std::to_string(kMaxResolution) + " are allowed (use a larger voxel size)");
        grid.dims[a] = std::max(1, int(cells)) + 2 * options.padding;
        grid.origin[a] = origin[a] - options.padding * grid.voxel_size;
    }
    return grid;
}

}  // namespace hyvox
