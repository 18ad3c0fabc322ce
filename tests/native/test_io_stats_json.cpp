// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "hyvox/stats_json.h"

TEST(IoStatsJson, HoldsTheFields) {
    hyvox::VoxelizeResult r;
    r.grid.origin = {-1.5, 0.25, 3};
    r.grid.voxel_size = 0.1;
    r.grid.dims = {10, 20, 30};
    r.stats.method = "cpu";
    r.stats.mode = "thin";
    r.stats.triangles_input = 12;
    r.stats.triangles_used = 10;
    r.stats.triangles_degenerate = 2;
    r.stats.voxel_count = 1234;
    r.stats.addTiming("validate", 1.5);
    r.stats.addTiming("voxelize", 2.5);
    r.stats.addTiming("voxelize", 1.0);
    hyvox::HybridStats hybrid;
    hybrid.pass1_gpu_ms = 0.25;
    hybrid.cutoff = std::nan("");
    r.stats.hybrid = hybrid;
    r.stats.options.gl.shader_dir = "odd \"dir\"\n";
    const std::string json = hyvox::statsToJson(r);
    for (const char* part : {"\"method\": \"cpu\"", "\"mode\": \"thin\"", "\"origin\": [-1.5, 0.25, 3]",
                             "\"voxel_size\": 0.1", "\"dims\": [10, 20, 30]", "\"voxel_count\": 1234",
                             "\"triangles\": {\"input\": 12, \"used\": 10, \"degenerate\": 2}", "\"validate\": 1.5",
                             "\"voxelize\": 3.5", "\"total_ms\": 5", "\"hybrid\": {\"pass1_gpu_ms\": 0.25",
                             "\"cutoff\": null", "\"shader_dir\": \"odd \\\"dir\\\"\\n\""})
        EXPECT_NE(json.find(part), std::string::npos) << part << "\n" << json;
}
