// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The one declaration of every voxelize option: name, type, default, limits or choices,
// unit, one line of help, and the environment variable a front door reads for it.
//
// Everything else is derived from this table: the CLI's parser and --help, the Python
// keywords, the generated .pyi and docstring, the Blender add-on's properties, the stats'
// "options" section, and voxelize()'s own checks. Adding an option = one entry in
// option_schema.cpp plus its field in options.h and the code that uses it.
#include <array>
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "hyvox/mesh.h"
#include "hyvox/options.h"

namespace hyvox {

enum class OptionType {
    Integer,  // whole number within [min, max]
    Number,   // finite real within [min, max] (or (min, max] when min_exclusive)
    Flag,     // true / false
    Text,     // free text (a path, a device name)
    Choice,   // one of `choices`
    Vector3,  // three finite reals (a position)
    Box,      // two corners, min <= max per axis
};

// A value of any option; std::monostate = unset (allowed for `nullable` options only; for
// the others, unset means the default).
using OptionValue =
    std::variant<std::monostate, std::int64_t, double, bool, std::string, std::array<double, 3>, Bounds>;

struct OptionSpec {
    const char* name;   // Python keyword; the CLI flag is "--" + name with '-' for '_'
    OptionType type;
    const char* group;  // "grid", "run", "output", "solid", "gl", "hybrid", "tessellation"
    const char* label;  // a short title for a UI ("Resolution", "Tessellation γ")
    const char* unit;   // "voxels", "world units", "MiB", "bytes", "" ...
    const char* help;   // one line
    bool nullable = false;        // may be unset (then a derived value is used; see help)
    double min = 0, max = 0;      // Integer, Number
    bool min_exclusive = false;   // Number: value must be > min
    std::vector<const char*> choices;      // Choice
    std::vector<const char*> cli_aliases;  // further CLI spellings ("--gamma")
    const char* env = nullptr;             // environment variable the front doors read, or null
    // The field behind the option (no checks: setOption checks first).
    OptionValue (*get)(const VoxelizeOptions&) = nullptr;
    void (*put)(VoxelizeOptions&, const OptionValue&) = nullptr;
    // Text of a form of its own (the region's "K/N"): the form for a usage line, what a valid
    // text is (for messages), and the check; null = any text.
    const char* text_form = nullptr;
    const char* text_rule = nullptr;
    bool (*text_valid)(const std::string& text) = nullptr;

    std::string cliFlag() const;  // "--voxel-size"
};

// Every option, in the order front doors list them.
const std::vector<OptionSpec>& optionSchema();

// The spec of `name`, or InvalidInput "unknown option 'name' (the options are: ...)".
const OptionSpec& findOption(const std::string& name);

// Refuses a value of the wrong type, out of its limits or not among the choices, with the
// message every front door shows: "<name> must be ..., got <value>". Returns normally for
// a valid value.
void checkOption(const OptionSpec& spec, const OptionValue& value);

// checkOption, then stores it (unset: the default for non-nullable options).
void setOption(VoxelizeOptions& options, const std::string& name, const OptionValue& value);

// Text as typed on a command line or in an environment variable, in the spec's type:
// "256", "0.5", "true"/"false"/"1"/"0"/"yes"/"no", "x,y,z", "x0,y0,z0,x1,y1,z1".
// InvalidInput with the same "<name> must be ..." message for text that does not parse.
OptionValue parseOptionText(const OptionSpec& spec, const std::string& text);

// "1,2.5,-3": the numbers of a comma-separated list (each a whole strtod parse, no range
// error); empty when any part is not a number. Vector and box options are written this way.
std::vector<double> parseNumberList(const std::string& text);

// The value as text (for --help defaults, reports and error messages); "" for unset.
std::string formatOptionValue(const OptionValue& value);

// What a valid value is, for messages: "a whole number between 1 and 16384" (a Text option
// with a form: its text_rule).
std::string describeOption(const OptionSpec& spec);

// For the front doors (the library itself reads no environment): sets every option whose
// OptionSpec::env variable `lookup` finds (std::getenv, or a test's table). InvalidInput
// names the variable.
void applyEnvironment(VoxelizeOptions& options, const char* (*lookup)(const char* variable));

// Whether the option changes what `method` does: "gl" options the GL methods, "hybrid" the
// hybrid's, "tessellation" the tessellation's; grid and run options every method.
bool optionAppliesTo(const OptionSpec& spec, Method method);

// checkOption on every field of a filled options struct: voxelize() calls it, so options set
// from C++ get the same messages as those from the front doors.
void checkOptions(const VoxelizeOptions& options);

}  // namespace hyvox
