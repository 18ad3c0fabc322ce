// SPDX-License-Identifier: GPL-3.0-or-later
#include "job_template_command.h"

#include <cstdio>

#include "cli_args.h"
#include "farm/flamenco_job_type.h"
#include "farm/openjd_templates.h"
#include "hyvox/stats_json.h"

namespace hyvox::cli {
namespace {

struct Kind {
    const char* name;
    std::string (*generate)();
    const char* what;
};

const Kind kKinds[] = {
    {"openjd", farm::blenderJobTemplate,
     "Open Job Description template (Deadline Cloud): a .blend's frames as chunked tasks"},
    {"openjd-regions", farm::regionJobTemplate,
     "Open Job Description template: one mesh's grid as region tasks and a merge"},
    {"flamenco", farm::flamencoJobType,
     "Flamenco job type (hyvox.js, for the Manager's scripts/ folder): a .blend's frames"},
};

}  // namespace

std::string jobTemplateUsage() {
    std::string text =
        "usage: hyvox job-template KIND [-o FILE]\n"
        "\n"
        "Prints a render-farm job for hyvox, its settings generated from the options schema\n"
        "(docs/farm.md tells how to install each):\n";
    for (const Kind& kind : kKinds) text += std::string("  ") + kind.name + "\n      " + kind.what + "\n";
    return text +
        "\ncommand options:\n  -o, --output FILE\n      write it to FILE (atomically) instead of printing it\n"
        "  -h, --help\n      show this help\n";
}

void runJobTemplate(const std::vector<std::string>& args) {
    const Kind* kind = nullptr;
    std::string output;
    for (std::size_t a = 0; a < args.size(); ++a) {
        const std::string& arg = args[a];
        if (arg == "-h" || arg == "--help") {
            std::fputs(jobTemplateUsage().c_str(), stdout);
            return;
        }
        if (arg == "-o" || arg == "--output") {
            if (a + 1 >= args.size()) throw UsageError(arg + " needs a value", "hyvox job-template --help");
            output = args[++a];
            continue;
        }
        if (kind)
            throw UsageError("more than one kind given ('" + std::string(kind->name) + "' and '" + arg + "')",
                             "hyvox job-template --help");
        for (const Kind& k : kKinds)
            if (arg == k.name) kind = &k;
        if (!kind)
            throw UsageError("unknown job kind '" + arg + "' (openjd, openjd-regions, flamenco)",
                             "hyvox job-template --help");
    }
    if (!kind) throw UsageError("no job kind given (openjd, openjd-regions, flamenco)", "hyvox job-template --help");
    const std::string text = kind->generate();
    if (output.empty())
        std::fputs(text.c_str(), stdout);
    else
        writeTextFileAtomic(output, text);
}

}  // namespace hyvox::cli
