// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target for the formats read through assimp, read as readMesh reads them: in the
// assimp reader process (native/src/mesh_io/assimp_reader.h). The first byte picks the format
// (fbx, 3mf), the rest is the file; an FBX's container is checked first (fbx_check.h). Whatever assimp does with the bytes,
// this process must get a mesh whose arrays agree and whose indices are in range, or an
// InvalidInput (a crash, a hang or memory past the budget in the reader process is one).
// Another exception, or anything that ends this process, is a finding.
//
// assimp is Debian's build, without coverage instrumentation: libFuzzer's feedback comes
// from hyvox's side only (the process, the wire decoder), so for assimp this is mutation
// around the seeds, as tests/damage/damage_meshes.py does at scale.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "hyvox/errors.h"
#include "mesh_io/assimp_reader.h"
#include "mesh_io/fbx_check.h"

namespace {

constexpr const char* kFormats[] = {"fbx", "3mf"};
// Small enough that a damaged file's allocations fail fast, large enough for the seeds.
constexpr hyvox::mesh_io::AssimpReadLimits kLimits{512ull << 20, 5.0};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    const std::string extension = kFormats[data[0] % (sizeof kFormats / sizeof kFormats[0])];
    const char* bytes = reinterpret_cast<const char*>(data + 1);
    try {
        if (extension == "fbx") hyvox::mesh_io::checkFbxContainer(bytes, size - 1, "fuzz.fbx", kLimits.memory_bytes);
        const hyvox::Mesh mesh =
            hyvox::mesh_io::readWithAssimp(bytes, size - 1, extension, "fuzz." + extension, kLimits);
        if (mesh.triangles.empty() || mesh.positions.size() % 3 != 0) std::abort();
        if (mesh.hasColors() && mesh.colors.size() != 4 * mesh.vertexCount()) std::abort();
        if (mesh.hasUvs() && mesh.uvs.size() != 2 * mesh.vertexCount()) std::abort();
        for (std::uint32_t i : mesh.triangles)
            if (i >= mesh.vertexCount()) std::abort();
    } catch (const hyvox::InvalidInput&) {
        // the expected answer to bad bytes
    }
    return 0;
}
