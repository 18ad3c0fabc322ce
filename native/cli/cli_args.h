// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Command-line parsing for `hyvox voxelize` and `hyvox gamma-sweep`: the voxelize options
// and their help come from the options schema (hyvox/option_schema.h); every mistake is a
// UsageError with the schema's message.
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "hyvox/options.h"

namespace hyvox::cli {

// A mistake on the command line: one line of message; `hint` says where the help is.
struct UsageError : std::runtime_error {
    explicit UsageError(const std::string& message, std::string hint_text = "hyvox --help lists the commands")
        : std::runtime_error(message), hint(std::move(hint_text)) {}
    std::string hint;
};

enum class Command { Help, Version, Voxelize, GammaSweep };

struct Arguments {
    Command command = Command::Help;
    std::string mesh_path;
    std::string output_path;
    std::string stats_json_path;  // empty: none
    bool quiet = false;     // -q: nothing on success, no progress
    bool progress = false;  // --progress: show progress also when stderr is not a terminal
    // Help: the command whose help was asked for (Help itself: the list of commands).
    Command help_topic = Command::Help;
    std::string texture_path;  // empty: none; a PNG sampled at the mesh's UVs for --attributes color
    VoxelizeOptions options;
    WriteOptions write;  // the .vdb's and the stats JSON's
    std::vector<double> gammas;  // gamma-sweep: the safety factors to try, ascending
    // Options given on the command line that the chosen method ignores (printed as warnings).
    std::vector<std::string> warnings;
};

// args without argv[0]; the options start from the environment variables the schema names.
Arguments parseArguments(const std::vector<std::string>& args);
// The help `hyvox --help` (topic Help: the commands) or `hyvox COMMAND --help` prints.
std::string usageText(Command topic = Command::Help);

}  // namespace hyvox::cli
