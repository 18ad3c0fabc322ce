// SPDX-License-Identifier: GPL-3.0-or-later
#include "cli_args.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "hyvox/errors.h"

namespace hyvox::cli {
namespace {

long long parseInteger(const std::string& option, const std::string& text, long long lo, long long hi) {
    errno = 0;
    char* end = nullptr;
    const long long value = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno == ERANGE)
        throw UsageError(option + " needs a whole number, got '" + text + "'");
    if (value < lo || value > hi)
        throw UsageError(option + " must be between " + std::to_string(lo) + " and " + std::to_string(hi) + ", got " +
                         text);
    return value;
}

double parseNumber(const std::string& option, const std::string& text) {
    errno = 0;
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(value))
        throw UsageError(option + " needs a finite number, got '" + text + "'");
    return value;
}

// "1,1.5,2": at least two positive, strictly ascending numbers (the fit needs two points,
// and a sorted table reads as the curve it is).
std::vector<double> parseGammaList(const std::string& option, const std::string& text) {
    std::vector<double> gammas;
    std::size_t begin = 0;
    while (begin <= text.size()) {
        const std::size_t comma = std::min(text.find(',', begin), text.size());
        const double gamma = parseNumber(option, text.substr(begin, comma - begin));
        if (!(gamma > 0)) throw UsageError(option + " needs gammas > 0, got " + text);
        if (!gammas.empty() && !(gamma > gammas.back()))
            throw UsageError(option + " needs ascending gammas, got " + text);
        gammas.push_back(gamma);
        begin = comma + 1;
    }
    if (gammas.size() < 2) throw UsageError(option + " needs at least two gammas to fit Eq. 3, got " + text);
    return gammas;
}

}  // namespace

const char* usageText() {
    return "usage: hyvox voxelize MESH -o OUT.vdb [options]\n"
           "       hyvox gamma-sweep MESH [--gammas 1,1.5,2,3,4,6] [options]\n"
           "       hyvox --help | --version\n"
           "\n"
           "voxelize: voxelizes the surface of a triangle mesh (PLY, PLY.GZ, OBJ, ...) into an\n"
           "OpenVDB file with a float grid 'density' (1 on occupied voxels).\n"
           "gamma-sweep: voxelizes the mesh with the tessellation method at each gamma, prints the\n"
           "share of the exact conservative voxels it misses (bias) and fits Eq. 3,\n"
           "gamma = -B ln(A bias), to tell the gamma a bias needs. Takes the grid, GL and\n"
           "tessellation options below (not --method, --mode, --gamma, -o).\n"
           "\n"
           "options:\n"
           "  -o, --output FILE        the .vdb file to write (written atomically)\n"
           "  --resolution N           voxels along the mesh's longest side (default 256)\n"
           "  --voxel-size S           voxel edge in mesh units (overrides --resolution)\n"
           "  --mode MODE              conservative (26-separating, default) | thin (6-separating)\n"
           "  --method METHOD          cpu (default) | reference | triangle | fragment | hybrid | tessellation\n"
           "  --padding P              empty voxels added on every side (default 0)\n"
           "  --threads T              CPU threads, 0 = all cores (default 0)\n"
           "  --memory-budget-mib M    refuse grids whose bits need more (default 4096)\n"
           "  --stats-json FILE        write origin, voxel size, dims, counts and timings as JSON\n"
           "                           (gamma-sweep: its table and fit)\n"
           "  --gl-device D            GL methods: '' auto, 'software', or a device index\n"
           "  --hybrid-cutoff C        hybrid: large-triangle cutoff in voxel units^2 (<0: auto)\n"
           "  --tess-gamma G, --gamma G  tessellation: safety factor gamma (default 1)\n"
           "  --pn-triangles           tessellation: PN-triangle smoothing\n"
           "  --displacement IMG       tessellation: displace along the normals by an 8/16-bit PNG\n"
           "                           height image sampled at the mesh's UVs (Blender Displace)\n"
           "  --strength S             tessellation: displacement strength in mesh units (default 1)\n"
           "  --midlevel M             tessellation: height that stays in place (default 0.5)\n"
           "  --gammas G1,G2,...       gamma-sweep: the gammas to try, at least two (default 1,1.5,2,3,4,6)\n"
           "  -q, --quiet              print nothing on success\n"
           "  -h, --help               show this help\n"
           "  --version                show the version\n";
}

