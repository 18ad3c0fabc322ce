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
