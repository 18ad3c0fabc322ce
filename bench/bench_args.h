// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Helpers shared by the benchmark programs (never part of the library, so a usage error
// may end the process).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "hyvox/gl_devices.h"
#include "hyvox/option_schema.h"

namespace hyvox::bench {

// The environment variables the options schema names (HYVOX_GL_DEVICE, HYVOX_SHADER_DIR,
// HYVOX_GL_TILE_BYTES, ...), set and not empty, read into `options` as the CLI reads them:
// the library itself reads none. A bad value throws InvalidInput with the schema's message.
inline void readEnvironment(VoxelizeOptions& options) {
    for (const OptionSpec& spec : optionSchema())
        if (const char* value = spec.env ? std::getenv(spec.env) : nullptr; value && *value)
            setOption(options, spec.name, parseOptionText(spec, value));
}

// The value that follows the option argv[a], advancing a past it; a missing value prints
// "<option> needs a value" and exits with status 2.
inline std::string optionValue(int argc, char** argv, int& a) {
    if (a + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", argv[a]);
        std::exit(2);
    }
    return argv[++a];
}

// A positive whole number (at most 2^20) for `option`, or the message, `usage` and exit status 2.
inline int positiveValue(const char* option, const std::string& text, const char* usage) {
    char* end = nullptr;
    const long value = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || value < 1 || value > 1 << 20) {
        std::fprintf(stderr, "%s needs a positive whole number, not '%s'\n%s", option, text.c_str(), usage);
        std::exit(2);
    }
    return int(value);
}

// The command line the mesh benchmarks share: --runs R, --res N (repeatable), --mesh-dir DIR
// (default $HYVOX_MESH_DIR, else `default_mesh_dir`), -h/--help (prints `usage`, exits 0) and the
// mesh files; `more(arg, a)` takes a benchmark's own options (advancing `a` past a value) and
// returns false for an unknown one (then the usage and exit status 2).
struct MeshBenchArgs {
    int runs = 3;
    std::vector<int> resolutions;
    std::string mesh_dir;
    std::vector<std::string> files;
};
template <typename More>
MeshBenchArgs parseMeshBenchArgs(int argc, char** argv, const char* usage, const char* default_mesh_dir, More more) {
    MeshBenchArgs args;
    args.mesh_dir = std::getenv("HYVOX_MESH_DIR") ? std::getenv("HYVOX_MESH_DIR") : default_mesh_dir;
    for (int a = 1; a < argc; ++a) {
        const std::string arg = argv[a];
        if (arg == "--help" || arg == "-h") {
            std::fputs(usage, stdout);
            std::exit(0);
        }
        if (arg == "--runs")
            args.runs = positiveValue("--runs", optionValue(argc, argv, a), usage);
        else if (arg == "--res")
            args.resolutions.push_back(positiveValue("--res", optionValue(argc, argv, a), usage));
        else if (arg == "--mesh-dir")
            args.mesh_dir = optionValue(argc, argv, a);
        else if (arg.size() > 1 && arg[0] == '-') {
            if (more(arg, a)) continue;
            std::fprintf(stderr, "unknown option '%s'\n%s", arg.c_str(), usage);
            std::exit(2);
        } else
            args.files.push_back(arg);
    }
    return args;
}

// The same with --out DIR as the one option of the benchmark's own, into `out_dir`.
inline MeshBenchArgs parseMeshBenchArgs(int argc, char** argv, const char* usage, const char* default_mesh_dir,
                                        std::string& out_dir) {
    return parseMeshBenchArgs(argc, argv, usage, default_mesh_dir, [&](const std::string& arg, int& a) {
        if (arg != "--out") return false;
        out_dir = optionValue(argc, argv, a);
        return true;
    });
}

// "a,b,,c" -> {"a", "b", "c"}: a comma-separated command-line list, empty items dropped.
inline std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ','))
        if (!item.empty()) out.push_back(item);
    return out;
}

// The median of repeated timings (mean of the middle two for an even count; 0 for none).
inline double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// The EGL devices the GL methods can use, for a results header: "EGL: software" or
// "EGL: /dev/dri/renderD128, software" (the GL methods take the first hardware one).
inline std::string glDevicesText() {
    std::string text;
    for (const GlDevice& device : listGlDevices()) text += (text.empty() ? "EGL: " : ", ") + device.name;
    return text.empty() ? "EGL: no device" : text;
}

}  // namespace hyvox::bench
