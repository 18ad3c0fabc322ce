// SPDX-License-Identifier: GPL-3.0-or-later
#include "hyvox/option_schema.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "core/option_row.h"
#include "hyvox/errors.h"
#include "hyvox/region.h"

namespace hyvox {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Accessors: one line per field, captureless so they fit the spec's function pointers.
// HYVOX_FIELD: a field of VoxelizeOptions (for Option::field); HYVOX_WRITE_FIELD: one of
// WriteOptions (for Option::writeField).
#define HYVOX_FIELD(type_get, expr)                                           \
    [](const VoxelizeOptions& o) -> OptionValue { return type_get(o.expr); }, \
        [](VoxelizeOptions& o, const OptionValue& v) { o.expr = fieldValue(v, o.expr); }
#define HYVOX_WRITE_FIELD(type_get, expr)                                  \
    [](const WriteOptions& o) -> OptionValue { return type_get(o.expr); }, \
        [](WriteOptions& o, const OptionValue& v) { o.expr = fieldValue(v, o.expr); }

OptionValue asInteger(std::int64_t v) { return v; }
OptionValue asNumber(double v) { return v; }
OptionValue asFlag(bool v) { return v; }
OptionValue asText(const std::string& v) { return v; }
OptionValue asOptionalNumber(const std::optional<double>& v) {
    return v ? OptionValue(*v) : OptionValue(std::monostate{});
}
OptionValue asOptionalVector(const std::optional<std::array<double, 3>>& v) {
    return v ? OptionValue(*v) : OptionValue(std::monostate{});
}
OptionValue asOptionalBox(const std::optional<Bounds>& v) {
    return v ? OptionValue(*v) : OptionValue(std::monostate{});
}
OptionValue asMode(Mode v) { return std::string(toString(v)); }
OptionValue asMethod(Method v) { return std::string(toString(v)); }
OptionValue asInsideRule(InsideRule v) { return std::string(toString(v)); }
OptionValue asAttributes(const AttributeSet& v) { return toString(v); }
OptionValue asRegion(const RegionOptions& v) { return formatRegion(v); }

// The stored value converted to the field's type (checked before: the variant holds the
// spec's type, or monostate for an unset nullable field).
int fieldValue(const OptionValue& v, int) { return int(std::get<std::int64_t>(v)); }
std::uint64_t fieldValue(const OptionValue& v, std::uint64_t) { return std::uint64_t(std::get<std::int64_t>(v)); }
double fieldValue(const OptionValue& v, double) { return std::get<double>(v); }
bool fieldValue(const OptionValue& v, bool) { return std::get<bool>(v); }
std::string fieldValue(const OptionValue& v, const std::string&) { return std::get<std::string>(v); }
Mode fieldValue(const OptionValue& v, Mode) { return parseMode(std::get<std::string>(v)); }
Method fieldValue(const OptionValue& v, Method) { return parseMethod(std::get<std::string>(v)); }
InsideRule fieldValue(const OptionValue& v, InsideRule) { return parseInsideRule(std::get<std::string>(v)); }
AttributeSet fieldValue(const OptionValue& v, const AttributeSet&) {
    return parseAttributeSet(std::get<std::string>(v));
}
RegionOptions fieldValue(const OptionValue& v, const RegionOptions&) { return parseRegion(std::get<std::string>(v)); }
template <typename T>
std::optional<T> fieldValue(const OptionValue& v, const std::optional<T>&) {
    if (std::holds_alternative<std::monostate>(v)) return std::nullopt;
    return std::get<T>(v);
}

static_assert(kMaxRegions == 2048, "the region's text_rule below names its limit");

std::vector<OptionSpec> buildSchema() {
    std::vector<OptionSpec> s;
    auto add = [&](const Option& row) { s.push_back(row.spec()); };
    // --- grid ---
    add(Option("resolution")
            .integer(1, kMaxResolution)
            .group("grid")
            .label("Resolution")
            .unit("voxels")
            .help("voxels along the longest side of the bounds (voxel_size overrides it)")
            .field(HYVOX_FIELD(asInteger, grid.resolution)));
    add(Option("voxel_size")
            .number(0, kInf)
            .excludingMin()
            .group("grid")
            .label("Voxel Size")
            .unit("world units")
            .help("edge length of one voxel; unset: the longest side / resolution")
            .nullable()
            .field(HYVOX_FIELD(asOptionalNumber, grid.voxel_size)));
    add(Option("origin")
            .vector3()
            .group("grid")
            .label("Origin")
            .unit("world units")
            .help("world position of voxel (0,0,0)'s min corner; unset: the bounds min")
            .nullable()
            .field(HYVOX_FIELD(asOptionalVector, grid.origin)));
    add(Option("bounds")
            .box()
            .group("grid")
            .label("Bounds")
            .unit("world units")
            .help("the box to voxelize (min and max corner); unset: the mesh bounds; geometry outside is clipped")
            .nullable()
            .field(HYVOX_FIELD(asOptionalBox, grid.bounds)));
    add(Option("padding")
            .integer(0, 1024)
            .group("grid")
            .label("Padding")
            .unit("voxels")
            .help("empty voxels added on every side")
            .field(HYVOX_FIELD(asInteger, grid.padding)));
    add(Option("region")
            .text()
            .group("grid")
            .label("Region")
            .help("voxelize only box K (from 0) of the N the grid is cut into along its longest side, at whole 8³ "
                  "leaves: one farm task's part, on the whole grid's transform, for hyvox merge to join into the whole "
                  "grid's file; '' = the whole grid; not for solid mode with attributes")
            .field(HYVOX_FIELD(asRegion, region))
            .textForm("K/N", "K/N with whole numbers 0 <= K < N <= 2048, or '' for the whole grid", isRegionText));
    // --- the run ---
    add(Option("mode")
            .choice(modeNames())
            .group("run")
            .label("Mode")
            .help("conservative: every voxel the surface touches (26-separating); thin: 6-separating; solid: "
                  "conservative plus every voxel whose centre is inside")
            .field(HYVOX_FIELD(asMode, mode)));
    add(Option("method")
            .choice(methodNames())
            .group("run")
            .label("Method")
            .help("cpu and reference run anywhere; triangle, fragment, hybrid and tessellation need GL 4.5")
            .field(HYVOX_FIELD(asMethod, method)));
    add(Option("threads")
            .integer(0, 4096)
            .group("run")
            .label("Threads")
            .unit("threads")
            .help("CPU threads of the voxelization and of the write; 0 = all cores")
            .field(HYVOX_FIELD(asInteger, threads))
            .writeField(HYVOX_WRITE_FIELD(asInteger, threads)));
    add(Option("memory_budget_mib")
            .integer(0, double(1 << 30))
            .group("run")
            .label("Memory Budget")
            .unit("MiB")
            .help("memory a run may take beside its mesh (every pass and the .vdb it writes; a run estimated to need "
                  "more is refused before it starts); 0 = half of this machine's memory")
            .field(HYVOX_FIELD(asInteger, memory_budget_mib))
            .writeField(HYVOX_WRITE_FIELD(asInteger, memory_budget_mib)));
    add(Option("tile_size")
            .integer(0, kMaxResolution)
            .group("run")
            .label("Tile Size")
            .unit("voxels")
            .help("side of the boxes voxelized one after the other (rounded up to a multiple of 8); 0 = from the "
                  "memory budget")
            .field(HYVOX_FIELD(asInteger, tile_size)));
    // --- attribute voxels ---
    add(Option("attributes")
            .choiceList(attributeNames())
            .group("run")
            .label("Attributes")
            .help("what to compute beside the voxels, a comma list: color (linear RGB, alpha when the source has "
                  "it) and normal per voxel (solid mode: the inside takes the surface's values, layer by layer "
                  "inward); sdf, a narrow-band signed distance grid (negative inside by the inside rule, in "
                  "every mode); '' = none")
            .field(HYVOX_FIELD(asAttributes, attributes)));
    add(Option("sdf_band")
            .integer(1, 64)
            .group("run")
            .label("SDF Band")
            .unit("voxels")
            .help("sdf: half-width of the narrow band (the grid is padded by at least this much)")
            .field(HYVOX_FIELD(asInteger, sdf.band)));
    // --- output files (WriteOptions alone) ---
    add(Option("durable_write")
            .flag()
            .group("output")
            .label("Durable Write")
            .help("sync each output file (.vdb, stats JSON) and its folder to disk before the write returns, so it "
                  "survives a power loss; off: written to a temporary and renamed (never half-written), not synced")
            .writeField(HYVOX_WRITE_FIELD(asFlag, durable)));
    // --- solid mode ---
    add(Option("inside")
            .choice(insideRuleNames())
            .group("solid")
            .label("Inside Rule")
            .help("solid and sdf: parity = odd ray crossings (closed meshes); winding = winding number >= 0.5 (holes, "
                  "flipped faces); auto = the winding number, by ray crossings when the mesh is closed and "
                  "consistently oriented, else by fast winding numbers")
            .field(HYVOX_FIELD(asInsideRule, solid.inside)));
    add(Option("winding_beta")
            .number(1, 100)
            .group("solid")
            .label("Winding Accuracy")
            .help("solid and sdf, winding: accuracy of the fast winding numbers (a cluster of triangles counts as one "
                  "expansion where the point is farther than beta times the cluster's radius); larger is more exact "
                  "and slower")
            .field(HYVOX_FIELD(asNumber, solid.winding_beta)));
    // --- GL methods ---
    add(Option("gl_device")
            .text()
            .group("gl")
            .label("GL Device")
            .help("EGL device: '' = a hardware GPU if any, else software; 'software'; or a device index")
            .env("HYVOX_GL_DEVICE")
            .field(HYVOX_FIELD(asText, gl.device)));
    add(Option("shader_dir")
            .text()
            .group("gl")
            .label("Shader Folder")
            .help("read the GLSL from this copy of shaders/ instead of the embedded one")
            .env("HYVOX_SHADER_DIR")
            .field(HYVOX_FIELD(asText, gl.shader_dir)));
    add(Option("gl_tile_bytes")
            .integer(0, double(1ull << 40))
            .group("gl")
            .label("GL Tile Size")
            .unit("bytes")
            .help("largest bit-grid tile on the GPU; 0 = one storage block (the device's limit)")
            .env("HYVOX_GL_TILE_BYTES")
            .field(HYVOX_FIELD(asInteger, gl.tile_bytes)));
    add(Option("gl_pair_list_bytes")
            .integer(0, double(1ull << 40))
            .group("gl")
            .label("GL Pair List Size")
            .unit("bytes")
            .help("largest list of (voxel, triangle) pairs the GL methods' colour/normal pass holds at once (a tile "
                  "whose pairs do not fit runs as halves); 0 = one storage block (the device's limit)")
            .field(HYVOX_FIELD(asInteger, gl.pair_list_bytes)));
    add(Option("gl_wall_timing")
            .flag()
            .group("gl")
            .label("Wall-Clock GPU Timing")
            .help("time GL passes by the wall clock instead of GPU timer queries (always on for software GL)")
            .env("HYVOX_GL_WALL_TIMING")
            .field(HYVOX_FIELD(asFlag, gl.wall_timing)));
    add(Option("tess_instanced")
            .flag()
            .group("tessellation")
            .label("Instanced Patches")
            .help("tessellation: draw one instance per patch (always on for software GL)")
            .env("HYVOX_TESS_INSTANCED")
            .field(HYVOX_FIELD(asFlag, gl.tess_instanced)));
    // --- hybrid ---
    add(Option("hybrid_cutoff")
            .number(-1, kInf)
            .group("hybrid")
            .label("Hybrid Cutoff")
            .unit("voxels²")
            .help("hybrid: projected triangle area above which a triangle is rasterized; negative = automatic")
            .field(HYVOX_FIELD(asNumber, hybrid.cutoff)));
    // --- tessellation ---
    add(Option("tess_gamma")
            .number(0, 1024)
            .excludingMin()
            .group("tessellation")
            .label("Tessellation Density")
            .help("tessellation: safety factor γ of Eq. 1 (higher misses fewer voxels, costs more points; below 2 a "
                  "closed mesh may leak)")
            .cliAlias("--gamma")
            .field(HYVOX_FIELD(asNumber, tessellation.gamma)));
    add(Option("pn_triangles")
            .flag()
            .group("tessellation")
            .label("PN-Triangles")
            .help("tessellation: PN-triangle smoothing")
            .field(HYVOX_FIELD(asFlag, tessellation.pn_triangles)));
    add(Option("displacement_image")
            .text()
            .group("tessellation")
            .label("Displacement Image")
            .help("tessellation: an 8/16-bit PNG height image sampled at the mesh's UVs (Blender Displace)")
            .cliAlias("--displacement")
            .field(HYVOX_FIELD(asText, tessellation.displacement_image)));
    add(Option("displacement_strength")
            .number(-kInf, kInf)
            .group("tessellation")
            .label("Displacement Strength")
            .unit("world units")
            .help("tessellation: displacement along the normal per unit of height")
            .cliAlias("--strength")
            .field(HYVOX_FIELD(asNumber, tessellation.displacement_strength)));
    add(Option("displacement_midlevel")
            .number(-kInf, kInf)
            .group("tessellation")
            .label("Displacement Midlevel")
            .help("tessellation: the height that stays in place")
            .cliAlias("--midlevel")
            .field(HYVOX_FIELD(asNumber, tessellation.displacement_midlevel)));
    add(Option("tess_counts")
            .flag()
            .group("tessellation")
            .label("Point Counts")
            .help("tessellation: also keep the points per voxel (the 'count' grid)")
            .field(HYVOX_FIELD(asFlag, tessellation.counts)));
    add(Option("snap_origin")
            .flag()
            .group("grid")
            .label("Snap Origin")
            .help("origin (unless given) at a whole multiple of the voxel size at or below the bounds min: a lattice "
                  "fixed in world space, so runs whose bounds differ keep the voxels of what did not move")
            .field(HYVOX_FIELD(asFlag, grid.snap_origin)));
    return s;
}

#undef HYVOX_FIELD
#undef HYVOX_WRITE_FIELD

const char* typeName(OptionType type) {
    switch (type) {
        case OptionType::Integer: return "a whole number";
        case OptionType::Number: return "a finite number";
        case OptionType::Flag: return "true or false";
        case OptionType::Text: return "text";
        case OptionType::Choice: return "one of the choices";
        case OptionType::Choices: return "a comma list of the choices";
        case OptionType::Vector3: return "three finite numbers x,y,z";
        case OptionType::Box: return "two corners x0,y0,z0,x1,y1,z1 with min <= max";
    }
    return "?";
}

std::string number(double value) {
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    char buf[32];
    for (int precision = 6; precision <= 17; ++precision) {
        std::snprintf(buf, sizeof buf, "%.*g", precision, value);
        if (std::strtod(buf, nullptr) == value) break;
    }
    return buf;
}

// "between 1 and 16384", "greater than 0 and at most 1024", "at least -1", "" (no limit).
std::string rangeText(const OptionSpec& spec) {
    const bool low = std::isfinite(spec.min), high = std::isfinite(spec.max);
    if (spec.min_exclusive)
        return "greater than " + number(spec.min) + (high ? " and at most " + number(spec.max) : "");
    if (low && high) return "between " + number(spec.min) + " and " + number(spec.max);
    if (low) return "at least " + number(spec.min);
    if (high) return "at most " + number(spec.max);
    return "";
}

[[noreturn]] void refuse(const OptionSpec& spec, const std::string& got) {
    throw InvalidInput(std::string(spec.name) + " must be " + describeOption(spec) + ", got " + got);
}

bool allFinite(const std::array<double, 3>& v) {
    return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

}  // namespace

std::string describeOption(const OptionSpec& spec) {
    std::string what = typeName(spec.type);
    const std::string range = rangeText(spec);
    if ((spec.type == OptionType::Integer || spec.type == OptionType::Number) && !range.empty()) what += " " + range;
    if (spec.type == OptionType::Text && spec.text_rule) what = spec.text_rule;
    if (spec.type == OptionType::Choice || spec.type == OptionType::Choices) {
        what = spec.type == OptionType::Choice ? "one of" : "a comma list of";
        for (std::size_t c = 0; c < spec.choices.size(); ++c) what += (c ? ", " : " ") + std::string(spec.choices[c]);
    }
    return what;
}

void applyEnvironment(VoxelizeOptions& options, const char* (*lookup)(const char* variable)) {
    for (const OptionSpec& spec : optionSchema()) {
        if (!spec.env || !spec.isVoxelizeOption()) continue;
        const char* text = lookup(spec.env);
        if (!text) continue;
        try {
            setOption(options, spec.name, parseOptionText(spec, text));
        } catch (const InvalidInput& e) {
            throw InvalidInput(std::string(spec.env) + ": " + e.what());
        }
    }
}

std::vector<double> parseNumberList(const std::string& text) {
    std::vector<double> out;
    std::size_t begin = 0;
    while (begin <= text.size()) {
        const std::size_t comma = std::min(text.find(',', begin), text.size());
        const std::string part = text.substr(begin, comma - begin);
        char* end = nullptr;
        errno = 0;
        const double value = std::strtod(part.c_str(), &end);
        if (part.empty() || *end != '\0' || errno == ERANGE) return {};
        out.push_back(value);
        begin = comma + 1;
    }
    return out;
}

OptionValue OptionSpec::defaultValue() const { return get ? get(VoxelizeOptions{}) : get_write(WriteOptions{}); }

std::string OptionSpec::cliFlag() const {
    std::string flag = std::string("--") + name;
    for (char& c : flag)
        if (c == '_') c = '-';
    return flag;
}

const std::vector<OptionSpec>& optionSchema() {
    static const std::vector<OptionSpec> schema = buildSchema();
    return schema;
}

const OptionSpec& findOption(const std::string& name) {
    std::string names;
    for (const OptionSpec& spec : optionSchema()) {
        if (name == spec.name) return spec;
        names += names.empty() ? spec.name : std::string(", ") + spec.name;
    }
    throw InvalidInput("unknown option '" + name + "' (the options are: " + names + ")");
}

std::string formatOptionValue(const OptionValue& value) {
    struct Format {
        std::string operator()(std::monostate) const { return ""; }
        std::string operator()(std::int64_t v) const { return std::to_string(v); }
        std::string operator()(double v) const { return number(v); }
        std::string operator()(bool v) const { return v ? "true" : "false"; }
        std::string operator()(const std::string& v) const { return "'" + v + "'"; }
        std::string operator()(const std::array<double, 3>& v) const {
            return number(v[0]) + "," + number(v[1]) + "," + number(v[2]);
        }
        std::string operator()(const Bounds& b) const { return (*this)(b.min) + "," + (*this)(b.max); }
    };
    return std::visit(Format{}, value);
}

void checkOption(const OptionSpec& spec, const OptionValue& value) {
    if (std::holds_alternative<std::monostate>(value)) return;  // unset: nullable or default
    const std::string got = formatOptionValue(value);
    switch (spec.type) {
        case OptionType::Integer: {
            if (!std::holds_alternative<std::int64_t>(value)) refuse(spec, got);
            const auto v = std::get<std::int64_t>(value);
            if (double(v) < spec.min || double(v) > spec.max) refuse(spec, got);
            return;
        }
        case OptionType::Number: {
            double v;
            if (const auto* i = std::get_if<std::int64_t>(&value))
                v = double(*i);
            else if (const auto* d = std::get_if<double>(&value))
                v = *d;
            else
                refuse(spec, got);
            const bool above = spec.min_exclusive ? v > spec.min : v >= spec.min;
            if (!std::isfinite(v) || !above || v > spec.max) refuse(spec, got);
            return;
        }
        case OptionType::Flag:
            if (!std::holds_alternative<bool>(value)) refuse(spec, got);
            return;
        case OptionType::Text:
            if (!std::holds_alternative<std::string>(value)) refuse(spec, got);
            if (spec.text_valid && !spec.text_valid(std::get<std::string>(value))) refuse(spec, got);
            return;
        case OptionType::Choice: {
            const auto* text = std::get_if<std::string>(&value);
            std::string choices;
            for (const char* choice : spec.choices) {
                if (text && *text == choice) return;
                choices += choices.empty() ? choice : std::string(", ") + choice;
            }
            throw InvalidInput("unknown " + std::string(spec.name) + " " + got + " (choose one of: " + choices + ")");
        }
        case OptionType::Choices: {
            const auto* text = std::get_if<std::string>(&value);
            if (!text) refuse(spec, got);
            for (std::size_t begin = 0; begin < text->size();) {
                const std::size_t comma = std::min(text->find(',', begin), text->size());
                const std::string item = text->substr(begin, comma - begin);
                bool known = false;
                for (const char* choice : spec.choices) known = known || item == choice;
                if (!known)
                    throw InvalidInput("unknown " + std::string(spec.name) + " '" + item + "' in " + got + " (" +
                                       describeOption(spec) + ")");
                begin = comma + 1;
            }
            return;
        }
        case OptionType::Vector3: {
            const auto* v = std::get_if<std::array<double, 3>>(&value);
            if (!v || !allFinite(*v)) refuse(spec, got);
            return;
        }
        case OptionType::Box: {
            const auto* b = std::get_if<Bounds>(&value);
            if (!b || !allFinite(b->min) || !allFinite(b->max)) refuse(spec, got);
            for (int a = 0; a < 3; ++a)
                if (b->max[a] < b->min[a]) refuse(spec, got);
            return;
        }
    }
}

namespace {

// setOption for either struct: `put` is the spec's accessor of that struct.
template <typename Options>
void storeOption(Options& options, const OptionSpec& spec, void (*put)(Options&, const OptionValue&),
                 const OptionValue& value) {
    checkOption(spec, value);
    if (std::holds_alternative<std::monostate>(value) && !spec.nullable) {
        put(options, spec.defaultValue());  // unset = the default
        return;
    }
    // Whole numbers are fine where reals are expected.
    if (spec.type == OptionType::Number)
        if (const auto* i = std::get_if<std::int64_t>(&value)) {
            put(options, double(*i));
            return;
        }
    put(options, value);
}

}  // namespace

void setOption(VoxelizeOptions& options, const std::string& name, const OptionValue& value) {
    const OptionSpec& spec = findOption(name);
    if (!spec.isVoxelizeOption())
        throw InvalidInput(name + " is an option of writing the result (WriteOptions), not of the voxelization");
    storeOption(options, spec, spec.put, value);
}

void setOption(WriteOptions& options, const std::string& name, const OptionValue& value) {
    const OptionSpec& spec = findOption(name);
    if (!spec.isWriteOption())
        throw InvalidInput(name + " is an option of the voxelization, not of writing the result (WriteOptions)");
    storeOption(options, spec, spec.put_write, value);
}

OptionValue parseOptionText(const OptionSpec& spec, const std::string& text) {
    const std::string got = "'" + text + "'";
    switch (spec.type) {
        case OptionType::Integer: {
            errno = 0;
            char* end = nullptr;
            const long long v = std::strtoll(text.c_str(), &end, 10);
            if (text.empty() || *end != '\0' || errno == ERANGE) refuse(spec, got);
            return std::int64_t(v);
        }
        case OptionType::Number: {
            errno = 0;
            char* end = nullptr;
            const double v = std::strtod(text.c_str(), &end);
            if (text.empty() || *end != '\0' || errno == ERANGE) refuse(spec, got);
            return v;
        }
        case OptionType::Flag:
            if (text == "1" || text == "true" || text == "yes" || text == "on") return true;
            if (text == "" || text == "0" || text == "false" || text == "no" || text == "off") return false;
            refuse(spec, got);
        case OptionType::Text:
        case OptionType::Choice:
        case OptionType::Choices: return text;
        case OptionType::Vector3: {
            const std::vector<double> v = parseNumberList(text);
            if (v.size() != 3) refuse(spec, got);
            return std::array<double, 3>{v[0], v[1], v[2]};
        }
        case OptionType::Box: {
            const std::vector<double> v = parseNumberList(text);
            if (v.size() != 6) refuse(spec, got);
            return Bounds{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
        }
    }
    refuse(spec, got);
}

bool optionAppliesTo(const OptionSpec& spec, Method method) {
    const std::string group = spec.group;
    if (group == "gl") return method != Method::Cpu && method != Method::Reference;
    if (group == "hybrid") return method == Method::Hybrid;
    if (group == "tessellation") return method == Method::Tessellation;
    return true;
}

void checkOptions(const VoxelizeOptions& options) {
    for (const OptionSpec& spec : optionSchema())
        if (spec.isVoxelizeOption()) checkOption(spec, spec.get(options));
}

void checkOptions(const WriteOptions& options) {
    for (const OptionSpec& spec : optionSchema())
        if (spec.isWriteOption()) checkOption(spec, spec.get_write(options));
}

}  // namespace hyvox
