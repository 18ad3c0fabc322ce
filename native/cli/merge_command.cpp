// SPDX-License-Identifier: GPL-3.0-or-later
#include "merge_command.h"

#include <algorithm>
#include <cstdio>
#include <iterator>

#include "command_support.h"
#include "hyvox/errors.h"
#include "hyvox/stats_json.h"  // checkOutputPath
#include "hyvox/vdb_merge.h"
#include "hyvox/version.h"
#include "progress_line.h"

namespace hyvox::cli {
namespace {

// The write options merge takes too, with the schema's names, limits and help.
const char* const kMergeOptions[] = {"threads", "durable_write"};

}  // namespace

std::string mergeUsageText() {
    std::string text =
        "usage: hyvox merge PART.vdb... -o OUT.vdb [options]\n"
        "\n"
        "Joins the .vdb files of a region job (hyvox voxelize MESH -o PART_K.vdb --region K/N, for\n"
        "K = 0 .. N-1) into one: every grid by name, leaf by leaf, into the file one run over the\n"
        "whole grid writes. Refuses parts that do not fit together (another grid, method, mode or\n"
        "hyvox version), a missing or repeated region, and parts that overlap.\n"
        "\n"
        "command options:\n"
        "  -o, --output FILE\n      the .vdb file to write (written atomically)\n";
    text += commonOptionsHelp();
    text += "\noptions shared with voxelize:\n";
    for (const char* name : kMergeOptions) text += optionHelp(findOption(name));
    return text;
}

Arguments parseMergeArguments(const std::vector<std::string>& args) {
    Arguments out;
    out.command = Command::Merge;
    for (std::size_t a = 1; a < args.size(); ++a) {
        OptionArgument argument(args, a);
        const std::string option = argument.option();
        bool negated = false;
        if (option == "-h" || option == "--help") {
            out.help_topic = Command::Merge;
            out.command = Command::Help;
            return out;
        } else if (option == "-o" || option == "--output") {
            out.output_path = argument.value();
        } else if (takeOutputFlag(argument, out)) {  // -q, --progress
        } else if (const OptionSpec* spec = specForFlag(option, negated)) {
            if (std::none_of(std::begin(kMergeOptions), std::end(kMergeOptions),
                             [&](const char* name) { return std::string(name) == spec->name; }))
                throw UsageError(option + " is not a merge option: the parts were voxelized with it");
            setFromFlag(out, *spec, argument, negated);
        } else if (!option.empty() && option[0] == '-' && option != "-") {
            throw UsageError("unknown option '" + option + "'");
        } else {
            out.part_paths.push_back(option);
        }
    }
    if (out.quiet && out.progress) throw UsageError("--progress and --quiet contradict each other; give one");
    if (out.part_paths.empty()) throw UsageError("no .vdb file given to merge");
    if (out.output_path.empty()) throw UsageError("no output file given (-o OUT.vdb)");
    return out;
}

void runMerge(const Arguments& args, const std::atomic<bool>& stop) {
    const auto thread_limit = limitThreads(args.write.threads);
    checkOutputPath(args.output_path);                   // before the parts are read
    ProgressLine interrupter = progressFor(args, stop);  // Ctrl-C and SIGTERM stop it, nothing written
    MergeOptions options;
    options.threads = args.write.threads;
    options.durable = args.write.durable;
    const MergeReport report = mergeVdbFiles(args.part_paths, args.output_path, options, &interrupter);
    if (args.quiet) return;
    const std::string job = report.regions ? " (the " + std::to_string(report.regions) + " regions of a job)" : "";
    std::printf("hyvox %s: merged %llu files%s -> %s\n", version(), (unsigned long long)report.parts, job.c_str(),
                args.output_path.c_str());
    std::printf("  grids    %llu, density %llu voxels in %llu leaves\n", (unsigned long long)report.grids,
                (unsigned long long)report.voxels, (unsigned long long)report.leaves);
    std::printf("  time ms  read %.1f, write %.1f, total %.1f\n", report.read_ms, report.write_ms,
                report.read_ms + report.write_ms);
}

}  // namespace hyvox::cli
