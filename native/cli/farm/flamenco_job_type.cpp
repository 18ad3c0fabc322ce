// SPDX-License-Identifier: GPL-3.0-or-later
#include "farm/flamenco_job_type.h"

#include <cmath>

#include "farm/headless_blender.h"
#include "farm/job_options.h"
#include "farm/yaml_writer.h"
#include "hyvox/version.h"

namespace hyvox::farm {
namespace {

// A JavaScript object literal's fields, one per line; values already JavaScript.
std::string object(const std::vector<std::pair<std::string, std::string>>& fields) {
    std::string out = "{ ";
    for (std::size_t f = 0; f < fields.size(); ++f) out += (f ? ", " : "") + fields[f].first + ": " + fields[f].second;
    return out + " }";
}

std::string array(const std::vector<std::string>& values) {
    std::string out = "[";
    for (std::size_t v = 0; v < values.size(); ++v) out += (v ? ", " : "") + quoted(values[v]);
    return out + "]";
}

std::string number(double value) { return shortestNumber(value); }

// A voxelize option as a Flamenco job setting: the schema's type, default, limits, choices
// and help (Flamenco shows propargs' limits as the Blender property's).
std::string optionSetting(const OptionSpec& spec) {
    std::vector<std::pair<std::string, std::string>> fields{{"key", quoted(spec.name)}, {"label", quoted(spec.label)}};
    const OptionValue def = spec.get(VoxelizeOptions{});
    std::vector<std::pair<std::string, std::string>> limits;
    if (std::isfinite(spec.min)) limits.push_back({"min", number(spec.min)});
    if (std::isfinite(spec.max)) limits.push_back({"max", number(spec.max)});
    switch (spec.type) {
        case OptionType::Integer:
            fields.push_back({"type", quoted("int32")});
            fields.push_back({"default", std::to_string(std::get<std::int64_t>(def))});
            fields.push_back({"propargs", object(limits)});
            break;
        case OptionType::Number:
            fields.push_back({"type", quoted("float")});
            fields.push_back({"default", number(spec.nullable ? farmUnsetValue(spec) : std::get<double>(def))});
            fields.push_back({"propargs", object(limits)});
            break;
        case OptionType::Flag:
            fields.push_back({"type", quoted("bool")});
            fields.push_back({"default", std::get<bool>(def) ? "true" : "false"});
            break;
        case OptionType::Text:
        case OptionType::Choices:  // a comma list, as text
            fields.push_back({"type", quoted("string")});
            fields.push_back({"default", quoted(std::get<std::string>(def))});
            break;
        case OptionType::Choice:
            fields.push_back({"type", quoted("string")});
            fields.push_back({"default", quoted(std::get<std::string>(def))});
            fields.push_back({"choices", array(std::vector<std::string>(spec.choices.begin(), spec.choices.end()))});
            break;
        case OptionType::Vector3:
        case OptionType::Box: break;  // job_options.cpp offers none
    }
    fields.push_back({"description", quoted(parameterDescription(spec))});
    return object(fields);
}

// [flag, setting key] pairs; "@chunk" is the task's frames.
std::string argumentTable(const std::vector<Argument>& args) {
    std::string out = "[\n";
    for (const Argument& a : args) {
        std::string key;
        switch (a.source) {
            case FarmJobValue::TaskFrames: key = "@chunk"; break;
            case FarmJobValue::JobFrames: key = "frames"; break;
            case FarmJobValue::OutputDir: key = "output_dir"; break;
            case FarmJobValue::Objects: key = "objects"; break;
            case FarmJobValue::Option: key = a.option->name; break;
            case FarmJobValue::None: break;  // jobArguments() gives none
        }
        out += "    [" + quoted(a.flag) + ", " + quoted(key) + "],\n";
    }
    return out + "]";
}

}  // namespace

std::string flamencoJobType() {
    std::string settings =
        "        { key: \"frames\", type: \"string\", required: true, eval: "
        "\"f'{C.scene.frame_start}-{C.scene.frame_end}'\",\n"
        "          description: \"The frames to voxelize, e.g. '1-250', '1-10, 20-30'\" },\n"
        "        { key: \"chunk_size\", type: \"int32\", default: 10, propargs: { min: 1 }, description: \"Frames per "
        "task\" },\n"
        "        { key: \"output_dir\", type: \"string\", subtype: \"dir_path\", required: true,\n"
        "          description: \"Folder of the .vdb files (Name_voxels_0001.vdb ...) and of the assembled .blend\" "
        "},\n"
        "        { key: \"objects\", type: \"string\", default: \"\",\n"
        "          description: \"Comma-separated names of the objects to voxelize into one volume; empty: the file's "
        "selection, or every visible mesh when nothing is selected\" },\n"
        "        { key: \"blendfile\", type: \"string\", required: true, visible: \"web\",\n"
        "          description: \"The .blend to voxelize (the add-on fills it in)\" },\n";
    for (const OptionSpec* spec : blenderJobOptions()) settings += "        " + optionSetting(*spec) + ",\n";

    return "// SPDX-License-Identifier: GPL-3.0-or-later\n"
           "// hyvox " +
        std::string(version()) +
        " Flamenco job type: voxelize a .blend's animation, a frame chunk per task,\n"
        "// then assemble the volume sequence. Generated from the options schema by `hyvox job-template\n"
        "// flamenco`; put it in the Manager's scripts/ folder as hyvox.js (docs/farm.md).\n"
        "\n"
        "const JOB_TYPE = {\n"
        "    label: \"hyvox Voxelize\",\n"
        "    description: \"Voxelizes the animation of a .blend into one OpenVDB file per frame (hyvox add-on)\",\n"
        "    settings: [\n" +
        settings +
        "    ],\n"
        "};\n"
        "\n"
        "// Blender's arguments after the .blend: find the worker's hyvox add-on and run its farm command.\n"
        "const HYVOX_AFTER_BLENDFILE = " +
        array(blenderArgsAfterFile()) +
        ";\n"
        "\n"
        "// The farm commands' arguments: [flag, setting key]; \"@chunk\" is the task's frames.\n"
        "const HYVOX_RUN_ARGS = " +
        argumentTable(runArguments()) +
        ";\n"
        "const HYVOX_ASSEMBLE_ARGS = " +
        argumentTable(assembleArguments()) + ";\n" +
        R"js(
function farmArgs(command, table, settings, chunk) {
    const args = [command];
    for (const [flag, key] of table) {
        args.push(flag, String(key === "@chunk" ? chunk : settings[key]));
    }
    return args;
}

function blenderCommand(settings, args) {
    return author.Command("blender-render", {
        exe: "{blender}",
        exeArgs: "{blenderArgs}",
        argsBefore: [],
        blendfile: settings.blendfile,
        args: HYVOX_AFTER_BLENDFILE.concat(args),
    });
}

function compileJob(job) {
    const settings = job.settings;
    const voxelizeTasks = [];
    for (const chunk of frameChunker(settings.frames, settings.chunk_size)) {
        const task = author.Task(`voxelize-${chunk}`, "blender");
        task.addCommand(blenderCommand(settings, farmArgs("run", HYVOX_RUN_ARGS, settings, chunk)));
        job.addTask(task);
        voxelizeTasks.push(task);
    }
    const assemble = author.Task("assemble", "blender");
    assemble.addCommand(blenderCommand(settings, farmArgs("assemble", HYVOX_ASSEMBLE_ARGS, settings, null)));
    for (const task of voxelizeTasks) {
        assemble.addDependency(task);
    }
    job.addTask(assemble);
}
)js";
}

}  // namespace hyvox::farm
