// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The voxelize options a farm job offers, as job parameters derived from the options
// schema (hyvox/option_schema.h): the parameter's name is the option's in CamelCase
// (voxel_size -> VoxelSize), and its type, default, limits, choices and help are the
// schema's. A farm parameter always has a value: an option the schema lets be unset
// (voxel_size) takes farmUnsetValue() (hyvox/farm_task.h) then, and the task leaves it out.
#include <string>
#include <vector>

#include "hyvox/farm_task.h"

namespace hyvox::farm {

// The options of the Blender job: those the add-on's headless script takes (cli_blender.py:
// method and the scene's settings, blender/properties.py SCENE_OPTIONS).
const std::vector<const OptionSpec*>& blenderJobOptions();
// The options of the region job (the hyvox CLI takes every one): the Blender job's, the
// attribute grids and the resources a task may use.
const std::vector<const OptionSpec*>& regionJobOptions();

std::string parameterName(const OptionSpec& spec);  // "VoxelSize"
// The parameter's description: the schema's help, unit, what a valid value is, and for a
// nullable option what the unset value means.
std::string parameterDescription(const OptionSpec& spec);

}  // namespace hyvox::farm
