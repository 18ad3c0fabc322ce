// SPDX-License-Identifier: GPL-3.0-or-later
// Section 4.1's six-direction ray-marching watertightness test (hyvox/accuracy.h).
#include <algorithm>
#include <cmath>
#include <limits>

#include "accuracy/same_dims.h"
#include "hyvox/accuracy.h"

namespace hyvox {

using accuracy::requireSameDims;

namespace {

// Where the centre lines of the columns along `axis` first and last meet the mesh, in voxel
// units along the axis (NaN = never): each triangle is tested against the column centres
// inside its projected bounding box, in double precision.
void castColumns(const ValidatedMesh& mesh, const GridSpec& grid, int axis, std::vector<double>& first,
                 std::vector<double>& last) {
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    const int n1 = grid.dims[a1], n2 = grid.dims[a2];
    const double nan = std::numeric_limits<double>::quiet_NaN();
    first.assign(std::size_t(n1) * n2, nan);
    last.assign(std::size_t(n1) * n2, nan);
    for (std::uint32_t t : mesh.usable) {
        const std::array<std::array<double, 3>, 3> p{grid.toVoxel(mesh.vertex(t, 0)), grid.toVoxel(mesh.vertex(t, 1)),
                                                     grid.toVoxel(mesh.vertex(t, 2))};
        // Signed doubled area in the (a1, a2) projection; edge-on triangles meet no centre line.
        const double area =
            (p[1][a1] - p[0][a1]) * (p[2][a2] - p[0][a2]) - (p[2][a1] - p[0][a1]) * (p[1][a2] - p[0][a2]);
        if (area == 0.0) continue;
        const double lo1 = std::min({p[0][a1], p[1][a1], p[2][a1]}), hi1 = std::max({p[0][a1], p[1][a1], p[2][a1]});
        const double lo2 = std::min({p[0][a2], p[1][a2], p[2][a2]}), hi2 = std::max({p[0][a2], p[1][a2], p[2][a2]});
        const int u0 = std::max(0, int(std::ceil(lo1 - 0.5))), u1 = std::min(n1 - 1, int(std::floor(hi1 - 0.5)));
        const int v0 = std::max(0, int(std::ceil(lo2 - 0.5))), v1 = std::min(n2 - 1, int(std::floor(hi2 - 0.5)));
        for (int u = u0; u <= u1; ++u)
            for (int v = v0; v <= v1; ++v) {
                const double x = u + 0.5, y = v + 0.5;
                auto edge = [&](int i, int j) {
                    return (p[j][a1] - p[i][a1]) * (y - p[i][a2]) - (p[j][a2] - p[i][a2]) * (x - p[i][a1]);
                };
                double w0 = edge(1, 2) / area, w1 = edge(2, 0) / area, w2 = edge(0, 1) / area;
                if (w0 < 0 || w1 < 0 || w2 < 0) continue;
                const double depth = w0 * p[0][axis] + w1 * p[1][axis] + w2 * p[2][axis];
                const std::size_t column = std::size_t(u) * n2 + v;
                if (!(first[column] <= depth)) first[column] = depth;
                if (!(last[column] >= depth)) last[column] = depth;
            }
    }
}

}  // namespace

WatertightReport rayMarchWatertightness(const BitGrid& result, const BitGrid& conservative, const ValidatedMesh& mesh,
                                        const GridSpec& grid) {
    requireSameDims(result, conservative);
    if (grid.dims != result.dims()) throw InvalidInput("accuracy: the grid and the voxel grids have different dims");
    const auto& dims = result.dims();
    WatertightReport report;
    std::vector<double> first, last;
    for (int axis = 0; axis < 3; ++axis) {
        const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
        const int length = dims[axis];
        castColumns(mesh, grid, axis, first, last);
        for (int direction : {+1, -1})
            for (int u = 0; u < dims[a1]; ++u)
                for (int v = 0; v < dims[a2]; ++v) {
                    ++report.rays;
                    const double depth = (direction > 0 ? first : last)[std::size_t(u) * dims[a2] + v];
                    if (std::isnan(depth) || depth < 0 || depth > length) {  // meets no surface in the grid
                        ++report.passed;
                        continue;
                    }
                    // Voxel `step` along the ray in grid `g`.
                    auto at = [&](const BitGrid& g, int step) {
                        std::array<int, 3> c{};
                        c[axis] = direction > 0 ? step : length - 1 - step;
                        c[a1] = u;
                        c[a2] = v;
                        return g.test(c[0], c[1], c[2]);
                    };
                    const int cell = std::min(length - 1, int(std::floor(depth)));
                    const int crossing = direction > 0 ? cell : length - 1 - cell;
                    int end = crossing;  // one past the conservative run from the crossing on
                    while (end < length && at(conservative, end)) ++end;
                    const int limit = std::min(length - 1, std::max(end, crossing + 1));
                    int hit = 0;
                    while (hit <= limit && !at(result, hit)) ++hit;
                    report.passed += hit <= limit ? 1 : 0;
                }
    }
    return report;
}

WatertightReport rayMarchWatertightness(const SparseGrid& result, const SparseGrid& conservative,
                                        const ValidatedMesh& mesh, const GridSpec& grid) {
    return rayMarchWatertightness(result.toBitGrid(), conservative.toBitGrid(), mesh, grid);
}

}  // namespace hyvox
