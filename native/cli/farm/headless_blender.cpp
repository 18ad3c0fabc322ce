// SPDX-License-Identifier: GPL-3.0-or-later
#include "farm/headless_blender.h"

#include <stdexcept>

#include "farm/job_options.h"

namespace hyvox::farm {
namespace {

// What the add-on declares for the jobs: its module name and its farm entry point
// (addon/hyvox_blender/__init__.py), a function taking the farm command's arguments.
constexpr const char* kAddon = "hyvox_blender";
constexpr const char* kEntryPoint = "farm_main";

}  // namespace

const std::string& blenderBootstrap() {
    static const std::string expression = [] {
        const std::string addon = kAddon;
        const std::string text =
            "import addon_utils, importlib, sys; "
            "found = [m.__name__ for m in addon_utils.modules() if m.__name__.rpartition(\".\")[2] == \"" +
            addon +
            "\"]; "
            "found or sys.exit(\"hyvox: error: this Blender has no hyvox add-on (install the extension, or the "
            "add-on in $BLENDER_USER_SCRIPTS/addons/)\"); "
            "addon_utils.enable(found[0], default_set=False, handle_error=None) or "
            "sys.exit(\"hyvox: error: could not enable the add-on \" + found[0]); "
            "importlib.import_module(found[0])." +
            kEntryPoint + "(sys.argv[sys.argv.index(\"--\") + 1:])";
        if (text.find('\'') != std::string::npos) throw std::logic_error("the bootstrap must not hold a '");
        return text;
    }();
    return expression;
}

std::vector<std::string> blenderArgsAfterFile() {
    return {"--python-exit-code", "1", "--python-expr", blenderBootstrap(), "--"};
}

namespace {

bool takesOption(FarmCommand command, const OptionSpec& spec) {
    for (const FarmTaskArgument& arg : farmTaskArguments())
        if (arg.option == &spec && arg.takenBy(command)) return true;
    return false;
}

// The job's arguments of `command`: the table's that a job fills, then the job's voxelize
// options that the command takes (`run` every one: it passes on what it does not parse).
std::vector<Argument> jobArguments(FarmCommand command) {
    std::vector<Argument> out;
    for (const FarmTaskArgument& arg : farmTaskArguments())
        if (arg.takenBy(command) && arg.job != FarmJobValue::None && arg.job != FarmJobValue::Option)
            out.push_back({arg.flag, arg.job});
    for (const OptionSpec* spec : blenderJobOptions())
        if (command == FarmCommand::Run || takesOption(command, *spec))
            out.push_back({spec->cliFlag(), FarmJobValue::Option, spec});
    return out;
}

}  // namespace

std::vector<Argument> runArguments() { return jobArguments(FarmCommand::Run); }

std::vector<Argument> assembleArguments() { return jobArguments(FarmCommand::Assemble); }

}  // namespace hyvox::farm
