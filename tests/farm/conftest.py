# SPDX-License-Identifier: GPL-3.0-or-later
"""The render-farm jobs run for real: `openjd run` of the generated templates with Debian's
Blender and the add-on installed as a studio deploys it (a legacy add-on in
$BLENDER_USER_SCRIPTS/addons/), and the Flamenco job type's commands. The oracle is the
add-on's own headless script (cli_blender.py, the operator) over the whole frame range in
one run; voxels are read back with pyopenvdb."""

import json
import os
import subprocess

import numpy as np
import pytest

BUILD = os.environ["HYVOX_BUILD_DIR"]
CLI = os.environ["HYVOX_CLI"]
FARM_VENV = os.environ["HYVOX_FARM_VENV"]
BLENDER = os.environ.get("HYVOX_BLENDER", "blender")
HERE = os.path.dirname(os.path.abspath(__file__))
OPENJD = os.path.join(FARM_VENV, "bin", "openjd")
FARM_PYTHON = os.path.join(FARM_VENV, "bin", "python")
FRAMES = "1-6"
RESOLUTION = "64"

# The animated scene: a torus that moves, turns and grows over frames 1-6 (its bounds and so
# its grid change every frame).
SCENE_SCRIPT = """
import bpy, sys
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.mesh.primitive_torus_add(major_segments=24, minor_segments=12)
torus = bpy.context.active_object
torus.name = "Torus"
for frame, location, angle, scale in ((1, (0, 0, 0), 0.0, 1.0), (6, (2, 1, 0.5), 1.2, 1.5)):
    torus.location, torus.rotation_euler, torus.scale = location, (angle, 0, angle / 2), (scale,) * 3
    for path in ("location", "rotation_euler", "scale"):
        torus.keyframe_insert(path, frame=frame)
bpy.ops.wm.save_as_mainfile(filepath=sys.argv[-1])
"""


def run(command, **kw):
    done = subprocess.run(command, capture_output=True, text=True, timeout=kw.pop("timeout", 300), **kw)
    return done


def check(done):
    assert done.returncode == 0, (done.args, done.stdout[-4000:], done.stderr[-4000:])
    return done


@pytest.fixture(scope="session")
def env(tmp_path_factory):
    """The environment of a farm worker: Debian's Blender first on PATH, the add-on
    installed in its user scripts folder (the job gets no path to it)."""
    scripts = tmp_path_factory.mktemp("user_scripts")
    os.makedirs(scripts / "addons")
    os.symlink(os.path.join(BUILD, "addon", "hyvox_blender"), scripts / "addons" / "hyvox_blender")
    out = dict(os.environ)
    out["BLENDER_USER_SCRIPTS"] = str(scripts)
    out["PATH"] = "/usr/bin:/bin:" + out.get("PATH", "")
    return out


@pytest.fixture(scope="session")
def scene(tmp_path_factory, env):
    path = str(tmp_path_factory.mktemp("scene") / "torus.blend")
    check(run([BLENDER, "-b", "--factory-startup", "-noaudio", "--python-expr", SCENE_SCRIPT, "--", path], env=env))
    return path


@pytest.fixture(scope="session")
def oracle(tmp_path_factory, env, scene):
    """The frames as the operator makes them in one run over the whole range."""
    out = str(tmp_path_factory.mktemp("oracle"))
    cli_blender = os.path.join(BUILD, "addon", "hyvox_blender", "cli_blender.py")
    check(
        run(
            [
                BLENDER,
                "-b",
                "-noaudio",
                scene,
                "--python",
                cli_blender,
                "--",
                "--frames",
                FRAMES,
                "--output",
                out,
                "--resolution",
                RESOLUTION,
                "--method",
                "cpu",
                "--mode",
                "conservative",
                "--objects",
                "Torus",
            ],
            env=env,
        )
    )
    return out


def voxels(path):
    """(sorted world-space centres, voxel size) of a .vdb's density grid."""
    import pyopenvdb as vdb

    grid = vdb.read(path, "density")
    ijk = np.array([item.min for item in grid.citerOnValues()], dtype=np.float64).reshape(-1, 3)
    size = grid.transform.voxelSize()[0]
    zero = np.array(grid.transform.indexToWorld((0, 0, 0)))
    centres = ijk * size + zero
    return centres[np.lexsort(centres.T[::-1])], size


def assert_same_voxels(a, b):
    (ca, sa), (cb, sb) = voxels(a), voxels(b)
    assert sa == sb, (a, b, sa, sb)
    assert ca.shape == cb.shape, (a, b, ca.shape, cb.shape)
    np.testing.assert_array_equal(ca, cb)


def frame_files(folder):
    return sorted(name for name in os.listdir(folder) if name.endswith(".vdb"))


def template(kind, tmp_path):
    path = tmp_path / f"{kind}.template"
    check(run([CLI, "job-template", kind, "-o", str(path)]))
    return str(path)


def openjd_run(template_path, params, env, step=None, extra=()):
    command = [OPENJD, "run", template_path]
    command += ["--step", step] if step else ["--step", "Assemble", "--run-dependencies"]
    for key, value in params.items():
        command += ["-p", f"{key}={value}"]
    return run(command + list(extra), env=env, timeout=600)


def job_params(scene, out, **more):
    params = {
        "BlendFile": scene,
        "OutputDir": out,
        "Frames": FRAMES,
        "ChunkSize": 2,
        "ChunkSeconds": 0,
        "Resolution": RESOLUTION,
        "Method": "cpu",
        "Mode": "conservative",
        "Objects": "Torus",
    }
    params.update(more)
    return params


def probe_assembled(blend, env):
    """What the assembled .blend holds, read by a Blender that opens it."""
    script = os.path.join(HERE, "probe_assembled.py")
    done = check(run([BLENDER, "-b", "-noaudio", blend, "--python", script], env=env))
    line = next(text for text in done.stdout.splitlines() if text.startswith("PROBE "))
    return json.loads(line[len("PROBE ") :])


def load_template(path):
    """A job template as data (PyYAML is in the farm venv)."""
    import json as _json

    done = check(
        run([FARM_PYTHON, "-c", "import json, sys, yaml; print(json.dumps(yaml.safe_load(open(sys.argv[1]))))", path])
    )
    return _json.loads(done.stdout)


def flamenco(job_type_path, settings=None):
    """The Flamenco job type's JOB_TYPE, or what its compileJob authors for `settings`."""
    command = [FARM_PYTHON, os.path.join(HERE, "flamenco_compile.py"), job_type_path]
    if settings is not None:
        command.append(json.dumps(settings))
    return json.loads(check(run(command)).stdout)
