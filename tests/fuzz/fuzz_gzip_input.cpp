// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target for the bounded gzip input and the PLY reader behind it (a .ply.gz as
// readMesh reads it): any bytes must give a mesh whose indices are in range, or
// InvalidInput, within the output bound (16 MiB here, so each input stays fast). Anything
// else (another exception, a crash, a sanitizer report, a hang, memory beyond
// -rss_limit_mb) is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "hyvox/errors.h"
#include "mesh_io/gzip_input.h"
#include "mesh_io/ply_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    constexpr std::uint64_t kMaxOutput = 16u << 20;
    try {
        const std::vector<char> compressed(data, data + size);
        const std::vector<char> plain = hyvox::mesh_io::gunzip(compressed, "fuzz.ply.gz", kMaxOutput);
        if (plain.empty() || plain.size() > kMaxOutput) std::abort();
        const hyvox::Mesh mesh = hyvox::mesh_io::readPly(plain.data(), plain.size(), "fuzz.ply.gz");
        if (mesh.triangles.empty() || mesh.positions.size() % 3 != 0) std::abort();
        for (std::uint32_t i : mesh.triangles)
            if (i >= mesh.vertexCount()) std::abort();
    } catch (const hyvox::InvalidInput&) {
        // the expected answer to bad bytes
    }
    return 0;
}
