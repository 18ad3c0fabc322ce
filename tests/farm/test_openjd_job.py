# SPDX-License-Identifier: GPL-3.0-or-later
"""`openjd run` of the Blender job (hyvox job-template openjd) with Debian's Blender: the
frames 1-6 in chunks of 2 on a session Blender equal the operator's frames, and the
assembled .blend plays them as one volume sequence; a task cancelled half way (SIGTERM)
leaves no partial file, and its re-run gives the operator's files."""
import os
import re
import signal
import subprocess

from conftest import (BLENDER, BUILD, FRAMES, OPENJD, assert_same_voxels, check, frame_files, job_params,
                      openjd_run, probe_assembled, run, template)

HEAVY_SCENE = """
import bpy, sys
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.mesh.primitive_uv_sphere_add(segments=512, ring_count=256)
ball = bpy.context.active_object
ball.name = "Ball"
for frame, x in ((1, 0.0), (6, 3.0)):
    ball.location = (x, 0, 0)
    ball.keyframe_insert("location", frame=frame)
bpy.ops.wm.save_as_mainfile(filepath=sys.argv[-1])
"""


def test_job_equals_the_operator_frame_by_frame(tmp_path, env, scene, oracle):
    out = str(tmp_path / "farm")
    done = check(openjd_run(template("openjd", tmp_path), job_params(scene, out), env))
    assert done.stdout.count("Frame(CHUNK[INT]) = ") == 3, done.stdout[-3000:]  # chunks of 2
    # One Blender served every chunk: started once, by the step's environment.
    assert done.stdout.count("session Blender") >= 1 and done.stdout.count("ready on ") == 1, done.stdout[-3000:]
    names = frame_files(out)
    assert names == frame_files(oracle) == [f"Torus_voxels_{f:04d}.vdb" for f in range(1, 7)]
    for name in names:
        assert_same_voxels(os.path.join(out, name), os.path.join(oracle, name))
    # A line per frame with its voxel count, as a farm's task log shows it.
    assert len(re.findall(r"\thyvox: frame \d+: [\d,]+ voxels in ", done.stdout)) == 6, done.stdout[-3000:]
    (volume,) = probe_assembled(os.path.join(out, "torus_voxels.blend"), env)
    assert volume["is_sequence"] and (volume["frame_start"], volume["frame_duration"]) == (1, 6)
    assert volume["materials"], volume
    for frame, path in volume["frames"].items():
        assert os.path.samefile(path, os.path.join(out, f"Torus_voxels_{int(frame):04d}.vdb")), (frame, path)
    assert not any(name.startswith(".") for name in os.listdir(out))


def test_cancelled_task_leaves_no_partial_file_and_its_rerun_gives_the_same_files(tmp_path, env):
    scene = str(tmp_path / "ball.blend")
    check(run([BLENDER, "-b", "--factory-startup", "-noaudio", "--python-expr", HEAVY_SCENE, "--", scene], env=env))
    oracle = str(tmp_path / "oracle")
    cli_blender = os.path.join(BUILD, "addon", "hyvox_blender", "cli_blender.py")
    check(run([BLENDER, "-b", "-noaudio", scene, "--python", cli_blender, "--", "--frames", FRAMES, "--output", oracle,
               "--resolution", "384", "--method", "cpu", "--mode", "conservative", "--objects", "Ball"], env=env))
    out = str(tmp_path / "farm")
    job = template("openjd", tmp_path)
    params = job_params(scene, out, ChunkSize=6, Resolution=384, Objects="Ball")
    command = [OPENJD, "run", job, "--step", "Voxelize"] + [a for k, v in params.items() for a in ("-p", f"{k}={v}")]
    farm = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
    log = []
    for line in farm.stdout:  # the farm cancels once the first frame is written
        log.append(line)
        if "hyvox: frame 1: " in line:
            farm.send_signal(signal.SIGTERM)
            break
    log.extend(farm.stdout)
    assert farm.wait(timeout=120) != 0, "".join(log[-40:])
    kept = frame_files(out)
    assert "Ball_voxels_0001.vdb" in kept and len(kept) < 6, ("the cancel came too late", kept, "".join(log[-40:]))
    assert sorted(os.listdir(out)) == kept  # no staging (.partial) file, nothing else
    for name in kept:
        assert_same_voxels(os.path.join(out, name), os.path.join(oracle, name))
    check(openjd_run(job, params, env, step="Voxelize"))
    assert sorted(os.listdir(out)) == frame_files(oracle)
    for name in frame_files(oracle):
        assert_same_voxels(os.path.join(out, name), os.path.join(oracle, name))
