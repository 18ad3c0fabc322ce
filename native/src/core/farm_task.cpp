// SPDX-License-Identifier: GPL-3.0-or-later
#include "hyvox/farm_task.h"

namespace hyvox {
namespace {

FarmTaskArgument text(const char* flag, std::vector<std::string> aliases, bool run, bool assemble, bool required,
                      const char* default_text, const char* help, FarmJobValue job) {
    return {flag, std::move(aliases), run, assemble, required, FarmValue::Text, nullptr, default_text, help, job};
}

FarmTaskArgument option(const char* name, std::vector<std::string> aliases) {
    const OptionSpec& spec = findOption(name);
    return {spec.cliFlag(), std::move(aliases),  true, true, false, FarmValue::Option, &spec, nullptr,
            spec.help,      FarmJobValue::Option};
}

FarmTaskArgument toggle(const char* flag, const char* help) {
    return {flag, {}, true, true, false, FarmValue::Switch, nullptr, nullptr, help, FarmJobValue::None};
}

}  // namespace

const std::vector<FarmTaskArgument>& farmTaskArguments() {
    static const std::vector<FarmTaskArgument> table = [] {
        std::vector<FarmTaskArgument> out{
            text("--frames", {}, true, false, true, nullptr, "the frames of this task, e.g. 11-20",
                 FarmJobValue::TaskFrames),
            text("--job-frames", {}, true, true, true, nullptr, "every frame of the job, e.g. 1-250",
                 FarmJobValue::JobFrames),
            text("--output", {"-o"}, true, true, true, nullptr, "folder of the .vdb files", FarmJobValue::OutputDir),
            text("--objects", {}, true, true, false, "", "comma-separated object names ('': cli_blender's choice)",
                 FarmJobValue::Objects),
            text("--blend", {}, true, true, false, nullptr, "open this .blend first", FarmJobValue::None),
            // The job's voxel size comes from these two (the task plans the first frame's
            // grid); the other voxelize options `run` passes on to the headless script.
            option("resolution", {"-r"}),
            option("voxel_size", {}),
            toggle("--viewport", "evaluate modifiers at viewport settings (default: render settings)"),
            text("--save", {}, false, true, false, nullptr,
                 "the .blend to write (default: OUTPUT/<scene>_voxels.blend)", FarmJobValue::None),
        };
        return out;
    }();
    return table;
}

double farmUnsetValue(const OptionSpec& spec) { return spec.min; }

}  // namespace hyvox
