// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The Blender job as a Flamenco job type (hyvox.js, for the Manager's scripts/ folder): the
// same settings (the voxelize options from the options schema) and the same headless
// command lines as the Open Job Description template, one blender-render command per
// frame chunk (frameChunker), then an assemble task that depends on them all.
#include <string>

namespace hyvox::farm {

std::string flamencoJobType();

}  // namespace hyvox::farm
