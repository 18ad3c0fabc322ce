// SPDX-License-Identifier: GPL-3.0-or-later
#include "support/voxel_checks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <deque>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/stopwatch.h"
#include "reference/reference_overlap.h"

namespace hyvox::test {
namespace {

std::uint64_t key(const Voxel& v) {
    return (std::uint64_t(std::uint32_t(v[0])) << 42) | (std::uint64_t(std::uint32_t(v[1])) << 21) |
        std::uint32_t(v[2]);
}

}  // namespace

std::string Comparison::summary() const {
    std::ostringstream out;
    out << "result " << result_voxels << " voxels";
    if (result_ms > 0) out << " (" << result_ms << " ms)";
    out << ", oracle " << oracle_voxels;
    if (oracle_ms > 0) out << " (" << oracle_ms << " ms)";
    out << "; disagreements: result-only " << result_only << ", oracle-only " << oracle_only << ", of which touches "
        << touches << ", unexplained " << unexplained.size() << " (" << unexplained_result_only
        << " result-only; check " << check_ms << " ms)";
    for (std::size_t n = 0; n < std::min<std::size_t>(5, unexplained.size()); ++n)
        out << (n ? " " : " e.g. ") << "(" << unexplained[n][0] << "," << unexplained[n][1] << "," << unexplained[n][2]
            << ")";
    return out.str();
}

Touch overlapWithin(const reference::Triangle& triangle, const Voxel& voxel, Mode mode, double eps) {
    return {reference::overlaps(triangle, voxel, mode, eps), reference::overlaps(triangle, voxel, mode, -eps)};
}

Comparison compareResults(const MeshView& mesh, Mode mode, const VoxelizeResult& result, const VoxelizeResult& oracle,
                          double eps) {
    // XOR-ing the bit words below is only meaningful (and in bounds) on the same grid.
    if (result.grid.dims != oracle.grid.dims || result.grid.origin != oracle.grid.origin ||
        result.grid.voxel_size != oracle.grid.voxel_size)
        throw std::invalid_argument("compareResults: the two results are on different grids");
    Comparison cmp;
    const Stopwatch watch;
    cmp.result_voxels = result.occupancy.count();
    cmp.oracle_voxels = oracle.occupancy.count();

    // The disagreements, as a bit grid (for lookups) and a list.
    BitGrid diff = result.occupancy.toBitGrid();
    const BitGrid oracle_bits = oracle.occupancy.toBitGrid();
    for (std::size_t w = 0; w < diff.wordCount(); ++w) diff.data()[w] ^= oracle_bits.data()[w];
    std::vector<Voxel> voxels;
    for (const auto& c : diff.coords()) {
        voxels.push_back({c[0], c[1], c[2]});
        ++(result.occupancy.test(c[0], c[1], c[2]) ? cmp.result_only : cmp.oracle_only);
    }
    if (voxels.empty()) {
        cmp.check_ms = watch.elapsedMs();
        return cmp;
    }

    std::unordered_map<std::uint64_t, std::size_t> index;
    for (std::size_t n = 0; n < voxels.size(); ++n) index[key(voxels[n])] = n;
    std::vector<std::atomic<bool>> grown(voxels.size()), shrunk(voxels.size());
    for (auto& g : grown) g = false;
    for (auto& s : shrunk) s = false;

    const ValidatedMesh validated = validate(mesh);
    const GridSpec& grid = result.grid;
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
                                          const Touch touch = overlapWithin(tri, {i, j, k}, mode, eps);
                                          if (touch.grown) grown[n] = true;
                                          if (touch.shrunk) shrunk[n] = true;
                                      }
                          }
                      });
    for (std::size_t n = 0; n < voxels.size(); ++n) {
        if (grown[n] && !shrunk[n]) {
            ++cmp.touches;
        } else {
            cmp.unexplained.push_back(voxels[n]);
            if (result.occupancy.test(voxels[n][0], voxels[n][1], voxels[n][2])) ++cmp.unexplained_result_only;
        }
    }
    cmp.check_ms = watch.elapsedMs();
    return cmp;
}

