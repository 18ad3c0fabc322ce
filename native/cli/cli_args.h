// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Command-line parsing for `hyvox voxelize` and `hyvox gamma-sweep`: the voxelize options
// and their help come from the options schema (hyvox/option_schema.h); every mistake is a
// UsageError with the schema's message.
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
    std::string texture_path;     // empty: none; a PNG sampled at the mesh's UVs for --attributes color
    bool quiet = false;
    VoxelizeOptions options;
    std::vector<double> gammas;  // gamma-sweep: the safety factors to try, ascending
    // Options given on the command line that the chosen method ignores (printed as warnings).
    std::vector<std::string> warnings;
};

// args without argv[0]; the options start from the environment variables the schema names.
Arguments parseArguments(const std::vector<std::string>& args);
std::string usageText();

}  // namespace hyvox::cli
