// SPDX-License-Identifier: GPL-3.0-or-later
#include "farm/openjd_templates.h"

#include <cmath>

#include "farm/headless_blender.h"
#include "farm/job_options.h"
#include "farm/yaml_writer.h"
#include "hyvox/version.h"

namespace hyvox::farm {
namespace {

// The task's bash scripts get every value as an argument (never pasted into their text),
// so a path with spaces or quotes reaches the program as it is.

// Run.sh BLENDER SCENE COMMAND ARGS...: in the session's Blender when there is one, else
// in a Blender of its own. exec: the farm's SIGTERM reaches the program itself.
std::string headlessScript() {
    return "#!/usr/bin/env bash\n"
           "# A farm command (run, assemble) of the hyvox add-on in Blender.\n"
           "set -euo pipefail\n"
           "blender=$1 scene=$2\n"
           "shift 2\n"
           "if [ -n \"${HYVOX_FARM_SOCKET:-}\" ]; then\n"
           "  exec \"$HYVOX_FARM_PYTHON\" \"$HYVOX_FARM_CLIENT\" \"$HYVOX_FARM_SOCKET\" \"$1\" --blend \"$scene\" "
           "\"${@:2}\"\n"
           "fi\n"
           "exec \"$blender\" -b \"$scene\" --python-exit-code 1 --python-expr '" +
        blenderBootstrap() + "' -- \"$@\"\n";
}

// Enter.sh BLENDER KEEP SESSION_DIR: starts the session's Blender and waits (on a pipe, not
// a clock) until it listens; its openjd_env lines give the tasks the way to it.
std::string enterScript() {
    return "#!/usr/bin/env bash\n"
           "# One Blender for this worker session's tasks (the hyvox add-on's farm/session.py).\n"
           "set -euo pipefail\n"
           "blender=$1 keep=$2 session=$3\n"
           "if [ \"$keep\" != true ]; then\n"
           "  echo \"hyvox: one Blender per task (SessionBlender is $keep)\"\n"
           "  exit 0\n"
           "fi\n"
           "log=\"$session/hyvox_blender.log\"\n"
           "# A short folder for the socket: a socket's path may hold only about 100 bytes.\n"
           "sockets=$(mktemp -d \"${TMPDIR:-/tmp}/hyvox.XXXXXX\")\n"
           "exec 4< <(exec setsid \"$blender\" -b --python-exit-code 1 --python-expr '" +
        blenderBootstrap() +
        "' -- serve --socket \"$sockets/blender\" --announce-fd 3 --session-dir \"$session\" "
        "3>&1 >>\"$log\" 2>&1 </dev/null)\n"
        "announced=$(cat <&4)\n"
        "if ! grep -q '^openjd_env: HYVOX_FARM_SOCKET=' <<<\"$announced\"; then\n"
        "  echo \"hyvox: error: the session's Blender did not start; its log:\" >&2\n"
        "  tail -n 40 \"$log\" >&2\n"
        "  rm -rf \"$sockets\"\n"
        "  exit 1\n"
        "fi\n"
        "echo \"$announced\"\n";
}

std::string exitScript() {
    return "#!/usr/bin/env bash\n"
           "# Ends the session's Blender (Enter.sh started it) and waits until it has quit.\n"
           "set -uo pipefail\n"
           "[ -n \"${HYVOX_FARM_SOCKET:-}\" ] || exit 0\n"
           "\"$HYVOX_FARM_PYTHON\" \"$HYVOX_FARM_CLIENT\" \"$HYVOX_FARM_SOCKET\" stop\n"
           "for _ in $(seq 300); do kill -0 \"$HYVOX_FARM_PID\" 2>/dev/null || break; sleep 0.1; done\n"
           "rm -rf \"$(dirname \"$HYVOX_FARM_SOCKET\")\"\n";
}

Yaml embeddedFile(const std::string& name, const std::string& data) {
    return Yaml::map()
        .add("name", Yaml::text(name))
        .add("type", Yaml::text("TEXT"))
        .add("filename", Yaml::text(name + ".sh"))
        .add("data", Yaml::block(data));
}

Yaml cancelation() {
    // SIGTERM first: the task cancels between native steps and deletes what it staged.
    return Yaml::map().add("mode", Yaml::text("NOTIFY_THEN_TERMINATE")).add("notifyPeriodInSeconds", Yaml::integer(60));
}

Yaml action(const std::vector<std::string>& args, bool cancelable) {
    Yaml out = Yaml::map().add("command", Yaml::text("bash")).add("args", Yaml::texts(args));
    if (cancelable) out.add("cancelation", cancelation());
    return out;
}

Yaml textParameter(const std::string& name, const std::string& def, const std::string& description) {
    return Yaml::map()
        .add("name", Yaml::text(name))
        .add("type", Yaml::text("STRING"))
        .add("default", Yaml::text(def))
        .add("description", Yaml::text(description));
}

Yaml intParameter(const std::string& name, std::int64_t def, std::int64_t min, std::int64_t max,
                  const std::string& description) {
    return Yaml::map()
        .add("name", Yaml::text(name))
        .add("type", Yaml::text("INT"))
        .add("default", Yaml::integer(def))
        .add("minValue", Yaml::integer(min))
        .add("maxValue", Yaml::integer(max))
        .add("description", Yaml::text(description));
}

Yaml pathParameter(const std::string& name, const std::string& object, const std::string& flow,
                   const std::string& description) {
    return Yaml::map()
        .add("name", Yaml::text(name))
        .add("type", Yaml::text("PATH"))
        .add("objectType", Yaml::text(object))
        .add("dataFlow", Yaml::text(flow))
        .add("description", Yaml::text(description));
}

// A voxelize option as a job parameter: the schema's type, default, limits, choices and help.
Yaml optionParameter(const OptionSpec& spec) {
    Yaml out = Yaml::map().add("name", Yaml::text(parameterName(spec)));
    const OptionValue def = spec.get(VoxelizeOptions{});
    switch (spec.type) {
        case OptionType::Integer:
            out.add("type", Yaml::text("INT")).add("default", Yaml::integer(std::get<std::int64_t>(def)));
            out.add("minValue", Yaml::integer(std::int64_t(spec.min)))
                .add("maxValue", Yaml::integer(std::int64_t(spec.max)));
            break;
        case OptionType::Number:
            out.add("type", Yaml::text("FLOAT"))
                .add("default", Yaml::number(spec.nullable ? farmUnsetValue(spec) : std::get<double>(def)));
            // OpenJD's limits are inclusive: an excluded minimum is the task's to refuse
            // (with the schema's message), or stands for unset.
            if (std::isfinite(spec.min)) out.add("minValue", Yaml::number(spec.min));
            if (std::isfinite(spec.max)) out.add("maxValue", Yaml::number(spec.max));
            break;
        case OptionType::Flag:
            out.add("type", Yaml::text("STRING")).add("default", Yaml::text(std::get<bool>(def) ? "true" : "false"));
            out.add("allowedValues", Yaml::texts({"true", "false"}));
            break;
        case OptionType::Text:
        case OptionType::Choices:  // a comma list, as text
            out.add("type", Yaml::text("STRING")).add("default", Yaml::text(std::get<std::string>(def)));
            break;
        case OptionType::Choice: {
            out.add("type", Yaml::text("STRING")).add("default", Yaml::text(std::get<std::string>(def)));
            out.add("allowedValues", Yaml::texts(std::vector<std::string>(spec.choices.begin(), spec.choices.end())));
            break;
        }
        case OptionType::Vector3:
        case OptionType::Box: break;  // job_options.cpp offers none
    }
    out.add("description", Yaml::text(parameterDescription(spec)));
    out.add("userInterface",
            Yaml::map().add("label", Yaml::text(spec.label)).add("groupLabel", Yaml::text("Voxelize Options")));
    return out;
}

std::string param(const std::string& name) { return "{{Param." + name + "}}"; }

std::vector<std::string> farmArgs(const std::string& command, const std::vector<Argument>& args) {
    std::vector<std::string> out{command};
    for (const Argument& a : args) {
        out.push_back(a.flag);
        switch (a.source) {
            case FarmJobValue::TaskFrames: out.push_back("{{Task.Param.Frame}}"); break;
            case FarmJobValue::JobFrames: out.push_back(param("Frames")); break;
            case FarmJobValue::OutputDir: out.push_back(param("OutputDir")); break;
            case FarmJobValue::Objects: out.push_back(param("Objects")); break;
            case FarmJobValue::Option: out.push_back(param(parameterName(*a.option))); break;
            case FarmJobValue::None: break;  // jobArguments() gives none
        }
    }
    return out;
}

std::vector<std::string> concat(std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

std::string header(const std::string& what) {
    return std::string("# hyvox ") + version() + " " + what +
        ", generated from the options schema by `hyvox job-template`; see docs/farm.md.\n";
}

}  // namespace

std::string blenderJobTemplate() {
    Yaml params = Yaml::list();
    params.push(pathParameter("BlendFile", "FILE", "IN", "The .blend to voxelize (its animation, at render settings)"));
    params.push(pathParameter("OutputDir", "DIRECTORY", "OUT",
                              "Folder of the .vdb files (Name_voxels_0001.vdb ...) and of the assembled .blend"));
    params.push(
        textParameter("Frames", "1-250", "The frames to voxelize: a range such as 1-250, or 1-250:2, or 1,5,9-20"));
    params.push(textParameter("Objects", "",
                              "Comma-separated names of the objects to voxelize into one volume; empty: the "
                              "file's selection, or every visible mesh when nothing is selected"));
    params.push(intParameter("ChunkSize", 10, 1, 150, "Frames per task (the farm may size chunks by ChunkSeconds)"));
    params.push(intParameter("ChunkSeconds", 300, 0, 86400,
                             "The run time a task aims at, in seconds (the farm sizes later chunks by the "
                             "first ones); 0: every task ChunkSize frames"));
    params.push(textParameter("BlenderExecutable", "blender",
                              "The worker's Blender (4.2+ with the hyvox extension, or any Blender with the "
                              "hyvox add-on installed); a name on PATH or a full path"));
    params.push(Yaml::map()
                    .add("name", Yaml::text("SessionBlender"))
                    .add("type", Yaml::text("STRING"))
                    .add("default", Yaml::text("true"))
                    .add("allowedValues", Yaml::texts({"true", "false"}))
                    .add("description",
                         Yaml::text("true: one Blender per worker session runs task after task "
                                    "(Blender starts once); false: a Blender of its own per task")));
    for (const OptionSpec* spec : blenderJobOptions()) params.push(optionParameter(*spec));

    const std::vector<std::string> headless_head{"{{Task.File.Run}}", param("BlenderExecutable"), param("BlendFile")};
    Yaml session = Yaml::map()
                       .add("name", Yaml::text("HyvoxSessionBlender"))
                       .add("description", Yaml::text("Keeps one Blender for the session's tasks"))
                       .add("script",
                            Yaml::map()
                                .add("actions",
                                     Yaml::map()
                                         .add("onEnter",
                                              action({"{{Env.File.Enter}}", param("BlenderExecutable"),
                                                      param("SessionBlender"), "{{Session.WorkingDirectory}}"},
                                                     true))
                                         .add("onExit", action({"{{Env.File.Exit}}"}, true)))
                                .add("embeddedFiles",
                                     Yaml::list()
                                         .push(embeddedFile("Enter", enterScript()))
                                         .push(embeddedFile("Exit", exitScript()))));
    Yaml frame = Yaml::map()
                     .add("name", Yaml::text("Frame"))
                     .add("type", Yaml::text("CHUNK[INT]"))
                     .add("range", Yaml::text(param("Frames")))
                     .add("chunks",
                          Yaml::map()
                              .add("defaultTaskCount", Yaml::text(param("ChunkSize")))
                              .add("targetRuntimeSeconds", Yaml::text(param("ChunkSeconds")))
                              .add("rangeConstraint", Yaml::text("NONCONTIGUOUS")));
    Yaml voxelize =
        Yaml::map()
            .add("name", Yaml::text("Voxelize"))
            .add("parameterSpace", Yaml::map().add("taskParameterDefinitions", Yaml::list().push(frame)))
            .add("stepEnvironments", Yaml::list().push(session))
            .add(
                "script",
                Yaml::map()
                    .add("actions",
                         Yaml::map().add("onRun", action(concat(headless_head, farmArgs("run", runArguments())), true)))
                    .add("embeddedFiles", Yaml::list().push(embeddedFile("Run", headlessScript()))));
    Yaml assemble =
        Yaml::map()
            .add("name", Yaml::text("Assemble"))
            .add("dependencies", Yaml::list().push(Yaml::map().add("dependsOn", Yaml::text("Voxelize"))))
            .add("script",
                 Yaml::map()
                     .add("actions",
                          Yaml::map().add(
                              "onRun", action(concat(headless_head, farmArgs("assemble", assembleArguments())), true)))
                     .add("embeddedFiles", Yaml::list().push(embeddedFile("Run", headlessScript()))));
    Yaml job = Yaml::map()
                   .add("specificationVersion", Yaml::text("jobtemplate-2023-09"))
                   .add("extensions", Yaml::texts({"TASK_CHUNKING"}))
                   .add("name", Yaml::text("hyvox: voxelize {{RawParam.BlendFile}} frames {{Param.Frames}}"))
                   .add("description",
                        Yaml::text("Voxelizes the animation of a .blend into one OpenVDB file per "
                                   "frame with the hyvox add-on, then saves a .blend that plays "
                                   "them back as one volume sequence."))
                   .add("parameterDefinitions", params)
                   .add("steps", Yaml::list().push(voxelize).push(assemble));
    return header("job template: voxelize a .blend's animation, a frame chunk per task") + job.render();
}

// Region.sh HYVOX MESH OUTPUT REGIONS REGION [--flag=VALUE UNSET]... -- OPTIONS...: region
// REGION (1..REGIONS) of the grid. The pairs before "--" are options a farm parameter holds
// their unset value for unless given: left out then (the CLI would refuse the value). The
// part's name says which region it is, so a re-run rewrites only its own (atomically: the
// CLI writes a temporary and renames it).
std::string regionScript() {
    return "#!/usr/bin/env bash\n"
           "# One region of the grid (hyvox voxelize --region K/N), K from 0.\n"
           "set -euo pipefail\n"
           "hyvox=$1 mesh=$2 output=$3 regions=$4 region=$5\n"
           "shift 5\n"
           "given=()\n"
           "while [ \"$1\" != -- ]; do\n"
           "  awk -v v=\"${1#*=}\" -v u=\"$2\" 'BEGIN { exit !(v + 0 == u + 0) }' || given+=(\"$1\")\n"
           "  shift 2\n"
           "done\n"
           "shift\n"
           "mkdir -p \"$output.regions\"\n"
           "k=$((region - 1))\n"
           "exec \"$hyvox\" voxelize \"$mesh\" -o \"$output.regions/region_${k}_of_${regions}.vdb\" --region "
           "\"$k/$regions\" "
           "--progress \"${given[@]}\" \"$@\"\n";
}

// Merge.sh HYVOX OUTPUT REGIONS: every part there, then one .vdb of them all.
std::string mergeScript() {
    return "#!/usr/bin/env bash\n"
           "# The regions merged into one .vdb (hyvox merge), once every part is there.\n"
           "set -euo pipefail\n"
           "hyvox=$1 output=$2 regions=$3\n"
           "parts=()\n"
           "for ((k = 0; k < regions; k++)); do\n"
           "  part=\"$output.regions/region_${k}_of_${regions}.vdb\"\n"
           "  [ -f \"$part\" ] || { echo \"hyvox: error: region $k of $regions is missing ($part)\" >&2; exit 1; }\n"
           "  parts+=(\"$part\")\n"
           "done\n"
           "exec \"$hyvox\" merge \"${parts[@]}\" -o \"$output\"\n";
}

std::string regionJobTemplate() {
    Yaml params = Yaml::list();
    params.push(pathParameter("MeshFile", "FILE", "IN", "The mesh to voxelize (PLY, PLY.GZ, OBJ, ...)"));
    params.push(pathParameter("OutputFile", "FILE", "OUT",
                              "The merged .vdb; the regions' parts go to OUTPUT.regions/region_K_of_N.vdb"));
    params.push(
        intParameter("Regions", 4, 1, 4096, "Boxes the grid is split into along its longest axis, one task each"));
    params.push(textParameter("HyvoxExecutable", "hyvox",
                              "The worker's hyvox command (pip install hyvox); a name on PATH or a full path"));
    std::vector<std::string> unset_pairs, options;
    for (const OptionSpec* spec : regionJobOptions()) {
        params.push(optionParameter(*spec));
        const std::string arg = spec->cliFlag() + "=" + param(parameterName(*spec));
        if (spec->nullable) {
            unset_pairs.push_back(arg);
            unset_pairs.push_back(shortestNumber(farmUnsetValue(*spec)));
        } else {
            options.push_back(arg);
        }
    }
    unset_pairs.push_back("--");
    Yaml region_step =
        Yaml::map()
            .add("name", Yaml::text("VoxelizeRegions"))
            .add("parameterSpace",
                 Yaml::map().add("taskParameterDefinitions",
                                 Yaml::list().push(Yaml::map()
                                                       .add("name", Yaml::text("Region"))
                                                       .add("type", Yaml::text("INT"))
                                                       .add("range", Yaml::text("1-{{Param.Regions}}")))))
            .add("script",
                 Yaml::map()
                     .add("actions",
                          Yaml::map().add(
                              "onRun",
                              action(concat({"{{Task.File.Region}}", param("HyvoxExecutable"), param("MeshFile"),
                                             param("OutputFile"), param("Regions"), "{{Task.Param.Region}}"},
                                            concat(unset_pairs, options)),
                                     true)))
                     .add("embeddedFiles", Yaml::list().push(embeddedFile("Region", regionScript()))));
    Yaml merge_step =
        Yaml::map()
            .add("name", Yaml::text("Merge"))
            .add("dependencies", Yaml::list().push(Yaml::map().add("dependsOn", Yaml::text("VoxelizeRegions"))))
            .add("script",
                 Yaml::map()
                     .add("actions",
                          Yaml::map().add("onRun",
                                          action({"{{Task.File.Merge}}", param("HyvoxExecutable"), param("OutputFile"),
                                                  param("Regions")},
                                                 true)))
                     .add("embeddedFiles", Yaml::list().push(embeddedFile("Merge", mergeScript()))));
    Yaml job = Yaml::map()
                   .add("specificationVersion", Yaml::text("jobtemplate-2023-09"))
                   .add("name", Yaml::text("hyvox: {{RawParam.MeshFile}} in {{Param.Regions}} regions"))
                   .add("description",
                        Yaml::text("Voxelizes one mesh's grid as regions of the same global grid, "
                                   "a task each, then merges them into one .vdb (hyvox CLI)."))
                   .add("parameterDefinitions", params)
                   .add("steps", Yaml::list().push(region_step).push(merge_step));
    return header("job template: one grid as region tasks and a merge") + job.render();
}

}  // namespace hyvox::farm
