// SPDX-License-Identifier: GPL-3.0-or-later
#include "hyvox/farm_task.h"

#include <cstdlib>
#include <map>
#include <regex>

#include "hyvox/errors.h"

namespace hyvox {
namespace {

FarmTaskArgument text(const char* flag, std::vector<std::string> aliases, bool run, bool assemble, bool required,
                      const char* default_text, const char* help, FarmJobValue job) {
    return {flag, std::move(aliases), run, assemble, required, FarmValue::Text, nullptr, default_text, help, job};
}

FarmTaskArgument option(const char* name, std::vector<std::string> aliases) {
    const OptionSpec& spec = findOption(name);
    return {spec.cliFlag(), std::move(aliases),  true, true, false, FarmValue::Option, &spec, nullptr,
            spec.help,      FarmJobValue::Option};
}

FarmTaskArgument toggle(const char* flag, const char* help) {
    return {flag, {}, true, true, false, FarmValue::Switch, nullptr, nullptr, help, FarmJobValue::None};
}

// The flag's spellings as argparse names it in messages: "--output/-o".
std::string spelled(const FarmTaskArgument& arg) {
    std::string out = arg.flag;
    for (const std::string& alias : arg.aliases) out += "/" + alias;
    return out;
}

// What argparse takes for a flag's value rather than for another flag: not starting with '-',
// or a negative number, a lone "-", or text with a space.
bool isValue(const std::string& token) {
    static const std::regex negative_number("^-\\d+$|^-\\d*\\.\\d+$");
    if (token.empty() || token[0] != '-' || token == "-") return true;
    if (token == "--") return false;
    return std::regex_match(token, negative_number) || token.find(' ') != std::string::npos;
}

// Whether `text` is what Python's int() / float() reads (the decimal forms a job writes).
bool parses(OptionType type, const std::string& text) {
    if (text.empty() || text.find_first_of("xX") != std::string::npos) return false;
    char* end = nullptr;
    if (type == OptionType::Integer)
        static_cast<void>(std::strtoll(text.c_str(), &end, 10));  // out of range: still a whole number
    else
        static_cast<void>(std::strtod(text.c_str(), &end));
    return *end == '\0';
}

void checkValue(const FarmTaskArgument& arg, const std::string& value) {
    if (arg.value != FarmValue::Option || parses(arg.option->type, value)) return;
    const char* kind = arg.option->type == OptionType::Integer ? "int" : "float";
    throw InvalidInput("argument " + spelled(arg) + ": invalid " + kind + " value: '" + value + "'");
}

}  // namespace

const std::vector<FarmTaskArgument>& farmTaskArguments() {
    static const std::vector<FarmTaskArgument> table = [] {
        std::vector<FarmTaskArgument> out{
            text("--frames", {}, true, false, true, nullptr, "the frames of this task, e.g. 11-20",
                 FarmJobValue::TaskFrames),
            text("--job-frames", {}, true, true, true, nullptr, "every frame of the job, e.g. 1-250",
                 FarmJobValue::JobFrames),
            text("--output", {"-o"}, true, true, true, nullptr, "folder of the .vdb files", FarmJobValue::OutputDir),
            text("--objects", {}, true, true, false, "", "comma-separated object names ('': cli_blender's choice)",
                 FarmJobValue::Objects),
            text("--blend", {}, true, true, false, nullptr, "open this .blend first", FarmJobValue::None),
            // The job's voxel size comes from these two (the task plans the first frame's
            // grid); the other voxelize options `run` passes on to the headless script.
            option("resolution", {"-r"}),
            option("voxel_size", {}),
            toggle("--viewport", "evaluate modifiers at viewport settings (default: render settings)"),
            text("--save", {}, false, true, false, nullptr,
                 "the .blend to write (default: OUTPUT/<scene>_voxels.blend)", FarmJobValue::None),
        };
        return out;
    }();
    return table;
}

FarmCommand parseFarmCommand(const std::string& name) {
    if (name == "run") return FarmCommand::Run;
    if (name == "assemble") return FarmCommand::Assemble;
    throw InvalidInput("unknown farm command '" + name + "' (run, assemble)");
}

double farmUnsetValue(const OptionSpec& spec) { return spec.min; }

void checkFarmTask(FarmCommand command, const std::vector<std::string>& args) {
    std::map<std::string, const FarmTaskArgument*> flags;
    for (const FarmTaskArgument& arg : farmTaskArguments()) {
        if (!arg.takenBy(command)) continue;
        flags[arg.flag] = &arg;
        for (const std::string& alias : arg.aliases) flags[alias] = &arg;
    }
    std::map<const FarmTaskArgument*, bool> given;
    std::vector<std::string> unknown;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& token = args[i];
        if (token == "--") {  // the rest is not the task's
            unknown.insert(unknown.end(), args.begin() + std::ptrdiff_t(i), args.end());
            break;
        }
        auto found = flags.find(token);
        const std::size_t equals = token.find('=');
        if (found == flags.end() && equals != std::string::npos && !token.empty() && token[0] == '-')
            found = flags.find(token.substr(0, equals));
        if (found == flags.end()) {
            unknown.push_back(token);
            continue;
        }
        const FarmTaskArgument& arg = *found->second;
        given[&arg] = true;
        const bool inline_value = found->first != token;
        if (arg.value == FarmValue::Switch) {
            if (inline_value)
                throw InvalidInput("argument " + spelled(arg) + ": ignored explicit argument '" +
                                   token.substr(equals + 1) + "'");
            continue;
        }
        if (inline_value) {
            checkValue(arg, token.substr(equals + 1));
        } else {
            if (i + 1 == args.size() || !isValue(args[i + 1]))
                throw InvalidInput("argument " + spelled(arg) + ": expected one argument");
            checkValue(arg, args[++i]);
        }
    }
    std::string missing;
    for (const FarmTaskArgument& arg : farmTaskArguments())
        if (arg.takenBy(command) && arg.required && !given.count(&arg))
            missing += (missing.empty() ? "" : ", ") + spelled(arg);
    if (!missing.empty()) throw InvalidInput("the following arguments are required: " + missing);
    if (command == FarmCommand::Assemble && !unknown.empty()) {
        std::string text;
        for (const std::string& token : unknown) text += (text.empty() ? "" : " ") + token;
        throw InvalidInput("assemble does not take " + text);
    }
}

}  // namespace hyvox
