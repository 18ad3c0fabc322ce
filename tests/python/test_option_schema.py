# SPDX-License-Identifier: GPL-3.0-or-later
"""The options schema is the one source of every front door: each option's bad values are
refused with the same message by the CLI and the Python module, every option set on the
command line or in Python reaches the run (stats["options"]), the environment variables the
schema names are read by both doors, and the generated stubs and docstring list every option.
Parametrised over hyvox.OPTIONS itself, so an option added later is tested without new code."""

import ast
import json
import math
import pathlib
import subprocess

import numpy as np
import pytest

import hyvox

TETRA_V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], np.float32)
TETRA_T = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], np.uint32)


def bad_values(spec):
    """(python value, command-line text) pairs the schema must refuse, from its own limits."""
    if spec.name == "region":  # text of a form of its own, K/N with K < N
        return [("2/2", "2/2"), ("1", "1"), ("1/2049", "1/2049")]
    if spec.type in ("int", "float"):
        below = spec.min if spec.min_exclusive else spec.min - 1
        cases = [below] if math.isfinite(spec.min) else []
        if math.isfinite(spec.max):
            cases.append(spec.max + 1)
        if spec.type == "int":
            cases = [int(v) for v in cases]
            return [(v, str(v)) for v in cases] + [("many", "many")]
        return [(float(v), repr(float(v))) for v in cases] + [(float("nan"), "nan")]
    return {
        "choice": [("bogus", "bogus")],
        "choices": [("bogus", "bogus"), ("color,bogus", "color,bogus")],
        "bool": [("maybe", "maybe")],
        "vector3": [("1,2", "1,2")],
        "box": [("1,2,3", "1,2,3")],
        "str": [],  # any text is a valid value
    }[spec.type]


CASES = [(spec.name, py, text) for spec in hyvox.OPTIONS for py, text in bad_values(spec)]


def test_every_option_kind_has_bad_values():
    refused = {name for name, _, _ in CASES}
    for spec in hyvox.OPTIONS:
        assert spec.name in refused or spec.type == "str", spec.name


def schema_message(name, value):
    with pytest.raises((ValueError, TypeError)) as error:
        hyvox.check_option(name, value)
    return str(error.value)


