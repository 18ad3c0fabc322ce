// SPDX-License-Identifier: GPL-3.0-or-later
#include "merge_command.h"

#include <cstdio>
#include <cstdlib>

#include "command_support.h"
#include "hyvox/errors.h"
#include "hyvox/stats_json.h"  // checkOutputPath
#include "hyvox/vdb_merge.h"
#include "hyvox/version.h"
#include "progress_line.h"

namespace hyvox::cli {
namespace {

// The voxelize options merge takes too, with the schema's names, limits and help.
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
        std::string option = args[a];
        std::string inline_value;
        bool has_inline = false;
        if (option.size() > 2 && option.compare(0, 2, "--") == 0 && option.find('=') != std::string::npos) {
            inline_value = option.substr(option.find('=') + 1);
            option = option.substr(0, option.find('='));
            has_inline = true;
        }
        auto value = [&]() -> std::string {
            if (has_inline) return inline_value;
            if (a + 1 >= args.size()) throw UsageError(option + " needs a value");
            return args[++a];
        };
        auto noValue = [&] {
            if (has_inline) throw UsageError(option + " takes no value");
        };
        if (option == "-h" || option == "--help") {
            out.help_topic = Command::Merge;
            out.command = Command::Help;
            return out;
        }
        if (option == "-o" || option == "--output") {
            out.output_path = value();
            continue;
        }
        if (option == "-q" || option == "--quiet") {
            noValue();
            out.quiet = true;
            continue;
        }
        if (option == "--progress") {
            noValue();
            out.progress = true;
            continue;
        }
        const OptionSpec* spec = nullptr;
        bool negated = false;
        for (const char* name : kMergeOptions) {
            const OptionSpec& candidate = findOption(name);
            if (option == candidate.cliFlag()) spec = &candidate;
            if (candidate.type == OptionType::Flag && option == "--no-" + candidate.cliFlag().substr(2)) {
                spec = &candidate;
                negated = true;
            }
        }
        if (spec) {
            try {
                OptionValue parsed;
                if (spec->type == OptionType::Flag && !has_inline)
                    parsed = !negated;
                else if (negated)
                    throw UsageError(option + " takes no value");
                else
                    parsed = parseOptionText(*spec, value());
                setOption(out.options, spec->name, parsed);
            } catch (const InvalidInput& e) {
                throw UsageError(option + ": " + e.what());
            }
            continue;
        }
        if (!option.empty() && option[0] == '-' && option != "-") throw UsageError("unknown option '" + option + "'");
        out.part_paths.push_back(option);
    }
    if (out.quiet && out.progress) throw UsageError("--progress and --quiet contradict each other; give one");
    if (out.part_paths.empty()) throw UsageError("no .vdb file given to merge");
    if (out.output_path.empty()) throw UsageError("no output file given (-o OUT.vdb)");
    return out;
}

void runMerge(const Arguments& args, const std::atomic<bool>& stop) {
    const auto thread_limit = limitThreads(args.options.threads);
    checkOutputPath(args.output_path);  // before the parts are read
    ProgressLine interrupter = progressFor(args, stop);  // Ctrl-C and SIGTERM stop it, nothing written
    MergeOptions options;
    options.threads = args.options.threads;
    options.durable_write = args.options.durable_write;
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
