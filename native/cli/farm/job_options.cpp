// SPDX-License-Identifier: GPL-3.0-or-later
#include "farm/job_options.h"

#include <cctype>
#include <stdexcept>

#include "farm/yaml_writer.h"

namespace hyvox::farm {
namespace {

std::vector<const OptionSpec*> specs(std::initializer_list<const char*> names) {
    std::vector<const OptionSpec*> out;
    for (const char* name : names) {
        const OptionSpec& spec = findOption(name);
        if (spec.type == OptionType::Vector3 || spec.type == OptionType::Box)
            throw std::logic_error(std::string("a farm parameter cannot hold option ") + name);
        if (spec.nullable && !(spec.type == OptionType::Number && spec.min_exclusive))
            throw std::logic_error(std::string("option ") + name + " has no value that could stand for unset");
        out.push_back(&spec);
    }
    return out;
}

}  // namespace

const std::vector<const OptionSpec*>& blenderJobOptions() {
    static const std::vector<const OptionSpec*> options =
        specs({"resolution", "voxel_size", "mode", "inside", "method", "tess_gamma", "hybrid_cutoff", "padding"});
    return options;
}

const std::vector<const OptionSpec*>& regionJobOptions() {
    static const std::vector<const OptionSpec*> options = [] {
        std::vector<const OptionSpec*> out = blenderJobOptions();
        for (const OptionSpec* spec : specs({"attributes", "memory_budget_mib", "threads"})) out.push_back(spec);
        return out;
    }();
    return options;
}

std::string parameterName(const OptionSpec& spec) {
    std::string out;
    bool upper = true;
    for (const char* c = spec.name; *c; ++c) {
        if (*c == '_') {
            upper = true;
            continue;
        }
        out += upper ? char(std::toupper(static_cast<unsigned char>(*c))) : *c;
        upper = false;
    }
    return out;
}

std::string parameterDescription(const OptionSpec& spec) {
    std::string text = spec.help;
    if (*spec.unit) text += std::string(" [") + spec.unit + "]";
    std::string valid = describeOption(spec);  // "a whole number between 1 and 16384"
    valid[0] = char(std::toupper(static_cast<unsigned char>(valid[0])));
    text += ". " + valid;
    if (spec.nullable) text += "; " + shortestNumber(farmUnsetValue(spec)) + " = unset";
    return text + ".";
}

}  // namespace hyvox::farm
