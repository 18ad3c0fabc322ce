// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The command lines a farm task runs in Blender, the same for every farm engine:
//
//   BLENDER -b SCENE.blend --python-exit-code 1 --python-expr BOOTSTRAP -- COMMAND ARGS...
//
// BOOTSTRAP finds the hyvox add-on the worker's Blender has installed (a legacy add-on in
// a scripts folder, or the extension), enables it and hands the arguments after "--" to
// its farm package (addon/hyvox_blender/farm/), so a job needs no path to the add-on.
#include <string>
#include <vector>

#include "hyvox/option_schema.h"

namespace hyvox::farm {

// One line of Python, without single quotes (the job scripts quote it with them).
const std::string& blenderBootstrap();
// The arguments before the .blend and those between it and the farm command.
std::vector<std::string> blenderArgsAfterFile();  // --python-exit-code 1 --python-expr BOOTSTRAP --

// What fills an argument: the task's frames, a job setting, or a voxelize option.
enum class Source { TaskFrames, JobFrames, OutputDir, Objects, Option };

struct Argument {
    std::string flag;  // "--frames", "--resolution"
    Source source;
    const OptionSpec* option = nullptr;  // Source::Option
};

// `run`: voxelize the task's frames with the job's options (farm/task.py).
std::vector<Argument> runArguments();
// `assemble`: check the job's frames and save the .blend of the sequence.
std::vector<Argument> assembleArguments();

}  // namespace hyvox::farm
