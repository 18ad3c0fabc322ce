// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target for one strict mesh reader, chosen at build time (HYVOX_FUZZ_PLY,
// HYVOX_FUZZ_OBJ, HYVOX_FUZZ_STL, HYVOX_FUZZ_OFF or HYVOX_FUZZ_GLTF): any bytes must give a
// mesh whose indices are in range, or InvalidInput. The glTF target reads both its forms
// (the first bytes tell GLB from JSON); a buffer URI naming a file is looked for beside
// "fuzz.gltf", in the folder the fuzzer runs in.
// The OBJ target also reads the bytes as an MTL (material file), whose seeds sit beside the
// OBJ ones.
// Anything else (another exception, a crash, a sanitizer report, a hang, memory beyond
// -rss_limit_mb) is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "hyvox/errors.h"
#include "mesh_io/gltf_reader.h"
#include "mesh_io/mtl_reader.h"
#include "mesh_io/obj_reader.h"
#include "mesh_io/off_reader.h"
#include "mesh_io/ply_reader.h"
#include "mesh_io/stl_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const char* bytes = reinterpret_cast<const char*>(data);
#if defined(HYVOX_FUZZ_OBJ)
    try {
        for (const hyvox::mesh_io::MtlMaterial& m : hyvox::mesh_io::readMtl(bytes, size, "fuzz.mtl"))
            if (m.name.empty()) std::abort();
    } catch (const hyvox::InvalidInput&) {}
#endif
    try {
#if defined(HYVOX_FUZZ_PLY)
        const hyvox::Mesh mesh = hyvox::mesh_io::readPly(bytes, size, "fuzz.ply");
#elif defined(HYVOX_FUZZ_STL)
        const hyvox::Mesh mesh = hyvox::mesh_io::readStl(bytes, size, "fuzz.stl");
#elif defined(HYVOX_FUZZ_OFF)
        const hyvox::Mesh mesh = hyvox::mesh_io::readOff(bytes, size, "fuzz.off");
#elif defined(HYVOX_FUZZ_GLTF)
        const hyvox::Mesh mesh = hyvox::mesh_io::readGltf(bytes, size, "fuzz.gltf", 256u << 20);
#else
        const hyvox::Mesh mesh = hyvox::mesh_io::readObj(bytes, size, "fuzz.obj");
#endif
        if (mesh.triangles.empty() || mesh.positions.size() % 3 != 0) std::abort();
        if (mesh.hasColors() && mesh.colors.size() != 4 * mesh.vertexCount()) std::abort();
        if (mesh.hasUvs() && mesh.uvs.size() != 2 * mesh.vertexCount()) std::abort();
        for (std::uint32_t i : mesh.triangles)
            if (i >= mesh.vertexCount()) std::abort();
        if (mesh.hasMaterials()) {
            if (mesh.material_ids.size() != mesh.triangleCount()) std::abort();
            for (std::uint32_t m : mesh.material_ids)
                if (m >= mesh.material_names.size() || 3 * std::size_t(m) + 2 >= mesh.material_colors.size())
                    std::abort();
        }
    } catch (const hyvox::InvalidInput&) {
        // the expected answer to bad bytes
    }
    return 0;
}
