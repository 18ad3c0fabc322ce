// SPDX-License-Identifier: GPL-3.0-or-later
#include "test_hybrid_oracle.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <deque>
#include <sstream>
#include <unordered_map>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "reference/reference_overlap.h"

namespace hyvox::test {
namespace {

std::uint64_t key(int i, int j, int k) {
    return (std::uint64_t(std::uint32_t(i)) << 42) | (std::uint64_t(std::uint32_t(j)) << 21) | std::uint32_t(k);
}

}  // namespace

std::string OracleComparison::summary() const {
    std::ostringstream out;
    out << "result " << result_voxels << " voxels, oracle " << oracle_voxels << "; result-only " << result_only
        << ", oracle-only " << oracle_only << ", touches " << touches << ", unexplained " << unexplained.size();
    for (std::size_t n = 0; n < std::min<std::size_t>(5, unexplained.size()); ++n)
        out << (n ? " " : " e.g. ") << "(" << unexplained[n][0] << "," << unexplained[n][1] << "," << unexplained[n][2]
            << ")";
    return out.str();
}

OracleComparison compareToOracle(const MeshView& mesh, Mode mode, const VoxelizeResult& result,
                                 const VoxelizeResult& oracle, double eps) {
    OracleComparison cmp;
    cmp.result_voxels = result.occupancy.count();
    cmp.oracle_voxels = oracle.occupancy.count();
    BitGrid diff(result.grid.dims);
    for (std::size_t w = 0; w < diff.wordCount(); ++w)
        diff.data()[w] = result.occupancy.data()[w] ^ oracle.occupancy.data()[w];
    const auto voxels = diff.coords();
    for (const auto& v : voxels)
        ++(result.occupancy.test(v[0], v[1], v[2]) ? cmp.result_only : cmp.oracle_only);
    if (voxels.empty())
        return cmp;

    // A disagreement is a touch iff some triangle meets the eps-grown voxel and none meets
    // the eps-shrunk one (the reference's own rule, in double precision).
    std::unordered_map<std::uint64_t, std::size_t> index;
    for (std::size_t n = 0; n < voxels.size(); ++n)
        index[key(voxels[n][0], voxels[n][1], voxels[n][2])] = n;
    std::vector<std::atomic<bool>> grown(voxels.size()), shrunk(voxels.size());
    const ValidatedMesh validated = validate(mesh);
    const GridSpec& grid = result.grid;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, validated.usable.size(), 512),
                      [&](const tbb::blocked_range<std::size_t>& chunk) {
                          for (std::size_t t = chunk.begin(); t != chunk.end(); ++t) {
                              const auto tri = reference::voxelSpaceTriangle(validated, validated.usable[t], grid);
                              const auto range = reference::candidateVoxels(tri, grid.dims, eps);
                              if (range.empty())
                                  continue;
                              for (int i = range.lo[0]; i <= range.hi[0]; ++i)
                                  for (int j = range.lo[1]; j <= range.hi[1]; ++j)
                                      for (int k = range.lo[2]; k <= range.hi[2]; ++k) {
                                          if (!diff.test(i, j, k))
                                              continue;
                                          const std::size_t n = index.at(key(i, j, k));
                                          const auto touch = reference::overlapWithin(tri, {i, j, k}, mode, eps);
                                          if (touch.grown)
                                              grown[n] = true;
                                          if (touch.shrunk)
                                              shrunk[n] = true;
                                      }
                          }
                      });
    for (std::size_t n = 0; n < voxels.size(); ++n) {
        if (grown[n] && !shrunk[n])
            ++cmp.touches;
        else
            cmp.unexplained.push_back({voxels[n][0], voxels[n][1], voxels[n][2]});
    }
    return cmp;
}

