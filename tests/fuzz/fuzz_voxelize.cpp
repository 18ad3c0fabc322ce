// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target for voxelize() on small random meshes: the input bytes become up to 16
// vertices, up to 16 triangles (indices taken modulo a slightly larger count, so some are out
// of range) and the grid options (resolution, mode, padding, tile size). The vertices come
// in one of two encodings, chosen by a bit of the options byte: raw float32 (NaN, inf,
// denormals, 1e-37 next to 1e33: slivers and needles that voxel space cannot hold) or
// 16-bit integers in 1/64 steps, scaled by a power of two from 2^-16 to 2^15 (exact in
// float, so the alignments that decide touching voxels occur often). The oracle is inside
// the target: the cpu method must set exactly the voxels of the double-precision reference, except voxels that
// merely touch a triangle (the reference's rule says yes with the box grown by 1e-5 voxel
// units and no with it shrunk by as much; docs/design.md, "Correctness"), or both must refuse the
// input with the same kind of error (InvalidInput / ResourceError). Anything else (a crash,
// a sanitizer report, another mismatch, a hang) is a finding.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_bytes.h"
#include "hyvox/errors.h"
#include "hyvox/voxelize.h"
#include "reference/reference_overlap.h"

namespace {

using hyvox::fuzz::Bytes;

// "" when the run succeeded (its voxels in `coords`), else the kind of error.
using Coords = std::vector<std::array<std::int32_t, 3>>;

std::string run(const hyvox::MeshView& mesh, hyvox::VoxelizeOptions options, hyvox::Method method, Coords& coords,
                hyvox::GridSpec& grid) {
    options.method = method;
    try {
        const hyvox::VoxelizeResult result = hyvox::voxelize(mesh, options);
        coords = result.occupancy.coords();
        std::sort(coords.begin(), coords.end());
        grid = result.grid;
        return "";
    } catch (const hyvox::InvalidInput&) {
        return "InvalidInput";
    } catch (const hyvox::ResourceError&) {
        return "ResourceError";
    }
}

// A voxel the two methods may disagree on: some triangle touches it (overlaps the box grown
// by eps) and none overlaps the box shrunk by eps.
bool isTouch(const hyvox::ValidatedMesh& mesh, const hyvox::GridSpec& grid, hyvox::Mode mode,
             const std::array<std::int32_t, 3>& voxel) {
    constexpr double kEps = 1e-5;
    bool grown = false;
    for (std::uint32_t t : mesh.usable) {
        const auto triangle = hyvox::reference::voxelSpaceTriangle(mesh, t, grid);
        if (hyvox::reference::overlaps(triangle, {voxel[0], voxel[1], voxel[2]}, mode, -kEps)) return false;
        grown = grown || hyvox::reference::overlaps(triangle, {voxel[0], voxel[1], voxel[2]}, mode, kEps);
    }
    return grown;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    Bytes bytes(data, size);
    const std::uint8_t counts = bytes.take<std::uint8_t>();
    const std::size_t vertex_count = 1 + (counts & 15), triangle_count = 1 + (counts >> 4);
    hyvox::VoxelizeOptions options;
    const std::uint8_t knobs = bytes.take<std::uint8_t>();
    options.grid.resolution = 1 + bytes.take<std::uint8_t>() % 48;  // small: the reference is brute force
    options.mode = (knobs & 1) ? hyvox::Mode::Thin : hyvox::Mode::Conservative;
    options.grid.padding = (knobs >> 1) & 3;
    options.tile_size = (knobs & 8) ? 8 * (1 + ((knobs >> 4) & 3)) : 0;  // tile borders too
    options.threads = 1;
    const hyvox::fuzz::Soup soup = hyvox::fuzz::takeSoup(bytes, vertex_count, triangle_count, knobs & 128);
    const hyvox::MeshView mesh{soup.positions.data(), vertex_count, soup.triangles.data(), triangle_count};

    Coords cpu, reference;
    hyvox::GridSpec grid;
    const std::string cpu_error = run(mesh, options, hyvox::Method::Cpu, cpu, grid);
    const std::string reference_error = run(mesh, options, hyvox::Method::Reference, reference, grid);
    if (cpu_error != reference_error) std::abort();
    if (!cpu_error.empty() || cpu == reference) return 0;
    Coords differ;
    std::set_symmetric_difference(cpu.begin(), cpu.end(), reference.begin(), reference.end(),
                                  std::back_inserter(differ));
    const hyvox::ValidatedMesh validated = hyvox::validate(mesh);
    for (const auto& voxel : differ)
        if (!isTouch(validated, grid, options.mode, voxel)) std::abort();
    return 0;
}
