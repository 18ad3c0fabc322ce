// SPDX-License-Identifier: GPL-3.0-or-later
#include "support/voxel_checks.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <sstream>
#include <unordered_map>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "reference/reference_overlap.h"

namespace hyvox::test {
namespace {

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::uint64_t key(const Voxel& v) {
    return (std::uint64_t(std::uint32_t(v[0])) << 42) | (std::uint64_t(std::uint32_t(v[1])) << 21) | std::uint32_t(v[2]);
}

}  // namespace

std::string Comparison::summary() const {
    std::ostringstream out;
    out << "cpu " << cpu_voxels << " voxels (" << cpu_ms << " ms), reference " << reference_voxels << " ("
        << reference_ms << " ms); disagreements: cpu-only " << cpu_only << ", reference-only " << reference_only
        << ", of which touches " << touches << ", unexplained " << unexplained.size() << " (check " << check_ms
        << " ms)";
    return out.str();
}

Comparison compareWithReference(const MeshView& mesh, VoxelizeOptions options, double eps) {
    Comparison cmp;
    auto start = std::chrono::steady_clock::now();
    options.method = Method::Cpu;
    const VoxelizeResult cpu = voxelize(mesh, options);
    cmp.cpu_ms = msSince(start);
    start = std::chrono::steady_clock::now();
    options.method = Method::Reference;
    const VoxelizeResult ref = voxelize(mesh, options);
    cmp.reference_ms = msSince(start);
    cmp.cpu_voxels = cpu.occupancy.count();
    cmp.reference_voxels = ref.occupancy.count();
    start = std::chrono::steady_clock::now();

    // The disagreements, as a bit grid (for lookups) and a list.
    BitGrid diff(cpu.grid.dims);
    for (std::size_t w = 0; w < diff.wordCount(); ++w) diff.data()[w] = cpu.occupancy.data()[w] ^ ref.occupancy.data()[w];
    std::vector<Voxel> voxels;
    for (const auto& c : diff.coords()) {
        voxels.push_back({c[0], c[1], c[2]});
        if (cpu.occupancy.test(c[0], c[1], c[2]))
            ++cmp.cpu_only;
        else
            ++cmp.reference_only;
    }
    if (voxels.empty()) {
        cmp.check_ms = msSince(start);
        return cmp;
    }

    std::unordered_map<std::uint64_t, std::size_t> index;
    for (std::size_t n = 0; n < voxels.size(); ++n) index[key(voxels[n])] = n;
    std::vector<std::atomic<bool>> grown(voxels.size()), shrunk(voxels.size());
    for (auto& g : grown) g = false;
    for (auto& s : shrunk) s = false;

    const ValidatedMesh validated = validate(mesh);
    const GridSpec& grid = cpu.grid;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, validated.usable.size(), 512),
                      [&](const tbb::blocked_range<std::size_t>& chunk) {
                          for (std::size_t t = chunk.begin(); t != chunk.end(); ++t) {
                              const auto tri = reference::voxelSpaceTriangle(validated, validated.usable[t], grid);
                              const auto range = reference::candidateVoxels(tri, grid.dims, eps);
                              if (range.empty()) continue;
                              for (int i = range.lo[0]; i <= range.hi[0]; ++i)
                                  for (int j = range.lo[1]; j <= range.hi[1]; ++j)
                                      for (int k = range.lo[2]; k <= range.hi[2]; ++k) {
                                          if (!diff.test(i, j, k)) continue;
                                          const std::size_t n = index.at(key({i, j, k}));
                                          const auto touch = reference::overlapWithin(tri, {i, j, k}, options.mode, eps);
                                          if (touch.grown) grown[n] = true;
                                          if (touch.shrunk) shrunk[n] = true;
                                      }
                          }
                      });
    for (std::size_t n = 0; n < voxels.size(); ++n) {
        if (grown[n] && !shrunk[n])
            ++cmp.touches;
        else
            cmp.unexplained.push_back(voxels[n]);
    }
    cmp.check_ms = msSince(start);
    return cmp;
}

std::uint64_t countHoles(const MeshView& mesh, const VoxelizeResult& result, std::uint64_t* samples,
                         std::vector<std::array<double, 3>>* first_holes, double slack) {
    const ValidatedMesh validated = validate(mesh);
    const GridSpec& grid = result.grid;
    const BitGrid& bits = result.occupancy;
    std::atomic<std::uint64_t> holes{0}, total{0};
    std::mutex mutex;

    // Is the voxel-space point p inside the closed box of some set voxel (within slack)?
    auto covered = [&](const std::array<double, 3>& p) {
        int lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::max(0, int(std::ceil(p[a] - slack)) - 1);
            hi[a] = std::min(grid.dims[a] - 1, int(std::floor(p[a] + slack)));
        }
        for (int i = lo[0]; i <= hi[0]; ++i)
            for (int j = lo[1]; j <= hi[1]; ++j)
                for (int k = lo[2]; k <= hi[2]; ++k)
                    if (bits.test(i, j, k)) return true;
        return false;
    };

    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, validated.usable.size(), 256),
                      [&](const tbb::blocked_range<std::size_t>& chunk) {
                          std::uint64_t local_holes = 0, local_total = 0;
                          for (std::size_t t = chunk.begin(); t != chunk.end(); ++t) {
                              std::array<std::array<double, 3>, 3> v;
                              for (int c = 0; c < 3; ++c) {
                                  const auto p = validated.vertex(validated.usable[t], c);
                                  for (int a = 0; a < 3; ++a) v[c][a] = (double(p[a]) - grid.origin[a]) / grid.voxel_size;
                              }
                              double longest = 0;
                              for (int c = 0; c < 3; ++c) {
                                  double len2 = 0;
                                  for (int a = 0; a < 3; ++a) len2 += (v[(c + 1) % 3][a] - v[c][a]) * (v[(c + 1) % 3][a] - v[c][a]);
                                  longest = std::max(longest, std::sqrt(len2));
                              }
                              // Spacing <= 1/2 voxel along every edge direction of the lattice.
                              const int n = std::max(2, int(std::ceil(2.0 * longest)));
                              for (int a = 0; a <= n; ++a)
                                  for (int b = 0; a + b <= n; ++b) {
                                      // v0 + (a/n)(v1 - v0) + (b/n)(v2 - v0): exact on axes where the
                                      // triangle is flat, so faces on voxel planes stay on them.
                                      std::array<double, 3> p;
                                      for (int x = 0; x < 3; ++x)
                                          p[x] = v[0][x] + (double(a) / n) * (v[1][x] - v[0][x]) +
                                                 (double(b) / n) * (v[2][x] - v[0][x]);
                                      // Samples outside the grid are clipped geometry: nothing to cover.
                                      bool in_grid = true;
                                      for (int x = 0; x < 3; ++x)
                                          in_grid &= p[x] >= -slack && p[x] <= grid.dims[x] + slack;
                                      if (!in_grid) continue;
                                      ++local_total;
                                      if (covered(p)) continue;
                                      ++local_holes;
                                      if (first_holes) {
                                          std::lock_guard<std::mutex> lock(mutex);
                                          if (first_holes->size() < 10) first_holes->push_back(p);
                                      }
                                  }
                          }
                          holes += local_holes;
                          total += local_total;
                      });
    if (samples) *samples = total;
    return holes;
}

}  // namespace hyvox::test
