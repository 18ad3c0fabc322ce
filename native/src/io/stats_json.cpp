// SPDX-License-Identifier: GPL-3.0-or-later
// A small hand-written JSON writer: the stats are a handful of numbers and names, not worth
// a dependency (Debian's nlohmann-json3-dev is not installed here).
#include "hyvox/stats_json.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <set>
#include <sstream>

#include "hyvox/version.h"
#include "io/atomic_file.h"

namespace hyvox {
namespace {

std::string quote(const std::string& text) {
    std::string out = "\"";
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        switch (c) {
            case '"': out += "\\\""; break;
            case '\\': out += "\\\\"; break;
            case '\n': out += "\\n"; break;
            case '\r': out += "\\r"; break;
            case '\t': out += "\\t"; break;
            default:
                if (c < 0x20) {
                    char buf[8];
                    std::snprintf(buf, sizeof buf, "\\u%04x", c);
                    out += buf;
                } else {
                    out += ch;
                }
        }
    }
    return out + "\"";
}

// Shortest text that reads back as the same double; JSON has no NaN/Inf, so those are null.
std::string number(double value) {
    if (!std::isfinite(value)) return "null";
    char buf[32];
    for (int precision = 15; precision <= 17; ++precision) {
        std::snprintf(buf, sizeof buf, "%.*g", precision, value);
        if (std::strtod(buf, nullptr) == value) break;
    }
    return buf;
}

std::string number(std::uint64_t value) { return std::to_string(value); }

}  // namespace

std::string statsToJson(const VoxelizeResult& result) {
    const Stats& s = result.stats;
    const GridSpec& g = result.grid;
    std::ostringstream out;
    out << "{\n";
    out << "  \"hyvox_version\": " << quote(version()) << ",\n";
    out << "  \"method\": " << quote(s.method) << ",\n";
    out << "  \"mode\": " << quote(s.mode) << ",\n";
    out << "  \"origin\": [" << number(g.origin[0]) << ", " << number(g.origin[1]) << ", " << number(g.origin[2])
        << "],\n";
    out << "  \"voxel_size\": " << number(g.voxel_size) << ",\n";
    out << "  \"dims\": [" << g.dims[0] << ", " << g.dims[1] << ", " << g.dims[2] << "],\n";
    out << "  \"voxel_count\": " << number(s.voxel_count) << ",\n";
    out << "  \"triangles\": {\"input\": " << number(s.triangles_input) << ", \"used\": " << number(s.triangles_used)
        << ", \"degenerate\": " << number(s.triangles_degenerate) << "},\n";
    // Stage names are keys; a stage that ran twice gets "#2", "#3" so no key repeats.
    out << "  \"timings_ms\": {";
    std::set<std::string> used;
    for (std::size_t t = 0; t < s.timings_ms.size(); ++t) {
        std::string key = s.timings_ms[t].first;
        for (int n = 2; !used.insert(key).second; ++n) key = s.timings_ms[t].first + "#" + std::to_string(n);
        out << (t ? ", " : "") << quote(key) << ": " << number(s.timings_ms[t].second);
    }
    out << "},\n";
    out << "  \"total_ms\": " << number(s.totalMs()) << ",\n";
    out << "  \"metrics\": {";
    bool first = true;
    for (const auto& [name, value] : s.metrics) {
        out << (first ? "" : ", ") << quote(name) << ": " << number(value);
        first = false;
    }
    out << "}\n}\n";
    return out.str();
}

void writeTextFileAtomic(const std::string& path, const std::string& text) {
    io::AtomicFile(path).writeWith([&](std::ostream& os) { os << text; });
}

}  // namespace hyvox
