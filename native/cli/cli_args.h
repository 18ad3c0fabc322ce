// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Command-line parsing for `hyvox voxelize`, `hyvox gamma-sweep` and `hyvox merge`
// (merge_command.h parses its own arguments): the voxelize options
// and their help come from the options schema (hyvox/option_schema.h); every mistake is a
// UsageError with the schema's message.
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "hyvox/option_schema.h"
#include "hyvox/options.h"

namespace hyvox::cli {

// A mistake on the command line: one line of message; `hint` says where the help is.
struct UsageError : std::runtime_error {
    explicit UsageError(const std::string& message, std::string hint_text = "hyvox --help lists the commands")
        : std::runtime_error(message), hint(std::move(hint_text)) {}
    std::string hint;
};

enum class Command { Help, Version, Voxelize, GammaSweep, Merge };

struct Arguments {
    Command command = Command::Help;
    std::string mesh_path;
    std::string output_path;
    std::string stats_json_path;  // empty: none
    bool quiet = false;           // -q: nothing on success, no progress
    bool progress = false;        // --progress: show progress also when stderr is not a terminal
    // Help: the command whose help was asked for (Help itself: the list of commands).
    Command help_topic = Command::Help;
    std::string texture_path;  // empty: none; a PNG sampled at the mesh's UVs for --attributes color
    VoxelizeOptions options;
    WriteOptions write;                   // the .vdb's and the stats JSON's
    std::vector<double> gammas;           // gamma-sweep: the safety factors to try, ascending
    std::vector<std::string> part_paths;  // merge: the .vdb files to join
    // Options given on the command line that the chosen method ignores (printed as warnings).
    std::vector<std::string> warnings;
};

// args without argv[0]; the options start from the environment variables the schema names.
Arguments parseArguments(const std::vector<std::string>& args);
// The help `hyvox --help` (topic Help: the commands) or `hyvox COMMAND --help` prints.
std::string usageText(Command topic = Command::Help);
// Pieces of that help the commands share: one option's entry (flag, help, default), and the
// options every command takes (--progress, --quiet, --help).
std::string optionHelp(const OptionSpec& spec);
std::string commonOptionsHelp();

// Argument `at` of a command line, "--name=value" split into the option and the value after '='.
class OptionArgument {
public:
    OptionArgument(const std::vector<std::string>& args, std::size_t& at);
    const std::string& option() const { return option_; }
    bool hasInlineValue() const { return inline_value_.has_value(); }
    // The value after '=', else the next argument (moving `at` past it); UsageError when none.
    std::string value();
    // UsageError when a value came after '='.
    void noValue() const;

private:
    const std::vector<std::string>& args_;
    std::size_t& at_;
    std::string option_;
    std::optional<std::string> inline_value_;
};

// -q/--quiet and --progress, which every command takes: sets it and returns true, else false.
bool takeOutputFlag(OptionArgument& argument, Arguments& out);

// The schema option a command-line flag names ("--voxel-size", an alias, or
// "--no-pn-triangles" for a flag's false; `negated` says which), or null.
const OptionSpec* specForFlag(const std::string& flag, bool& negated);
// Sets that option from the argument (in out.options, out.write or both, as the option is the
// voxelization's, the write's or both): a flag's true or false, else its value. UsageError with
// the schema's message after the flag as typed.
void setFromFlag(Arguments& out, const OptionSpec& spec, OptionArgument& argument, bool negated);

}  // namespace hyvox::cli
