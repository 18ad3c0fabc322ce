// SPDX-License-Identifier: GPL-3.0-or-later
#include "cli_args.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <utility>

#include "hyvox/errors.h"
#include "hyvox/option_schema.h"
#include "merge_command.h"

namespace hyvox::cli {
namespace {

// The voxelize options gamma-sweep sets itself, and why.
const char* sweepFixes(const std::string& name) {
    if (name == "mode" || name == "method")
        return "the sweep always compares the tessellation method with the exact conservative voxels";
    if (name == "tess_gamma") return "it takes --gammas G1,G2,...";
    if (name == "region") return "the sweep measures the whole grid";
    return nullptr;
}

// "1,1.5,2": at least two positive, strictly ascending numbers (the fit needs two points,
// and a sorted table reads as the curve it is).
std::vector<double> parseGammaList(const std::string& option, const std::string& text) {
    const std::vector<double> gammas = parseNumberList(text);
    if (gammas.empty()) throw UsageError(option + " needs finite numbers, got '" + text + "'");
    for (std::size_t n = 0; n < gammas.size(); ++n) {
        if (!std::isfinite(gammas[n])) throw UsageError(option + " needs finite numbers, got '" + text + "'");
        if (!(gammas[n] > 0)) throw UsageError(option + " needs gammas > 0, got " + text);
        if (n > 0 && !(gammas[n] > gammas[n - 1])) throw UsageError(option + " needs ascending gammas, got " + text);
    }
    if (gammas.size() < 2) throw UsageError(option + " needs at least two gammas to fit Eq. 3, got " + text);
    return gammas;
}

}  // namespace

const OptionSpec* specForFlag(const std::string& flag, bool& negated) {
    for (const OptionSpec& spec : optionSchema()) {
        const std::string own = spec.cliFlag();
        negated = spec.type == OptionType::Flag && flag == "--no-" + own.substr(2);
        if (flag == own || negated) return &spec;
        for (const char* alias : spec.cli_aliases)
            if (flag == alias) return &spec;
    }
    negated = false;
    return nullptr;
}

OptionArgument::OptionArgument(const std::vector<std::string>& args, std::size_t& at)
    : args_(args), at_(at), option_(args[at]) {
    if (option_.size() > 2 && option_.compare(0, 2, "--") == 0) {
        const auto eq = option_.find('=');
        if (eq != std::string::npos) {
            inline_value_ = option_.substr(eq + 1);
            option_ = option_.substr(0, eq);
        }
    }
}

std::string OptionArgument::value() {
    if (inline_value_) return *inline_value_;
    if (at_ + 1 >= args_.size()) throw UsageError(option_ + " needs a value");
    return args_[++at_];
}

void OptionArgument::noValue() const {
    if (inline_value_) throw UsageError(option_ + " takes no value");
}

bool takeOutputFlag(OptionArgument& argument, Arguments& out) {
    const std::string& option = argument.option();
    if (option != "-q" && option != "--quiet" && option != "--progress") return false;
    argument.noValue();
    (option == "--progress" ? out.progress : out.quiet) = true;
    return true;
}

void setFromFlag(Arguments& out, const OptionSpec& spec, OptionArgument& argument, bool negated) {
    const std::string& flag = argument.option();
    try {
        OptionValue parsed;
        if (spec.type == OptionType::Flag && !argument.hasInlineValue())
            parsed = !negated;
        else if (negated)
            throw UsageError(flag + " takes no value");
        else
            parsed = parseOptionText(spec, argument.value());
        // One flag, both structs where the option is both (threads, memory_budget_mib).
        if (spec.isVoxelizeOption()) setOption(out.options, spec.name, parsed);
        if (spec.isWriteOption()) setOption(out.write, spec.name, parsed);
    } catch (const InvalidInput& e) {  // the schema's message, after the flag as typed
        throw UsageError(flag + ": " + e.what());
    }
}

namespace {

std::string placeholder(const OptionSpec& spec) {
    switch (spec.type) {
        case OptionType::Integer: return " N";
        case OptionType::Number: return " X";
        case OptionType::Flag: return "";
        case OptionType::Text: return std::string(" ") + (spec.text_form ? spec.text_form : "TEXT");
        case OptionType::Choice:
        case OptionType::Choices: {
            const char* between = spec.type == OptionType::Choice ? "|" : ",";
            std::string choices;
            for (const char* c : spec.choices) choices += (choices.empty() ? " " : between) + std::string(c);
            return choices;
        }
        case OptionType::Vector3: return " X,Y,Z";
        case OptionType::Box: return " X0,Y0,Z0,X1,Y1,Z1";
    }
    return "";
}

}  // namespace

std::string optionHelp(const OptionSpec& spec) {
    std::string flag = "  " + spec.cliFlag() + placeholder(spec);
    if (spec.type == OptionType::Flag) flag += ", --no-" + spec.cliFlag().substr(2);
    for (const char* alias : spec.cli_aliases) flag += std::string(", ") + alias + placeholder(spec);
    std::string line = flag + "\n      " + spec.help;
    if (*spec.unit) line += std::string(" [") + spec.unit + "]";
    if (!spec.nullable) {
        const std::string value = formatOptionValue(spec.defaultValue());
        line += " (default " + (value == "''" ? std::string("none") : value) + ")";
    }
    if (spec.env) line += std::string(" (env ") + spec.env + ")";
    return line + "\n";
}

std::string commonOptionsHelp() {
    return "  --progress\n      show progress on stderr also when it is not a terminal (a log, a pipe)\n"
           "  -q, --quiet\n      print nothing on success, no progress\n"
           "  -h, --help\n      show this help\n";
}

namespace {

// The schema's options, less those the command sets itself (fixed(name) not null).
std::string voxelizeOptionsHelp(const char* (*fixed)(const std::string&)) {
    std::string text =
        "\nvoxelize options (the same names as the keywords of hyvox.voxelize and, for the output,\n"
        "VoxelGrid.write_vdb; a flag's value may also be given as --name=true|false; environment\n"
        "variables apply unless the flag is given):\n";
    for (const OptionSpec& spec : optionSchema())
        if (!fixed || !fixed(spec.name)) text += optionHelp(spec);
    return text;
}

}  // namespace

std::string usageText(Command topic) {
    if (topic == Command::Merge) return mergeUsageText();
    if (topic == Command::Voxelize) {
        std::string text =
            "usage: hyvox voxelize MESH -o OUT.vdb [options]\n"
            "\n"
            "Voxelizes the surface of a triangle mesh (PLY, PLY.GZ, OBJ, ...) into an OpenVDB file\n"
            "with a float grid 'density' (1 on occupied voxels); with --attributes, also 'color'\n"
            "(Vec3f, linear), 'alpha' (float, when the colours have it) and 'normal' (Vec3f).\n"
            "\n"
            "command options:\n"
            "  -o, --output FILE\n      the .vdb file to write (written atomically)\n"
            "  --stats-json FILE\n      write the grid, counts, timings, options and the method's figures as JSON\n"
            "  --texture IMG\n      a PNG sampled at the mesh's UVs for --attributes color (else the file's vertex\n"
            "      colours are used, else an OBJ's materials: MTL Kd and map_Kd)\n";
        return text + commonOptionsHelp() + voxelizeOptionsHelp(nullptr);
    }
    if (topic == Command::GammaSweep) {
        std::string text =
            "usage: hyvox gamma-sweep MESH [--gammas 1,1.5,2,3,4,6] [options]\n"
            "\n"
            "Voxelizes the mesh with the tessellation method at each gamma, prints the share of the\n"
            "exact conservative voxels it misses (bias), of the exact thin voxels (bias_thin), the\n"
            "voxels inside the thin set a flood from outside reaches (leaked; 0 = watertight) and\n"
            "fits Eq. 3, gamma = -B ln(A bias), to tell the gamma a bias needs.\n"
            "\n"
            "command options:\n"
            "  --gammas G1,G2,...\n      the gammas to try, at least two, ascending (default 1,1.5,2,3,4,6)\n"
            "  --stats-json FILE\n      write the table and the fit as JSON\n";
        return text + commonOptionsHelp() + voxelizeOptionsHelp(sweepFixes);
    }
    return "usage: hyvox voxelize MESH -o OUT.vdb [options]\n"
           "       hyvox gamma-sweep MESH [--gammas 1,1.5,2,3,4,6] [options]\n"
           "       hyvox merge PART.vdb... -o OUT.vdb [options]\n"
           "       hyvox job-template openjd|openjd-regions|flamenco [-o FILE]\n"
           "       hyvox --help | --version\n"
           "\n"
           "commands:\n"
           "  voxelize      voxelize the surface of a triangle mesh into an OpenVDB file\n"
           "  gamma-sweep   measure how many voxels the tessellation method misses at each gamma\n"
           "  merge         join the .vdb files of the regions of one grid into the grid's file\n"
           "  job-template  print a render-farm job (Open Job Description, Flamenco) for hyvox\n"
           "\n"
           "'hyvox COMMAND --help' shows the options of a command.\n";
}

namespace {

Arguments parseCommand(const std::vector<std::string>& args);

}  // namespace

Arguments parseArguments(const std::vector<std::string>& args) {
    if (args.empty()) throw UsageError("no command given");
    try {
        return parseCommand(args);
    } catch (const UsageError& e) {
        // A mistake after a known command points at that command's own help.
        if (args[0] == "voxelize" || args[0] == "gamma-sweep" || args[0] == "merge")
            throw UsageError(e.what(), "hyvox " + args[0] + " --help lists its options");
        throw;
    }
}

namespace {

Arguments parseCommand(const std::vector<std::string>& args) {
    Arguments out;
    if (args.empty()) throw UsageError("no command given");
    if (args[0] == "-h" || args[0] == "--help" || args[0] == "help") return out;
    if (args[0] == "--version" || args[0] == "-V") {
        out.command = Command::Version;
        return out;
    }
    if (args[0] == "merge") return parseMergeArguments(args);
    if (args[0] == "voxelize") {
        out.command = Command::Voxelize;
    } else if (args[0] == "gamma-sweep") {
        out.command = Command::GammaSweep;
        out.options.method = Method::Tessellation;
        out.options.tessellation.counts = false;  // the sweep needs only the occupancy
        out.gammas = {1, 1.5, 2, 3, 4, 6};
    } else {
        throw UsageError("unknown command '" + args[0] +
                         "' (the commands are 'voxelize', 'gamma-sweep', 'merge' and 'job-template')");
    }
    try {
        applyEnvironment(out.options, [](const char* variable) -> const char* { return std::getenv(variable); });
    } catch (const InvalidInput& e) {
        throw UsageError(e.what());
    }
    const bool sweep = out.command == Command::GammaSweep;
    std::vector<std::pair<std::string, const OptionSpec*>> given;  // flag as typed, its option

    for (std::size_t a = 1; a < args.size(); ++a) {
        OptionArgument argument(args, a);
        const std::string option = argument.option();
        auto value = [&] { return argument.value(); };
        bool negated = false;
        if (option == "-h" || option == "--help") {
            out.help_topic = out.command;
            out.command = Command::Help;
            return out;
        } else if (option == "-o" || option == "--output") {
            if (sweep)
                throw UsageError(option +
                                 " is not a gamma-sweep option: the sweep writes no .vdb "
                                 "(--stats-json writes its table)");
            out.output_path = value();
        } else if (option == "--stats-json") {
            out.stats_json_path = value();
        } else if (option == "--texture") {
            if (sweep) throw UsageError(option + " is not a gamma-sweep option: the sweep computes no attributes");
            out.texture_path = value();
        } else if (option == "--gammas") {
            if (!sweep) throw UsageError("--gammas belongs to gamma-sweep; voxelize takes one --tess-gamma");
            out.gammas = parseGammaList(option, value());
        } else if (takeOutputFlag(argument, out)) {  // -q, --progress
        } else if (const OptionSpec* spec = specForFlag(option, negated)) {
            if (sweep)
                if (const char* why = sweepFixes(spec->name))
                    throw UsageError(option + " is not a gamma-sweep option: " + why);
            given.emplace_back(option, spec);
            setFromFlag(out, *spec, argument, negated);
        } else if (!option.empty() && option[0] == '-' && option != "-") {
            throw UsageError("unknown option '" + option + "'");
        } else if (out.mesh_path.empty()) {
            out.mesh_path = option;
        } else {
            throw UsageError("more than one mesh given ('" + out.mesh_path + "' and '" + option + "')");
        }
    }
    // Options another method would use are not an error (a script may pass one set of flags
    // to every method), but they must not be ignored silently.
    for (const auto& [flag, spec] : given)
        if (!optionAppliesTo(*spec, out.options.method))
            out.warnings.push_back(flag + " does not apply to the " + toString(out.options.method) +
                                   " method: ignored");
    if (out.quiet && out.progress) throw UsageError("--progress and --quiet contradict each other; give one");
    if (out.mesh_path.empty()) throw UsageError("no mesh file given");
    if (!sweep && out.output_path.empty()) throw UsageError("no output file given (-o OUT.vdb)");
    return out;
}

}  // namespace

}  // namespace hyvox::cli