std::uint64_t countSixLeaks(const MeshView& mesh, const VoxelizeResult& result, std::uint64_t* inside_count) {
    const GridSpec& grid = result.grid;
    const auto& d = grid.dims;
    const ValidatedMesh validated = validate(mesh);
    // Crossings of the +x rays through voxel centres (j + 1/2, k + 1/2) with the surface.
    std::vector<std::vector<double>> crossings(static_cast<std::size_t>(d[1]) * d[2]);
    for (std::uint32_t t : validated.usable) {
        const auto tri = reference::voxelSpaceTriangle(validated, t, grid);
        double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
        for (const auto& p : tri)
            for (int a = 0; a < 2; ++a) {
                lo[a] = std::min(lo[a], p[a + 1]);
                hi[a] = std::max(hi[a], p[a + 1]);
            }
        for (int j = std::max(0, int(std::ceil(lo[0] - 0.5))); j <= std::min(d[1] - 1, int(std::floor(hi[0] - 0.5)));
             ++j)
            for (int k = std::max(0, int(std::ceil(lo[1] - 0.5)));
                 k <= std::min(d[2] - 1, int(std::floor(hi[1] - 0.5))); ++k) {
                const double y = j + 0.5, z = k + 0.5;
                double w[3];
                for (int c = 0; c < 3; ++c) {
                    const auto& a = tri[(c + 1) % 3];
                    const auto& b = tri[(c + 2) % 3];
                    w[c] = (a[1] - y) * (b[2] - z) - (a[2] - z) * (b[1] - y);
                }
                const bool pos = w[0] >= 0 && w[1] >= 0 && w[2] >= 0, neg = w[0] <= 0 && w[1] <= 0 && w[2] <= 0;
                const double sum = w[0] + w[1] + w[2];
                if ((!pos && !neg) || sum == 0)
                    continue;
                double x = 0;
                for (int c = 0; c < 3; ++c)
                    x += w[c] / sum * tri[c][0];
                crossings[std::size_t(j) * d[2] + k].push_back(x);
            }
    }
    std::vector<char> inside(static_cast<std::size_t>(d[0]) * d[1] * d[2], 0);
    auto at = [&](int i, int j, int k) { return (std::size_t(i) * d[1] + j) * d[2] + k; };
    std::uint64_t inside_total = 0;
    for (int j = 0; j < d[1]; ++j)
        for (int k = 0; k < d[2]; ++k) {
            auto& xs = crossings[std::size_t(j) * d[2] + k];
            std::sort(xs.begin(), xs.end());
            for (int i = 0; i < d[0]; ++i) {
                const double x = i + 0.5;
                const auto before = std::lower_bound(xs.begin(), xs.end(), x) - xs.begin();
                if (before % 2 == 1) {
                    inside[at(i, j, k)] = 1;
                    ++inside_total;
                }
            }
        }
    if (inside_count)
        *inside_count = inside_total;

    // Flood the empty voxels from the grid's faces, 6-connected.
    std::vector<char> reached(inside.size(), 0);
    std::deque<std::array<int, 3>> queue;
    auto push = [&](int i, int j, int k) {
        if (i < 0 || j < 0 || k < 0 || i >= d[0] || j >= d[1] || k >= d[2])
            return;
        if (reached[at(i, j, k)] || result.occupancy.test(i, j, k))
            return;
        reached[at(i, j, k)] = 1;
        queue.push_back({i, j, k});
    };
    for (int i = 0; i < d[0]; ++i)
        for (int j = 0; j < d[1]; ++j)
            for (int k = 0; k < d[2]; ++k)
                if (i == 0 || j == 0 || k == 0 || i == d[0] - 1 || j == d[1] - 1 || k == d[2] - 1)
                    push(i, j, k);
    while (!queue.empty()) {
        const auto v = queue.front();
        queue.pop_front();
        push(v[0] + 1, v[1], v[2]);
        push(v[0] - 1, v[1], v[2]);
        push(v[0], v[1] + 1, v[2]);
        push(v[0], v[1] - 1, v[2]);
        push(v[0], v[1], v[2] + 1);
        push(v[0], v[1], v[2] - 1);
    }
    std::uint64_t leaks = 0;
    for (std::size_t n = 0; n < inside.size(); ++n)
        leaks += inside[n] && reached[n];
    return leaks;
}

}  // namespace hyvox::test
