// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Open Job Description job templates (jobtemplate-2023-09, AWS Deadline Cloud's format):
//
// blenderJobTemplate(): a .blend's animation voxelized into one .vdb per frame. Step
//   Voxelize: tasks are frame chunks (TASK_CHUNKING), each the add-on's farm `run` in
//   Blender; its step environment keeps one Blender per worker session and hands it task
//   after task (farm/session.py), unless SessionBlender is false. Step Assemble, after it:
//   checks every frame's file and saves a .blend with the volume sequence set up.
// regionJobTemplate(): one mesh file's grid split into regions voxelized as tasks by the
//   hyvox CLI (`voxelize --region K/N`), then merged into one .vdb (`merge`).
#include <string>

namespace hyvox::farm {

std::string blenderJobTemplate();
std::string regionJobTemplate();

}  // namespace hyvox::farm
