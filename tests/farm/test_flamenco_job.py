# SPDX-License-Identifier: GPL-3.0-or-later
"""The Flamenco job type (hyvox job-template flamenco): its compileJob, run in QuickJS against
Flamenco's documented API (flamenco_api.js), authors a task per frame chunk and an assemble
task after them, with the OpenJD template's command lines; those commands, run for real as
Flamenco Worker runs blender-render, give the operator's frames."""

import os

from conftest import (
    BLENDER,
    assert_same_voxels,
    check,
    flamenco,
    frame_files,
    load_template,
    probe_assembled,
    run,
    template,
)


def test_compiled_commands_run_for_real(tmp_path, env, scene, oracle):
    job_type = template("flamenco", tmp_path)
    out = str(tmp_path / "farm")
    settings = {s["key"]: s.get("default") for s in flamenco(job_type)["settings"]}
    settings.update(
        frames="1-6",
        chunk_size=2,
        output_dir=out,
        objects="Torus",
        blendfile=scene,
        resolution=64,
        method="cpu",
        mode="conservative",
    )
    tasks = flamenco(job_type, settings)["tasks"]
    assert [t["name"] for t in tasks] == ["voxelize-1,2", "voxelize-3,4", "voxelize-5,6", "assemble"]
    assert tasks[-1]["dependencies"] == [t["name"] for t in tasks[:-1]]
    assert all(t["type"] == "blender" and len(t["commands"]) == 1 for t in tasks)

    # The same command lines as the OpenJD template's, value for value.
    openjd = load_template(template("openjd", tmp_path))
    params = {
        p["name"]: str(settings[key])
        for p, key in (
            (p, k)
            for p in openjd["parameterDefinitions"]
            for k in settings
            if k.replace("_", "") == p["name"].lower().replace("dir", "_dir").replace("_", "")
        )
    }
    for step, task in ((openjd["steps"][0], tasks[0]), (openjd["steps"][1], tasks[-1])):
        expected = step["script"]["actions"]["onRun"]["args"][3:]
        expected = [a.replace("{{Task.Param.Frame}}", "1,2") for a in expected]
        for name, value in params.items():
            expected = [a.replace("{{Param." + name + "}}", value) for a in expected]
        args = task["commands"][0]["parameters"]["args"]
        assert args[args.index("--") + 1 :] == expected

    for task in tasks:  # in their dependency order
        (command,) = task["commands"]
        assert command["name"] == "blender-render"
        p = command["parameters"]
        assert (p["exe"], p["exeArgs"], p["argsBefore"], p["blendfile"]) == ("{blender}", "{blenderArgs}", [], scene)
        # {exe} {exeArgs} {argsBefore} {blendfile} {args}, with the Manager's defaults.
        check(run([BLENDER, "-b", "-y", *p["argsBefore"], p["blendfile"], *p["args"]], env=env))
    assert frame_files(out) == frame_files(oracle)
    for name in frame_files(out):
        assert_same_voxels(os.path.join(out, name), os.path.join(oracle, name))
    (volume,) = probe_assembled(os.path.join(out, "torus_voxels.blend"), env)
    assert volume["is_sequence"] and (volume["frame_start"], volume["frame_duration"]) == (1, 6)