@pytest.mark.parametrize("name,value,text", CASES, ids=[f"{n}={t}" for n, _, t in CASES])
def test_bad_value_same_message_in_python_and_cli(name, value, text, cli, tmp_path):
    message = schema_message(name, value)
    assert message.startswith(f"{name} must be ") or message.startswith(f"unknown {name} '"), message
    assert message.rsplit(", got ", 1)[-1] or "choose one of" in message

    with pytest.raises((ValueError, TypeError)) as python_error:
        hyvox.voxelize(TETRA_V, TETRA_T, **{name: value})
    assert str(python_error.value) == message

    spec = hyvox.option(name)
    done = subprocess.run(
        [str(cli), "voxelize", "mesh.ply", "-o", str(tmp_path / "out.vdb"), f"{spec.cli_flag}={text}"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode == 2
    assert f"hyvox: error: {spec.cli_flag}: {message}\n" in done.stderr
    assert not (tmp_path / "out.vdb").exists()


def good_value(spec):
    """A valid value other than the default, for runs of the cpu method on a tetrahedron."""
    special = {
        "method": "reference",
        "voxel_size": 0.125,
        "origin": (-0.5, -0.25, 0.0),
        "bounds": ((-0.5, -0.5, -0.5), (1.5, 1.5, 1.5)),
        "gl_device": "software",
        "shader_dir": "/nonexistent/shaders",
        "displacement_image": "height.png",
        "attributes": "normal",
        "region": "1/2",
        "memory_budget_mib": 512,
    }
    if spec.name in special:
        return special[spec.name]
    if spec.type == "choice":
        return next(c for c in spec.choices if c != spec.default)
    if spec.type == "bool":
        return not spec.default
    if spec.type == "int":
        return spec.default + 1 if spec.default + 1 <= spec.max else spec.default - 1
    if spec.type == "float":
        return spec.default + 0.5 if spec.default + 0.5 <= spec.max else spec.default / 2
    raise AssertionError(f"no good value for {spec.name} ({spec.type})")


def as_json(value):
    return json.loads(json.dumps(value))


def cli_text(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, tuple):
        return ",".join(cli_text(v) for v in np.ravel(value))
    return str(value)


@pytest.mark.filterwarnings("ignore::hyvox.IgnoredOptionWarning")  # other methods' options on purpose
@pytest.mark.parametrize("spec", hyvox.OPTIONS, ids=lambda s: s.name)
def test_every_option_reaches_the_run_from_both_doors(spec, cli, tmp_path, tetra_obj):
    value = good_value(spec)
    assert value != spec.default
    # cpu ignores the GL and tessellation options, so every one can be set on a cpu run.
    others = {} if spec.name == "method" else {"method": "cpu"}
    grid = hyvox.voxelize(TETRA_V, TETRA_T, **others, **{spec.name: value})
    assert grid.stats["options"][spec.name] == as_json(value)

    stats = tmp_path / "stats.json"
    args = [
        str(cli),
        "voxelize",
        str(tetra_obj),
        "-o",
        str(tmp_path / "out.vdb"),
        "--stats-json",
        str(stats),
        "-q",
        f"{spec.cli_flag}={cli_text(value)}",
    ] + [f"--{k}={v}" for k, v in others.items()]
    done = subprocess.run(args, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert json.loads(stats.read_text())["options"][spec.name] == as_json(value)


ENV_SPECS = [spec for spec in hyvox.OPTIONS if spec.env]


def test_environment_variables_are_schema_options():
    assert {spec.env for spec in ENV_SPECS} == {
        "HYVOX_GL_DEVICE",
        "HYVOX_SHADER_DIR",
        "HYVOX_GL_TILE_BYTES",
        "HYVOX_GL_WALL_TIMING",
        "HYVOX_TESS_INSTANCED",
    }


@pytest.mark.filterwarnings("ignore::hyvox.IgnoredOptionWarning")  # other methods' options on purpose
@pytest.mark.parametrize("spec", ENV_SPECS, ids=lambda s: s.env)
def test_environment_reaches_the_run_from_both_doors(spec, cli, tmp_path, monkeypatch, tetra_obj):
    value = good_value(spec)
    monkeypatch.setenv(spec.env, cli_text(value))
    grid = hyvox.voxelize(TETRA_V, TETRA_T, method="cpu")
    assert grid.stats["options"][spec.name] == as_json(value)
    # An explicit keyword wins over the environment.
    assert hyvox.voxelize(TETRA_V, TETRA_T, **{spec.name: spec.default}).stats["options"][spec.name] == spec.default

    stats = tmp_path / "stats.json"
    done = subprocess.run(
        [str(cli), "voxelize", str(tetra_obj), "-o", str(tmp_path / "o.vdb"), "-q", "--stats-json", str(stats)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    assert json.loads(stats.read_text())["options"][spec.name] == as_json(value)


def test_bad_environment_value_names_the_variable(cli, monkeypatch):
    monkeypatch.setenv("HYVOX_GL_TILE_BYTES", "lots")
    with pytest.raises(ValueError, match="HYVOX_GL_TILE_BYTES: gl_tile_bytes must be a whole number"):
        hyvox.voxelize(TETRA_V, TETRA_T)
    done = subprocess.run([str(cli), "voxelize", "m.ply", "-o", "o.vdb"], capture_output=True, text=True, timeout=60)
    assert done.returncode == 2 and "HYVOX_GL_TILE_BYTES: gl_tile_bytes must be a whole number" in done.stderr


def test_unknown_option_is_a_type_error_naming_the_options():
    with pytest.raises(TypeError, match=r"unknown option 'resolutoin' \(the options are: resolution, "):
        hyvox.voxelize(TETRA_V, TETRA_T, resolutoin=8)


@pytest.mark.filterwarnings("ignore::hyvox.IgnoredOptionWarning")  # other methods' options on purpose
def test_unset_options_are_the_schema_defaults(cli, tmp_path, tetra_obj):
    # Unset at either door must mean the schema's default: a run that leaves every option
    # unset and one that spells each default out set the same voxels and report the same
    # options (a door with defaults of its own would differ here).
    explicit = {spec.name: spec.default for spec in hyvox.OPTIONS if spec.default is not None}
    unset, spelled = hyvox.voxelize(TETRA_V, TETRA_T), hyvox.voxelize(TETRA_V, TETRA_T, **explicit)
    assert unset.stats["options"] == spelled.stats["options"]
    assert np.array_equal(unset.to_dense(), spelled.to_dense())
    stats = tmp_path / "stats.json"
    done = subprocess.run(
        [str(cli), "voxelize", str(tetra_obj), "-o", str(tmp_path / "o.vdb"), "-q", "--stats-json", str(stats)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    cli_stats = json.loads(stats.read_text())
    assert cli_stats["options"] == unset.stats["options"]
    assert cli_stats["voxel_count"] == unset.voxel_count


STUB_TYPES = {
    "int": "int",
    "float": "float",
    "bool": "bool",
    "str": "str",
    "vector3": "Sequence[float]",
    "box": "Tuple[Sequence[float], Sequence[float]]",
}


def test_generated_stubs_list_every_option():
    stub = pathlib.Path(hyvox.__file__).with_name("__init__.pyi")
    tree = ast.parse(stub.read_text())
    voxelize = next(node for node in tree.body if isinstance(node, ast.FunctionDef) and node.name == "voxelize")
    keywords = {arg.arg: ast.unparse(arg.annotation) for arg in voxelize.args.kwonlyargs}
    for spec in hyvox.OPTIONS:
        names = "Literal[" + ", ".join(repr(c) for c in spec.choices) + "]"
        inner = {"choice": names, "choices": f"Union[str, Sequence[{names}]]"}.get(spec.type) or STUB_TYPES[spec.type]
        assert keywords.pop(spec.name) == f"Optional[{inner}]", spec.name
    assert set(keywords) == {
        "uvs",
        "normals",
        "displacement_pixels",
        "colors",
        "texture",
        "material_ids",
        "palette",
        "textures",
        "face_normals",
        "progress",
        "cancel",
    }


def test_generated_stubs_list_every_write_option():
    stub = pathlib.Path(hyvox.__file__).with_name("_core.pyi")
    tree = ast.parse(stub.read_text())
    grid = next(node for node in tree.body if isinstance(node, ast.ClassDef) and node.name == "VoxelGrid")
    write_vdb = next(node for node in grid.body if isinstance(node, ast.FunctionDef) and node.name == "write_vdb")
    keywords = [arg.arg for arg in write_vdb.args.args[2:] + write_vdb.args.kwonlyargs]
    assert sorted(keywords) == sorted([spec.name for spec in hyvox.WRITE_OPTIONS] + ["cancel", "progress"])


def test_docstring_and_cli_help_list_every_option(cli):
    helptext = subprocess.run([str(cli), "voxelize", "--help"], capture_output=True, text=True, timeout=60).stdout
    for spec in hyvox.OPTIONS:
        assert f"    {spec.name} ({spec.type}" in hyvox.voxelize.__doc__
    for spec in hyvox.OPTIONS + hyvox.WRITE_OPTIONS:
        assert f"  {spec.cli_flag}" in helptext and spec.help in helptext


def test_stats_have_the_backends_typed_section():
    stats = hyvox.voxelize(TETRA_V, TETRA_T, method="cpu").stats
    assert isinstance(stats["cpu"]["split_triangles"], int)
    assert not {"reference", "hybrid", "tessellation"} & set(stats)
    reference = hyvox.voxelize(TETRA_V, TETRA_T, resolution=4, method="reference").stats
    # The brute force tests every voxel of each triangle's bounding box: at least one each.
    assert reference["reference"]["voxel_tests"] >= len(TETRA_T) and "cpu" not in reference


METHOD_GROUPS = {
    "gl": {"triangle", "fragment", "hybrid", "tessellation"},
    "hybrid": {"hybrid"},
    "tessellation": {"tessellation"},
}


@pytest.mark.parametrize("spec", [s for s in hyvox.OPTIONS if s.group in METHOD_GROUPS], ids=lambda s: s.name)
def test_cli_warns_about_options_the_method_ignores(spec, cli, tmp_path, tetra_obj):
    flag = f"{spec.cli_flag}={cli_text(good_value(spec))}"
    done = subprocess.run(
        [str(cli), "voxelize", str(tetra_obj), "-o", str(tmp_path / "o.vdb"), "-q", "--method=cpu", flag],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    assert f"hyvox: warning: {spec.cli_flag} does not apply to the cpu method: ignored" in done.stderr
    # The method the option belongs to takes it without a word (on llvmpipe where there is no GPU).
    method = sorted(METHOD_GROUPS[spec.group])[-1]
    done = subprocess.run(
        [str(cli), "voxelize", str(tetra_obj), "-o", str(tmp_path / "o.vdb"), "-q", f"--method={method}", flag],
        capture_output=True,
        text=True,
        timeout=120,
    )
    # The arguments must have parsed (warnings are printed right after parsing, a usage error,
    # status 2, prints none); the run itself may fail on the test value (a missing shader
    # folder or displacement image, a tile too small).
    assert done.returncode != 2, done.stderr
    assert "warning" not in done.stderr
