// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The command lines a farm task runs in Blender, the same for every farm engine:
//
//   BLENDER -b SCENE.blend --python-exit-code 1 --python-expr BOOTSTRAP -- COMMAND ARGS...
//
// BOOTSTRAP enables the installed add-on named hyvox_blender (a legacy add-on in a scripts
// folder, or the extension bl_ext.<repository>.hyvox_blender) and calls the entry point the
// add-on declares for farm tasks, hyvox_blender.farm_main(), with the arguments after "--";
// so a job needs no path to the add-on and knows nothing of its inside. COMMAND's arguments
// are the farm task's table (hyvox/farm_task.h).
#include <string>
#include <vector>

#include "hyvox/farm_task.h"

namespace hyvox::farm {

// One line of Python, without single quotes (the job scripts quote it with them).
const std::string& blenderBootstrap();
// The arguments before the .blend and those between it and the farm command.
std::vector<std::string> blenderArgsAfterFile();  // --python-exit-code 1 --python-expr BOOTSTRAP --

// An argument a job writes, and what fills it: the task's frames, a job setting, or a
// voxelize option (then `option`).
struct Argument {
    std::string flag;  // "--frames", "--resolution"
    FarmJobValue source;
    const OptionSpec* option = nullptr;
};

// `run`: voxelize the task's frames with the job's options (every one: run passes on those
// it does not parse itself).
std::vector<Argument> runArguments();
// `assemble`: check the job's frames and save the .blend of the sequence (the size options:
// the frames' voxel size is checked against the job's).
std::vector<Argument> assembleArguments();

}  // namespace hyvox::farm
