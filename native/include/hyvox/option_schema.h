// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// The one declaration of every option of a voxelization (VoxelizeOptions) and of its write
/// (WriteOptions): name, type, default, limits or choices, unit, one line of help, and the
/// environment variable a front door reads for it.
///
/// Everything else is derived from this table: the CLI's parser and --help, the Python
/// keywords (voxelize()'s and write_vdb()'s), the generated .pyi and docstring, the Blender
/// add-on's properties, the stats' "options" section, and voxelize()'s and writeVdb()'s own
/// checks. Adding an option = one entry in option_schema.cpp plus its field in options.h and
/// the code that uses it.
#include <array>
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "hyvox/mesh.h"
#include "hyvox/options.h"

namespace hyvox {

/// The kind of an option's value.
enum class OptionType {
    Integer,  ///< whole number within [min, max]
    Number,   ///< finite real within [min, max] (or (min, max] when min_exclusive)
    Flag,     ///< true / false
    Text,     ///< free text (a path, a device name)
    Choice,   ///< one of `choices`
    Choices,  ///< a comma list of `choices` (text; "" = none)
    Vector3,  ///< three finite reals (a position)
    Box,      ///< two corners, min <= max per axis
};

/// A value of any option; std::monostate = unset (allowed for `nullable` options only; for
/// the others, unset means the default).
using OptionValue =
    std::variant<std::monostate, std::int64_t, double, bool, std::string, std::array<double, 3>, Bounds>;

/// One option of the schema. The schema (optionSchema()) is built once and never changes:
/// reading it is thread-safe.
struct OptionSpec {
    const char* name;                      ///< Python keyword; the CLI flag is "--" + name with '-' for '_'
    OptionType type;                       ///< the kind of its value
    const char* group;                     ///< "grid", "run", "output", "solid", "gl", "hybrid", "tessellation"
    const char* label;                     ///< a short title for a UI ("Resolution", "Tessellation γ")
    const char* unit;                      ///< "voxels", "world units", "MiB", "bytes", "" ...
    const char* help;                      ///< one line
    bool nullable = false;                 ///< may be unset (then a derived value is used; see help)
    double min = 0;                        ///< Integer, Number: the least value (see min_exclusive)
    double max = 0;                        ///< Integer, Number: the largest value
    bool min_exclusive = false;            ///< Number: value must be > min
    std::vector<const char*> choices;      ///< Choice, Choices
    std::vector<const char*> cli_aliases;  ///< further CLI spellings ("--gamma")
    const char* env = nullptr;             ///< environment variable the front doors read, or null
    // The field behind the option (no checks: setOption checks first): in VoxelizeOptions,
    // in WriteOptions, or in both (threads, memory_budget_mib); null where a struct has none.
    OptionValue (*get)(const VoxelizeOptions&) = nullptr;            ///< reads the VoxelizeOptions field
    void (*put)(VoxelizeOptions&, const OptionValue&) = nullptr;     ///< stores it
    OptionValue (*get_write)(const WriteOptions&) = nullptr;         ///< reads the WriteOptions field
    void (*put_write)(WriteOptions&, const OptionValue&) = nullptr;  ///< stores it
    // Text of a form of its own (the region's "K/N"); null = any text.
    const char* text_form = nullptr;                        ///< the form, for a usage line
    const char* text_rule = nullptr;                        ///< what a valid text is, for messages
    bool (*text_valid)(const std::string& text) = nullptr;  ///< whether a text has the form

    std::string cliFlag() const;                                 ///< "--voxel-size"
    bool isVoxelizeOption() const { return get != nullptr; }     ///< a field of VoxelizeOptions
    bool isWriteOption() const { return get_write != nullptr; }  ///< a field of WriteOptions
    /// The default: the field of a default-constructed struct (monostate for nullable options).
    OptionValue defaultValue() const;
};

/// Every option, in the order front doors list them (built on first use; thread-safe).
const std::vector<OptionSpec>& optionSchema();

/// The spec of `name`.
/// @throws InvalidInput "unknown option 'name' (the options are: ...)"
const OptionSpec& findOption(const std::string& name);

/// Refuses a value of the wrong type, out of its limits or not among the choices. Returns
/// normally for a valid value (monostate, unset, included).
/// @throws InvalidInput with the message every front door shows: "<name> must be ..., got <value>"
void checkOption(const OptionSpec& spec, const OptionValue& value);

/// Stores a value in an option's field, by the option's schema name, after checkOption()
/// (unset: the default for non-nullable options; a whole number is fine for a Number).
/// @throws InvalidInput an unknown name, a bad value (checkOption's message), or an option of
///         the other struct ("durable_write is an option of writing the result, ...")
///@{
void setOption(VoxelizeOptions& options, const std::string& name, const OptionValue& value);
void setOption(WriteOptions& options, const std::string& name, const OptionValue& value);
///@}

/// Text as typed on a command line or in an environment variable, in the spec's type:
/// "256", "0.5", "true"/"false"/"1"/"0"/"yes"/"no", "x,y,z", "x0,y0,z0,x1,y1,z1".
/// @throws InvalidInput with the same "<name> must be ..." message for text that does not parse
OptionValue parseOptionText(const OptionSpec& spec, const std::string& text);

/// "1,2.5,-3": the numbers of a comma-separated list (each a whole strtod parse, no range
/// error); empty when any part is not a number. Vector and box options are written this way.
std::vector<double> parseNumberList(const std::string& text);

/// The value as text (for --help defaults, reports and error messages); "" for unset.
std::string formatOptionValue(const OptionValue& value);

/// What a valid value is, for messages: "a whole number between 1 and 16384" (a Text option
/// with a form: its text_rule).
std::string describeOption(const OptionSpec& spec);

/// For the front doors (the library itself reads no environment): sets every voxelize option
/// whose OptionSpec::env variable `lookup` finds (std::getenv, or a test's table).
/// @throws InvalidInput naming the variable, for a value the option refuses
void applyEnvironment(VoxelizeOptions& options, const char* (*lookup)(const char* variable));

/// Whether the option changes what `method` does: "gl" options the GL methods, "hybrid" the
/// hybrid's, "tessellation" the tessellation's; grid and run options every method.
bool optionAppliesTo(const OptionSpec& spec, Method method);

/// checkOption on every field of a filled options struct: voxelize() and writeVdb() call it,
/// so options set from C++ get the same messages as those from the front doors.
/// @throws InvalidInput for the first field out of its limits
///@{
void checkOptions(const VoxelizeOptions& options);
void checkOptions(const WriteOptions& options);
///@}

}  // namespace hyvox
