# SPDX-License-Identifier: GPL-3.0-or-later
"""The generated jobs: valid for Open Job Description's own checker, and every voxelize
option a parameter (a Flamenco setting) equal to its entry of the options schema, for
exactly the options the add-on's headless script takes."""

import math
import os

import hyvox
import pytest

from conftest import BLENDER, CLI, OPENJD, check, flamenco, load_template, run, template


def camel(name):
    return "".join(part.capitalize() for part in name.split("_"))


def headless_options(env):
    """method + the Scene's settings: the voxelize options cli_blender.py takes."""
    expr = (
        "import addon_utils, sys; addon_utils.enable('hyvox_blender', default_set=False, handle_error=None); "
        "from hyvox_blender.blender.ui.properties import SCENE_OPTIONS; print('OPTIONS', ','.join(SCENE_OPTIONS))"
    )
    done = check(run([BLENDER, "-b", "--factory-startup", "-noaudio", "--python-expr", expr], env=env))
    line = next(text for text in done.stdout.splitlines() if text.startswith("OPTIONS "))
    return ["method"] + line.split(" ", 1)[1].split(",")


def expected_parameter(spec):
    """What the schema says an OpenJD parameter for `spec` is."""
    default = hyvox.Options().get(spec.name)
    out = {"name": camel(spec.name)}
    if spec.type == "int":
        out.update(type="INT", default=default, minValue=int(spec.min), maxValue=int(spec.max))
    elif spec.type == "float":
        out.update(type="FLOAT", default=spec.min if default is None else default)
        out.update({k: v for k, v in (("minValue", spec.min), ("maxValue", spec.max)) if math.isfinite(v)})
    elif spec.type == "choice":
        out.update(type="STRING", default=default, allowedValues=list(spec.choices))
    elif spec.type == "str":
        out.update(type="STRING", default=default)
    return out


@pytest.mark.parametrize("kind", ["openjd", "openjd-regions"])
def test_openjd_check_passes(tmp_path, kind):
    done = check(run([OPENJD, "check", template(kind, tmp_path)]))
    assert "passes validation checks" in done.stdout


def test_blender_job_parameters_are_the_schema_options_of_the_headless_script(tmp_path, env):
    params = {p["name"]: p for p in load_template(template("openjd", tmp_path))["parameterDefinitions"]}
    names = headless_options(env)
    assert {"BlendFile", "OutputDir", "Frames", "Objects", "BlenderExecutable"} <= set(params)
    option_params = {n for n, p in params.items() if p.get("userInterface", {}).get("groupLabel") == "Voxelize Options"}
    assert option_params == {camel(n) for n in names}
    for name in names:
        spec = hyvox.option(name)
        param = params[camel(name)]
        assert {k: param.get(k) for k in expected_parameter(spec)} == expected_parameter(spec)
        assert param["description"].startswith(spec.help), (param["description"], spec.help)
        assert param["userInterface"]["label"] == spec.label


def test_region_job_parameters_equal_the_schema(tmp_path):
    params = {p["name"]: p for p in load_template(template("openjd-regions", tmp_path))["parameterDefinitions"]}
    for spec in hyvox.OPTIONS:
        if camel(spec.name) in params:
            param = params[camel(spec.name)]
            assert {k: param.get(k) for k in expected_parameter(spec)} == expected_parameter(spec)
    assert {"Attributes", "MemoryBudgetMib", "Threads", "Resolution", "VoxelSize", "Mode", "Method"} <= set(params)


def test_flamenco_settings_are_the_same_options(tmp_path, env):
    settings = {s["key"]: s for s in flamenco(template("flamenco", tmp_path))["settings"]}
    names = headless_options(env)
    assert {"frames", "chunk_size", "output_dir", "objects", "blendfile"} | set(names) == set(settings)
    types = {"int": "int32", "float": "float", "choice": "string", "str": "string"}
    for name in names:
        spec, setting = hyvox.option(name), settings[name]
        default = hyvox.Options().get(name)
        assert setting["type"] == types[spec.type]
        assert setting["default"] == (spec.min if default is None else default)
        assert setting.get("choices", []) == list(spec.choices)
        if spec.type in ("int", "float"):
            assert setting["propargs"] == {k: v for k, v in (("min", spec.min), ("max", spec.max)) if math.isfinite(v)}
        assert setting["description"].startswith(spec.help)


def test_job_template_command_errors(tmp_path):
    for args in ([], ["bogus"], ["openjd", "flamenco"], ["openjd", "-o"]):
        done = run([CLI, "job-template", *args])
        assert done.returncode == 2 and "hyvox: error:" in done.stderr, (args, done.stderr)
    done = run([CLI, "job-template", "openjd", "-o", str(tmp_path / "no" / "such" / "folder" / "t.yaml")])
    assert done.returncode == 1 and "hyvox: error:" in done.stderr, done.stderr
    assert not os.path.exists(tmp_path / "no")
