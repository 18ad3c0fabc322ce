// SPDX-License-Identifier: GPL-3.0-or-later
#include "hyvox/grid.h"

#include <algorithm>
#include <cmath>
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
    GridSpec grid;
    if (options.voxel_size) {
        grid.voxel_size = *options.voxel_size;
    } else {
        if (!(longest > 0.0))
            throw InvalidInput("the mesh has zero extent; give a voxel size instead of a resolution");
        grid.voxel_size = longest / options.resolution;
    }
    const std::array<double, 3> origin = options.origin.value_or(bounds.min);
    for (int a = 0; a < 3; ++a) {
        // The grid starts at the origin and must reach the bounds max; ceil of the exact ratio,
        // so a box whose size is a multiple of the voxel size gets exactly that many voxels.
        const double span = std::max(0.0, bounds.max[a] - origin[a]);
        const double cells = std::ceil(span / grid.voxel_size);
        if (cells > double(kMaxResolution))
            throw InvalidInput("the grid would need " + std::to_string(cells) + " voxels along an axis; at most " +
                               std::to_string(kMaxResolution) + " are allowed (use a larger voxel size)");
        grid.dims[a] = std::max(1, int(cells)) + 2 * options.padding;
        grid.origin[a] = origin[a] - options.padding * grid.voxel_size;
    }
    return grid;
}

}  // namespace hyvox