Comparison compareWithReference(const MeshView& mesh, VoxelizeOptions options, double eps) {
    Stopwatch watch;
    options.method = Method::Cpu;
    const VoxelizeResult cpu = voxelize(mesh, options);
    const double cpu_ms = watch.restart();
    options.method = Method::Reference;
    const VoxelizeResult ref = voxelize(mesh, options);
    const double reference_ms = watch.elapsedMs();
    Comparison cmp = compareResults(mesh, options.mode, cpu, ref, eps);
    cmp.result_ms = cpu_ms;
    cmp.oracle_ms = reference_ms;
    return cmp;
}

void expectMatchesOracle(const Comparison& cmp) {
    EXPECT_GT(cmp.oracle_voxels, 0u) << cmp.summary();
    EXPECT_TRUE(cmp.unexplained.empty()) << cmp.summary();
    EXPECT_LE(cmp.touches, std::max<std::uint64_t>(10, cmp.oracle_voxels / 10000)) << cmp.summary();
}

std::uint64_t countHoles(const MeshView& mesh, const VoxelizeResult& result, std::uint64_t* samples,
                         std::vector<std::array<double, 3>>* first_holes, double slack) {
    const ValidatedMesh validated = validate(mesh);
    const GridSpec& grid = result.grid;
    const BitGrid bits = result.occupancy.toBitGrid();
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
                              for (int c = 0; c < 3; ++c) v[c] = grid.toVoxel(validated.vertex(validated.usable[t], c));
                              double longest = 0;
                              for (int c = 0; c < 3; ++c) {
                                  double len2 = 0;
                                  for (int a = 0; a < 3; ++a)
                                      len2 += (v[(c + 1) % 3][a] - v[c][a]) * (v[(c + 1) % 3][a] - v[c][a]);
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

// inside[(i*dy + j)*dz + k]: is the point (i+1/2, j+1/2+dy', k+1/2+dz') inside the mesh, by the
// parity of a ray along +x? The tiny irrational offsets keep the rays off mesh edges and
// vertices; they move the point by far less than a voxel, so an empty voxel's answer is
// that of its centre (a surface passing between them would have marked the voxel).
std::vector<char> insideByParity(const MeshView& mesh, const GridSpec& grid) {
    const int nx = grid.dims[0], ny = grid.dims[1], nz = grid.dims[2];
    const double oy = 0.5 + 1.1e-6 * std::sqrt(2.0), oz = 0.5 + 0.7e-6 * std::sqrt(3.0);
    std::vector<std::vector<double>> crossings(std::size_t(ny) * nz);
    const ValidatedMesh v = validate(mesh);
    for (std::uint32_t t : v.usable) {
        std::array<double, 3> p[3];
        for (int c = 0; c < 3; ++c) p[c] = grid.toVoxel(v.vertex(t, c));
        const double ymin = std::min({p[0][1], p[1][1], p[2][1]}), ymax = std::max({p[0][1], p[1][1], p[2][1]});
        const double zmin = std::min({p[0][2], p[1][2], p[2][2]}), zmax = std::max({p[0][2], p[1][2], p[2][2]});
        for (int j = std::max(0, int(std::floor(ymin - oy))); j <= std::min(ny - 1, int(std::ceil(ymax - oy))); ++j)
            for (int k = std::max(0, int(std::floor(zmin - oz))); k <= std::min(nz - 1, int(std::ceil(zmax - oz)));
                 ++k) {
                const double y = j + oy, z = k + oz;
                // Point in the projected (y,z) triangle: all edge functions of one sign.
                double e[3];
                for (int c = 0; c < 3; ++c) {
                    const std::array<double, 3>& a = p[c];
                    const std::array<double, 3>& b = p[(c + 1) % 3];
                    e[c] = (b[1] - a[1]) * (z - a[2]) - (b[2] - a[2]) * (y - a[1]);
                }
                const bool in = (e[0] > 0 && e[1] > 0 && e[2] > 0) || (e[0] < 0 && e[1] < 0 && e[2] < 0);
                if (!in) continue;
                const double area = e[0] + e[1] + e[2];
                // Barycentric interpolation of x at the hit.
                const double x = (e[1] * p[0][0] + e[2] * p[1][0] + e[0] * p[2][0]) / area;
                crossings[std::size_t(j) * nz + k].push_back(x);
            }
    }
    std::vector<char> inside(std::size_t(nx) * ny * nz, 0);
    for (int j = 0; j < ny; ++j)
        for (int k = 0; k < nz; ++k) {
            auto& xs = crossings[std::size_t(j) * nz + k];
            std::sort(xs.begin(), xs.end());
            std::size_t passed = 0;
            for (int i = 0; i < nx; ++i) {
                while (passed < xs.size() && xs[passed] < i + 0.5) ++passed;
                inside[(std::size_t(i) * ny + j) * nz + k] = char(passed % 2);
            }
        }
    return inside;
}

Separation floodFromBoundary(const BitGrid& bits, const std::vector<char>& inside) {
    const auto d = bits.dims();
    auto id = [&](int i, int j, int k) { return (std::size_t(i) * d[1] + j) * d[2] + k; };
    const std::size_t count = std::size_t(d[0]) * d[1] * d[2];
    std::vector<char> seen(count, 0);
    std::deque<std::array<int, 3>> queue;
    for (int i = 0; i < d[0]; ++i)
        for (int j = 0; j < d[1]; ++j)
            for (int k = 0; k < d[2]; ++k) {
                const bool boundary = i == 0 || j == 0 || k == 0 || i == d[0] - 1 || j == d[1] - 1 || k == d[2] - 1;
                if (boundary && !bits.test(i, j, k)) {
                    seen[id(i, j, k)] = 1;
                    queue.push_back({i, j, k});
                }
            }
    const int steps[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    while (!queue.empty()) {
        const auto p = queue.front();
        queue.pop_front();
        for (const auto& s : steps) {
            const int i = p[0] + s[0], j = p[1] + s[1], k = p[2] + s[2];
            if (!bits.inside(i, j, k) || seen[id(i, j, k)] || bits.test(i, j, k)) continue;
            seen[id(i, j, k)] = 1;
            queue.push_back({i, j, k});
        }
    }
    Separation out;
    for (int i = 0; i < d[0]; ++i)
        for (int j = 0; j < d[1]; ++j)
            for (int k = 0; k < d[2]; ++k) {
                if (bits.test(i, j, k)) continue;
                const bool in = inside[id(i, j, k)];
                out.reached += seen[id(i, j, k)];
                out.inside_empty += in;
                out.inside_reached += in && seen[id(i, j, k)];
            }
    return out;
}

Separation expectSixSeparating(const MeshView& mesh, const VoxelizeResult& result, std::uint64_t min_inside_empty) {
    const std::vector<char> inside = insideByParity(mesh, result.grid);
    const Separation s = floodFromBoundary(result.occupancy.toBitGrid(), inside);
    EXPECT_GT(s.reached, 0u);
    EXPECT_GT(s.inside_empty, min_inside_empty) << "the mesh should enclose empty voxels";
    EXPECT_EQ(s.inside_reached, 0u) << "a 6-connected path of empty voxels leaks into the inside";

    BitGrid open(result.occupancy.dims());
    const int mid = open.dims()[0] / 2;
    for (const auto& c : result.occupancy.coords())
        if (c[0] != mid) open.set(c[0], c[1], c[2]);
    EXPECT_GT(floodFromBoundary(open, inside).inside_reached, 0u) << "negative control: slab x = " << mid << " removed";
    return s;
}

}  // namespace hyvox::test
