// SPDX-License-Identifier: GPL-3.0-or-later
// A small hand-written JSON writer: the stats are a handful of numbers and names, not worth
// a dependency (Debian's nlohmann-json3-dev is not installed here).
#include "hyvox/stats_json.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <sstream>
#include <variant>

#include "hyvox/json_text.h"
#include "hyvox/option_schema.h"
#include "hyvox/version.h"
#include "os/atomic_file.h"

namespace hyvox {

namespace {
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
// Section fields are numbers, and a few are names (the solid section's rule and reason).
std::string number(const std::string& text) { return jsonQuote(text); }

std::string json(const OptionValue& value) {
    struct Json {
        std::string operator()(std::monostate) const { return "null"; }
        std::string operator()(std::int64_t v) const { return std::to_string(v); }
        std::string operator()(double v) const { return number(v); }
        std::string operator()(bool v) const { return v ? "true" : "false"; }
        std::string operator()(const std::string& v) const { return jsonQuote(v); }
        std::string operator()(const std::array<double, 3>& v) const {
            return "[" + number(v[0]) + ", " + number(v[1]) + ", " + number(v[2]) + "]";
        }
        std::string operator()(const Bounds& b) const { return "[" + (*this)(b.min) + ", " + (*this)(b.max) + "]"; }
    };
    return std::visit(Json{}, value);
}

}  // namespace

std::string statsToJson(const VoxelizeResult& result) {
    const Stats& s = result.stats;
    const GridSpec& g = result.grid;
    std::ostringstream out;
    out << "{\n";
    out << "  \"hyvox_version\": " << jsonQuote(version()) << ",\n";
    out << "  \"method\": " << jsonQuote(s.method) << ",\n";
    out << "  \"mode\": " << jsonQuote(s.mode) << ",\n";
    out << "  \"origin\": [" << number(g.origin[0]) << ", " << number(g.origin[1]) << ", " << number(g.origin[2])
        << "],\n";
    out << "  \"voxel_size\": " << number(g.voxel_size) << ",\n";
    out << "  \"dims\": [" << g.dims[0] << ", " << g.dims[1] << ", " << g.dims[2] << "],\n";
    if (s.region) {  // the box a region's run voxelized, voxels [lo, hi) of the grid
        const RegionBox& box = *s.region;
        out << "  \"region\": {\"index\": " << s.options.region.index << ", \"count\": " << s.options.region.count
            << ", \"axis\": " << jsonQuote(std::string(1, "xyz"[box.axis])) << ", \"lo\": [" << box.lo[0] << ", "
            << box.lo[1] << ", " << box.lo[2] << "], \"hi\": [" << box.hi[0] << ", " << box.hi[1] << ", " << box.hi[2]
            << "]},\n";
    }
    out << "  \"voxel_count\": " << number(s.voxel_count) << ",\n";
    out << "  \"leaves\": " << number(s.leaves) << ",\n";
    out << "  \"tiles\": " << number(s.tiles) << ",\n";
    if (s.vdb_bytes) out << "  \"vdb_bytes\": " << number(s.vdb_bytes) << ",\n";
    if (s.attribute_pieces || s.options.attributes.surfaceValues()) {  // tessellation: no clipped pieces
        out << "  \"attribute_pieces\": " << number(s.attribute_pieces) << ",\n";
        out << "  \"attribute_leaves_rounded\": " << number(s.attribute_leaves_rounded) << ",\n";
        out << "  \"attribute_voxels_unreached\": " << number(s.attribute_voxels_unreached) << ",\n";
    }
    out << "  \"triangles\": {\"input\": " << number(s.triangles_input) << ", \"used\": " << number(s.triangles_used)
        << ", \"degenerate\": " << number(s.triangles_degenerate) << "},\n";
    // Stage names are keys: Stats::addTiming sums a stage that ran again (once per tile).
    out << "  \"timings_ms\": {";
    for (std::size_t t = 0; t < s.timings_ms.size(); ++t)
        out << (t ? ", " : "") << jsonQuote(s.timings_ms[t].first) << ": " << number(s.timings_ms[t].second);
    out << "},\n";
    out << "  \"total_ms\": " << number(s.totalMs()) << ",\n";
    // The options the run used, by their schema names (unset ones are left out).
    out << "  \"options\": {";
    bool first = true;
    for (const OptionSpec& spec : optionSchema()) {
        if (!spec.isVoxelizeOption()) continue;
        const OptionValue value = spec.get(s.options);
        if (std::holds_alternative<std::monostate>(value)) continue;
        out << (first ? "" : ", ") << jsonQuote(spec.name) << ": " << json(value);
        first = false;
    }
    out << "}";
    // The backend's own section: "cpu", "reference", "hybrid" or "tessellation".
    s.visitSections([&](const char* section, const auto& figures) {
        out << ",\n  " << jsonQuote(section) << ": {";
        bool first_field = true;
        figures.visit([&](const char* name, const auto& value) {
            out << (first_field ? "" : ", ") << jsonQuote(name) << ": " << number(value);
            first_field = false;
        });
        out << "}";
    });
    out << "\n}\n";
    return out.str();
}

void writeTextFileAtomic(const std::string& path, const std::string& text, bool durable) {
    os::AtomicFile(path, durable ? os::Durability::Durable : os::Durability::Atomic).writeWith([&](std::ostream& out) {
        out << text;
    });
}

void checkOutputPath(const std::string& path) { os::checkDestination(path); }

}  // namespace hyvox
