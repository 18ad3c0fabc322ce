// SPDX-License-Identifier: GPL-3.0-or-later
// Reads a mesh, voxelizes its surface and prints how many voxels it takes; with a fourth
// argument, writes them as an OpenVDB file too.
//   voxel_count MESH [RESOLUTION [METHOD [OUT.vdb]]]
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "hyvox/hyvox.h"
#include "hyvox/mesh_io.h"
#include "hyvox/vdb.h"

int main(int argc, char** argv) {
    if (argc < 2 || argc > 5) {
        std::fprintf(stderr, "usage: voxel_count MESH [RESOLUTION [METHOD [OUT.vdb]]]\n");
        return 2;
    }
    try {
        const hyvox::Mesh mesh = hyvox::readMesh(argv[1]);
        hyvox::VoxelizeOptions options;  // the schema's defaults: conservative, cpu, 256
        if (argc > 2) hyvox::setOption(options, "resolution", std::int64_t(std::atoll(argv[2])));
        if (argc > 3) hyvox::setOption(options, "method", std::string(argv[3]));
        const hyvox::VoxelizeResult result = hyvox::voxelize(mesh.view(), options);
        std::printf("%llu voxels in a %s grid of voxel size %g (%s)\n",
                    static_cast<unsigned long long>(result.stats.voxel_count), result.grid.dimsText().c_str(),
                    result.grid.voxel_size, result.stats.method.c_str());
        if (argc > 4) hyvox::writeVdb(result, argv[4]);
        return 0;
    } catch (const std::exception& e) {  // InvalidInput, ResourceError, BackendError, ...
        std::fprintf(stderr, "voxel_count: %s\n", e.what());
        return 1;
    }
}
