// SPDX-License-Identifier: GPL-3.0-or-later
// The flood test of watertightness (hyvox/accuracy.h): 6-connected floods from outside the
// grid, one over the exact voxels' empty space and one over the result's.
#include <vector>

#include "accuracy/same_dims.h"
#include "hyvox/accuracy.h"

namespace hyvox {

using accuracy::requireSameDims;

namespace {

// 1 for every empty voxel of `bits` that a 6-connected path of empty voxels joins to the
// grid's faces (so to the space outside the grid); index (i·dy + j)·dz + k.
std::vector<char> reachedFromOutside(const BitGrid& bits) {
    const auto& d = bits.dims();
    const std::size_t sj = std::size_t(d[2]), si = std::size_t(d[1]) * d[2];
    std::vector<char> reached(si * std::size_t(d[0]), 0);
    // The voxels still to expand, as linear indices (8 bytes each: a 512³ grid's inside can
    // be 20M voxels deep in the stack). Depth-first: the same set as breadth-first.
    std::vector<std::size_t> stack;
    auto visit = [&](int i, int j, int k) {
        const std::size_t id = std::size_t(i) * si + std::size_t(j) * sj + std::size_t(k);
        if (reached[id] || bits.test(i, j, k)) return;
        reached[id] = 1;
        stack.push_back(id);
    };
    for (int i = 0; i < d[0]; ++i)
        for (int j = 0; j < d[1]; ++j)
            for (int k = 0; k < d[2]; ++k)
                if (i == 0 || j == 0 || k == 0 || i == d[0] - 1 || j == d[1] - 1 || k == d[2] - 1) visit(i, j, k);
    while (!stack.empty()) {
        const std::size_t id = stack.back();
        stack.pop_back();
        const int i = int(id / si), j = int(id % si / sj), k = int(id % sj);
        if (i > 0) visit(i - 1, j, k);
        if (i + 1 < d[0]) visit(i + 1, j, k);
        if (j > 0) visit(i, j - 1, k);
        if (j + 1 < d[1]) visit(i, j + 1, k);
        if (k > 0) visit(i, j, k - 1);
        if (k + 1 < d[2]) visit(i, j, k + 1);
    }
    return reached;
}

}  // namespace

SealReport floodFromOutside(const BitGrid& result, const BitGrid& exact) {
    requireSameDims(result, exact);
    const std::vector<char> outside_exact = reachedFromOutside(exact);
    const std::vector<char> outside_result = reachedFromOutside(result);
    const auto& d = exact.dims();
    SealReport report;
    std::size_t id = 0;
    for (int i = 0; i < d[0]; ++i)
        for (int j = 0; j < d[1]; ++j)
            for (int k = 0; k < d[2]; ++k, ++id) {
                const bool enclosed = !exact.test(i, j, k) && !outside_exact[id];
                report.enclosed += enclosed;
                report.leaked += enclosed && outside_result[id];
            }
    return report;
}

SealReport floodFromOutside(const SparseGrid& result, const SparseGrid& exact) {
    return floodFromOutside(result.toBitGrid(), exact.toBitGrid());
}

}  // namespace hyvox
