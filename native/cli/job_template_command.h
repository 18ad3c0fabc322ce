// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// `hyvox job-template KIND [-o FILE]`: prints (or writes) a render-farm job generated from
// the options schema: openjd (the Blender job, Open Job Description / Deadline Cloud),
// openjd-regions (one mesh's grid as region tasks and a merge), flamenco (the Blender job
// as a Flamenco job type, hyvox.js).
#include <string>
#include <vector>

namespace hyvox::cli {

// args: what follows "job-template". Throws UsageError for a mistake.
void runJobTemplate(const std::vector<std::string>& args);
std::string jobTemplateUsage();

}  // namespace hyvox::cli
