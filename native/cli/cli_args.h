// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Command-line parsing for `hyvox voxelize` and `hyvox gamma-sweep`: plain code, no
// dependency, every mistake a UsageError with a message that says what to type instead.
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "hyvox/options.h"

namespace hyvox::cli {

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

enum class Command { Help, Version, Voxelize, GammaSweep };

struct Arguments {
    Command command = Command::Help;
    std::string mesh_path;
    std::string output_path;
    std::string stats_json_path;  // empty: none
    bool quiet = false;
    VoxelizeOptions options;
    std::vector<double> gammas;  // gamma-sweep: the safety factors to try, ascending
};

Arguments parseArguments(const std::vector<std::string>& args);  // args without argv[0]
const char* usageText();

}  // namespace hyvox::cli
