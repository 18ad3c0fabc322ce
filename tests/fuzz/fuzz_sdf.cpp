// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target for the sdf's band distances (native/src/sdf/): the input bytes become a
// soup of up to 16 triangles on up to 16 vertices (as fuzz_voxelize decodes them: raw float32
// with NaN, Inf, slivers and needles, or 16-bit integers in 1/64 steps scaled by a power of
// two, so faces on voxel planes and through voxel centres occur often), a small resolution
// (up to 32) and a band of 1 to 6 voxels. The oracle (abort on violation):
//  - voxelize() with the sdf attribute either succeeds or refuses with InvalidInput or
//    ResourceError, as the surface alone does;
//  - every block of the band, computed both ways (every triangle swept, and the small ones
//    queried wherever a block has any: sdf/band_queries.h), holds at every voxel of the grid
//    the brute-force closest distance over the usable triangles (tests/native/support/
//    closest_point.h) within 1e-5 voxel where that is below the band, and band² exactly
//    where it is beyond (voxels within 1e-9 of the band's edge skipped); every voxel of a
//    block the bins leave out lies beyond the band.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "fuzz_bytes.h"
#include "hyvox/errors.h"
#include "hyvox/voxelize.h"
#include "sdf/band_bins.h"
#include "sdf/band_distances.h"
#include "support/closest_point.h"

namespace {

using hyvox::fuzz::Bytes;
using Vec3 = std::array<double, 3>;

using hyvox::test::closest_point::pointTriangleDistance;

#define REQUIRE(condition)                                                                 \
    do {                                                                                   \
        if (!(condition)) {                                                                \
            std::fprintf(stderr, "fuzz_sdf.cpp:%d: violated: %s\n", __LINE__, #condition); \
            std::abort();                                                                  \
        }                                                                                  \
    } while (false)

std::string errorOf(const hyvox::MeshView& mesh, const hyvox::VoxelizeOptions& options, hyvox::GridSpec& grid) {
    try {
        grid = hyvox::voxelize(mesh, options).grid;
        return "";
    } catch (const hyvox::InvalidInput&) {
        return "InvalidInput";
    } catch (const hyvox::ResourceError&) {
        return "ResourceError";
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    Bytes bytes(data, size);
    const std::uint8_t counts = bytes.take<std::uint8_t>();
    const std::size_t vertex_count = 1 + (counts & 15), triangle_count = 1 + (counts >> 4);
    const std::uint8_t knobs = bytes.take<std::uint8_t>();
    hyvox::VoxelizeOptions options;
    options.grid.resolution = 1 + bytes.take<std::uint8_t>() % 32;  // small: the oracle is brute force
    options.mode = hyvox::Mode::Conservative;
    options.sdf.band = 1 + (knobs & 7) % 6;
    options.threads = 1;
    const hyvox::fuzz::Soup soup = hyvox::fuzz::takeSoup(bytes, vertex_count, triangle_count, knobs & 128);
    const hyvox::MeshView mesh{soup.positions.data(), vertex_count, soup.triangles.data(), triangle_count};

    hyvox::GridSpec grid, sdf_grid;
    hyvox::VoxelizeOptions with_sdf = options;
    with_sdf.attributes.sdf = true;
    const std::string error = errorOf(mesh, options, grid);
    REQUIRE(errorOf(mesh, with_sdf, sdf_grid) == error);
    if (!error.empty()) return 0;

    // The blocks on the sdf run's grid (padded by the band), both ways, against brute force.
    const hyvox::ValidatedMesh validated = hyvox::validate(mesh);
    std::vector<std::array<Vec3, 3>> corners;
    for (const std::uint32_t t : validated.usable)
        corners.push_back({sdf_grid.toVoxel(validated.vertex(t, 0)), sdf_grid.toVoxel(validated.vertex(t, 1)),
                           sdf_grid.toVoxel(validated.vertex(t, 2))});
    const double band = double(options.sdf.band);
    const hyvox::sdf::BandBins bins =
        hyvox::sdf::binBand(validated, sdf_grid, band, std::uint64_t(1) << 31, 2048, nullptr);
    const hyvox::sdf::BlockLayout blocks(sdf_grid);
    std::vector<double> swept(hyvox::sdf::kBlockVoxels), queried(hyvox::sdf::kBlockVoxels);
    hyvox::sdf::BlockQueries queries;
    std::size_t number = 0;  // the next of the bins' blocks (ascending)
    for (std::uint64_t index = 0; index < std::uint64_t(blocks.counts[0]) * blocks.counts[1] * blocks.counts[2];
         ++index) {
        const bool binned = number < bins.blocks.size() && bins.blocks[number] == index;
        if (binned) {
            std::uint64_t evaluations = 0;
            hyvox::sdf::blockDistances(validated, sdf_grid, band, bins, number, swept.data(), evaluations, nullptr);
            hyvox::sdf::blockDistances(validated, sdf_grid, band, bins, number, queried.data(), evaluations, &queries,
                                       0.0);
            ++number;
        }
        const std::array<std::int32_t, 3> block = blocks.at(index);
        constexpr int kSide = hyvox::sdf::BlockLayout::kSide;
        for (int x = 0; x < kSide; ++x)
            for (int y = 0; y < kSide; ++y)
                for (int z = 0; z < kSide; ++z) {
                    const int i = kSide * block[0] + x, j = kSide * block[1] + y, k = kSide * block[2] + z;
                    if (i >= sdf_grid.dims[0] || j >= sdf_grid.dims[1] || k >= sdf_grid.dims[2]) continue;
                    const Vec3 p{i + 0.5, j + 0.5, k + 0.5};
                    double d = HUGE_VAL;
                    for (const auto& c : corners) d = std::min(d, pointTriangleDistance(p, c[0], c[1], c[2]));
                    if (std::fabs(d - band) < 1e-9) continue;
                    if (!binned) {
                        REQUIRE(d > band);
                        continue;
                    }
                    const std::size_t at = std::size_t(hyvox::sdf::blockOffset(x, y, z));
                    for (const double d2 : {swept[at], queried[at]}) {
                        if (d > band)
                            REQUIRE(d2 == band * band);
                        else
                            REQUIRE(std::fabs(std::sqrt(d2) - d) < 1e-5);
                    }
                }
    }
    REQUIRE(number == bins.blocks.size());
    return 0;
}
