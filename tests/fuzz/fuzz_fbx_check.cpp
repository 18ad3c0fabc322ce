// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target for the FBX container check (native/src/mesh_io/fbx_check.h), which reads
// untrusted bytes in hyvox's own process before assimp's process sees them: any bytes must
// pass or give InvalidInput, within 64 MiB of inflated arrays. Anything else is a finding.
#include <cstddef>
#include <cstdint>

#include "hyvox/errors.h"
#include "mesh_io/fbx_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        hyvox::mesh_io::checkFbxContainer(reinterpret_cast<const char*>(data), size, "fuzz.fbx", 64u << 20);
    } catch (const hyvox::InvalidInput&) {
        // the expected answer to bad bytes
    }
    return 0;
}
