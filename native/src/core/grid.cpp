// SPDX-License-Identifier: GPL-3.0-or-later
#include "hyvox/grid.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "hyvox/errors.h"

namespace hyvox {

GridSpec makeGrid(const Bounds& mesh_bounds, const GridOptions& options) {
    const Bounds bounds = options.bounds.value_or(mesh_bounds);
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(bounds.min[a]) || !std::isfinite(bounds.max[a]) || bounds.max[a] < bounds.min[a])
            throw InvalidInput("grid bounds are invalid (max < min or not finite)");
    if (options.padding < 0 || options.padding > 1024)
        throw InvalidInput("padding must be between 0 and 1024 voxels, got " + std::to_string(options.padding));

    std::array<double, 3> extent{};
    for (int a = 0; a < 3; ++a) extent[a] = bounds.max[a] - bounds.min[a];
    const double longest = std::max({extent[0], extent[1], extent[2]});

    GridSpec grid;
    if (options.voxel_size) {
        const double s = *options.voxel_size;
        if (!(s > 0.0) || !std::isfinite(s))
            throw InvalidInput("voxel size must be a positive finite number, got " + std::to_string(s));
        grid.voxel_size = s;
    } else {
        if (options.resolution < 1 || options.resolution > kMaxResolution)
            throw InvalidInput("resolution must be between 1 and " + std::to_string(kMaxResolution) + ", got " +
                               std::to_string(options.resolution));
        if (!(longest > 0.0))
            throw InvalidInput("the mesh has zero extent; give a voxel size instead of a resolution");
        grid.voxel_size = longest / options.resolution;
    }

    const std::array<double, 3> origin = options.origin.value_or(bounds.min);
    for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(origin[a])) throw InvalidInput("grid origin is not finite");
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
