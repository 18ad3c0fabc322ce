// SPDX-License-Identifier: GPL-3.0-or-later
#include "farm/headless_blender.h"

#include <stdexcept>

#include "farm/job_options.h"

namespace hyvox::farm {

const std::string& blenderBootstrap() {
    static const std::string expression = [] {
        const std::string text =
            "import addon_utils, importlib, sys; "
            "found = [m.__name__ for m in addon_utils.modules() if m.__name__.rpartition(\".\")[2] == "
            "\"hyvox_blender\"]; "
            "found or sys.exit(\"hyvox: error: this Blender has no hyvox add-on (install the extension, or the "
            "add-on in $BLENDER_USER_SCRIPTS/addons/)\"); "
            "addon_utils.enable(found[0], default_set=False, handle_error=None) or "
            "sys.exit(\"hyvox: error: could not enable the add-on \" + found[0]); "
            "importlib.import_module(found[0] + \".farm\").main(sys.argv[sys.argv.index(\"--\") + 1:])";
        if (text.find('\'') != std::string::npos) throw std::logic_error("the bootstrap must not hold a '");
        return text;
    }();
    return expression;
}

std::vector<std::string> blenderArgsAfterFile() {
    return {"--python-exit-code", "1", "--python-expr", blenderBootstrap(), "--"};
}

namespace {

std::vector<Argument> withOptions(std::vector<Argument> args, bool size_only) {
    for (const OptionSpec* spec : blenderJobOptions()) {
        const std::string name = spec->name;
        if (size_only && name != "resolution" && name != "voxel_size") continue;
        args.push_back({spec->cliFlag(), Source::Option, spec});
    }
    return args;
}

}  // namespace

std::vector<Argument> runArguments() {
    return withOptions({{"--frames", Source::TaskFrames},
                        {"--job-frames", Source::JobFrames},
                        {"--output", Source::OutputDir},
                        {"--objects", Source::Objects}},
                       false);
}

std::vector<Argument> assembleArguments() {
    // The voxel size is checked against the job's: the size options are the job's too.
    return withOptions(
        {{"--job-frames", Source::JobFrames}, {"--output", Source::OutputDir}, {"--objects", Source::Objects}}, true);
}

}  // namespace hyvox::farm
