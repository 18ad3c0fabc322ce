// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "hyvox/bit_grid.h"
#include "hyvox/grid.h"

namespace hyvox {

struct Stats {
    std::string method;
    std::string mode;
    std::uint64_t triangles_input = 0;
    std::uint64_t triangles_used = 0;
    std::uint64_t triangles_degenerate = 0;  // skipped
    std::uint64_t voxel_count = 0;
    // Stage name -> milliseconds, in the order the stages ran (validate, grid, voxelize, ...).
    std::vector<std::pair<std::string, double>> timings_ms;
    // Backend-specific figures: pass1_gpu_ms, pass2_gpu_ms, large_triangles, cutoff, bias, ...
    std::map<std::string, double> metrics;

    void addTiming(std::string stage, double ms) { timings_ms.emplace_back(std::move(stage), ms); }
    double totalMs() const {
        double total = 0;
        for (const auto& stage : timings_ms) total += stage.second;
        return total;
    }
    // Milliseconds of one stage, 0 when it did not run.
    double timingMs(const std::string& stage) const {
        for (const auto& [name, ms] : timings_ms)
            if (name == stage) return ms;
        return 0.0;
    }
};

// A voxel with a value (multi-valued output such as the tessellation method's point counts).
struct VoxelCount {
    std::int32_t i, j, k;
    std::uint32_t count;
};

struct VoxelizeResult {
    GridSpec grid;
    BitGrid occupancy;               // one bit per voxel, OpenVDB leaf layout
    std::vector<VoxelCount> counts;  // empty unless the method is multi-valued
    Stats stats;
};

}  // namespace hyvox
