// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// The arguments of a farm task, declared once: the commands the Blender add-on runs for a
/// farm job (`run`: voxelize a chunk of frames; `assemble`: check every frame and save the
/// .blend that plays them), each flag with its aliases, whether it is required, its value and
/// help, and what a farm job fills it with.
///
/// Both sides of the contract are built from this table: the job generators (`hyvox
/// job-template`) write their command lines from it, and the add-on builds its parser from it
/// (hyvox._core.FARM_TASK_ARGUMENTS).
#include <string>
#include <vector>

#include "hyvox/option_schema.h"

namespace hyvox {

/// A farm command of the add-on.
enum class FarmCommand {
    Run,       ///< voxelize the task's frames; arguments it does not know go on to the headless script
    Assemble,  ///< check the job's frames and save the .blend of the sequence; refuses other arguments
};

/// What follows a flag.
enum class FarmValue {
    Text,    ///< one argument, any text
    Switch,  ///< nothing: the flag alone means true
    Option,  ///< one argument, a voxelize option's value (its type and unset value from the schema)
};

/// What a farm job fills an argument with; None: the job does not write it.
enum class FarmJobValue {
    None,        ///< written by hand or by the session's client (--blend), never by the job
    TaskFrames,  ///< the task's chunk of frames
    JobFrames,   ///< every frame of the job
    OutputDir,   ///< the job's output folder
    Objects,     ///< the job's object names
    Option,      ///< the job's parameter of the same voxelize option
};

/// One flag of the farm commands.
struct FarmTaskArgument {
    std::string flag;                  ///< "--job-frames"
    std::vector<std::string> aliases;  ///< further spellings ("-o")
    bool run;                          ///< taken by `run`
    bool assemble;                     ///< taken by `assemble`
    bool required;                     ///< the command refuses to start without it
    FarmValue value;                   ///< what follows the flag
    const OptionSpec* option;          ///< FarmValue::Option: the schema's entry; else null
    const char* default_text;          ///< FarmValue::Text: the value when absent; null: none
    const char* help;                  ///< one line
    FarmJobValue job;                  ///< what a farm job fills it with

    /// Whether `command` takes this flag.
    bool takenBy(FarmCommand command) const { return command == FarmCommand::Run ? run : assemble; }
};

/// Every flag of the farm commands, in the order the jobs write them.
const std::vector<FarmTaskArgument>& farmTaskArguments();

/// A farm job's parameter always has a value: a voxelize option the schema lets be unset (a
/// nullable Number with an excluded minimum: voxel_size) takes that minimum to mean unset.
double farmUnsetValue(const OptionSpec& spec);

}  // namespace hyvox