Arguments parseArguments(const std::vector<std::string>& args) {
    Arguments out;
    if (args.empty()) throw UsageError("no command given");
    if (args[0] == "-h" || args[0] == "--help" || args[0] == "help") return out;
    if (args[0] == "--version" || args[0] == "-V") {
        out.command = Command::Version;
        return out;
    }
    if (args[0] == "voxelize") {
        out.command = Command::Voxelize;
    } else if (args[0] == "gamma-sweep") {
        out.command = Command::GammaSweep;
        out.options.method = Method::Tessellation;
        out.options.tessellation.counts = false;  // the sweep needs only the occupancy
        out.gammas = {1, 1.5, 2, 3, 4, 6};
    } else {
        throw UsageError("unknown command '" + args[0] + "' (the commands are 'voxelize' and 'gamma-sweep')");
    }
    const bool sweep = out.command == Command::GammaSweep;
    auto voxelizeOnly = [&](const std::string& option, const char* why) {
        if (sweep) throw UsageError(option + " is not a gamma-sweep option: " + why);
    };
    const char* kFixedMethod = "the sweep always compares the tessellation method with the exact conservative voxels";

    for (std::size_t a = 1; a < args.size(); ++a) {
        std::string option = args[a];
        std::optional<std::string> inline_value;
        if (option.size() > 2 && option.compare(0, 2, "--") == 0) {
            const auto eq = option.find('=');
            if (eq != std::string::npos) {
                inline_value = option.substr(eq + 1);
                option = option.substr(0, eq);
            }
        }
        auto value = [&]() -> std::string {
            if (inline_value) return *inline_value;
            if (a + 1 >= args.size()) throw UsageError(option + " needs a value");
            return args[++a];
        };
        auto noValue = [&] {
            if (inline_value) throw UsageError(option + " takes no value");
        };
        VoxelizeOptions& o = out.options;
        if (option == "-h" || option == "--help") {
            out.command = Command::Help;
            return out;
        } else if (option == "-o" || option == "--output") {
            voxelizeOnly(option, "the sweep writes no .vdb (--stats-json writes its table)");
            out.output_path = value();
        } else if (option == "--resolution") {
            o.grid.resolution = int(parseInteger(option, value(), 1, kMaxResolution));
        } else if (option == "--voxel-size") {
            const double s = parseNumber(option, value());
            if (!(s > 0)) throw UsageError("--voxel-size must be positive");
            o.grid.voxel_size = s;
        } else if (option == "--mode") {
            voxelizeOnly(option, kFixedMethod);
            try {
                o.mode = parseMode(value());
            } catch (const InvalidInput& e) {
                throw UsageError(e.what());
            }
        } else if (option == "--method") {
            voxelizeOnly(option, kFixedMethod);
            try {
                o.method = parseMethod(value());
            } catch (const InvalidInput& e) {
                throw UsageError(e.what());
            }
        } else if (option == "--padding") {
            o.grid.padding = int(parseInteger(option, value(), 0, 1024));
        } else if (option == "--threads") {
            o.threads = int(parseInteger(option, value(), 0, 4096));
        } else if (option == "--memory-budget-mib") {
            o.memory_budget = std::uint64_t(parseInteger(option, value(), 1, 1ll << 30)) << 20;
        } else if (option == "--stats-json") {
            out.stats_json_path = value();
        } else if (option == "--gl-device") {
            o.gl.device = value();
        } else if (option == "--hybrid-cutoff") {
            o.hybrid.cutoff = parseNumber(option, value());
        } else if (option == "--tess-gamma" || option == "--gamma") {
            voxelizeOnly(option, "it takes --gammas G1,G2,...");
            o.tessellation.gamma = parseNumber(option, value());
        } else if (option == "--gammas") {
            if (!sweep) throw UsageError("--gammas belongs to gamma-sweep; voxelize takes one --gamma");
            out.gammas = parseGammaList(option, value());
        } else if (option == "--displacement") {
            o.tessellation.displacement_image = value();
        } else if (option == "--strength") {
            o.tessellation.displacement_strength = parseNumber(option, value());
        } else if (option == "--midlevel") {
            o.tessellation.displacement_midlevel = parseNumber(option, value());
        } else if (option == "--pn-triangles") {
            noValue();
            o.tessellation.pn_triangles = true;
        } else if (option == "-q" || option == "--quiet") {
            noValue();
            out.quiet = true;
        } else if (!option.empty() && option[0] == '-' && option != "-") {
            throw UsageError("unknown option '" + option + "'");
        } else if (out.mesh_path.empty()) {
            out.mesh_path = option;
        } else {
            throw UsageError("more than one mesh given ('" + out.mesh_path + "' and '" + option + "')");
        }
    }
    if (out.mesh_path.empty()) throw UsageError("no mesh file given");
    if (!sweep && out.output_path.empty()) throw UsageError("no output file given (-o OUT.vdb)");
    return out;
}

}  // namespace hyvox::cli
