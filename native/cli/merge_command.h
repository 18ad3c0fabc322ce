// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// `hyvox merge PART.vdb... -o OUT.vdb`: the .vdb files of a region job joined into the file
// the one-machine run writes (hyvox/vdb_merge.h).
#include <atomic>
#include <string>
#include <vector>

#include "cli_args.h"

namespace hyvox::cli {

// args[0] is "merge"; UsageError for anything but parts, -o, --threads, --durable-write,
// --progress, --quiet and --help.
Arguments parseMergeArguments(const std::vector<std::string>& args);
std::string mergeUsageText();
void runMerge(const Arguments& args, const std::atomic<bool>& stop);

}  // namespace hyvox::cli
