# SPDX-License-Identifier: GPL-3.0-or-later
"""`openjd run` of the Blender job (hyvox job-template openjd) with Debian's Blender: the
frames 1-6 in chunks of 2 on a session Blender equal the operator's frames, and the
assembled .blend plays them as one volume sequence; a task cancelled half way (SIGTERM)
leaves no partial file, and its re-run gives the files of an uninterrupted run."""

import os
import re
import signal
import subprocess

from conftest import OPENJD, assert_same_voxels, check, frame_files, job_params, openjd_run, probe_assembled, template

# The OpenVDB header's file UUID (bytes 21-56): new for every file written; the rest of two
# writes of the same voxels is the same, byte for byte.
UUID = slice(21, 57)


def same_file_but_its_uuid(a, b):
    with open(a, "rb") as fa, open(b, "rb") as fb:
        x, y = bytearray(fa.read()), bytearray(fb.read())
    x[UUID], y[UUID] = b"", b""
    return x == y


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


def test_cancelled_task_leaves_no_partial_file_and_its_rerun_gives_the_same_files(tmp_path, env, scene):
    # One task of six frames at a resolution where a frame takes a moment: the cancel comes
    # once the first frame is written, long before the last one.
    job = template("openjd", tmp_path)
    clean = str(tmp_path / "uninterrupted")
    check(openjd_run(job, job_params(scene, clean, ChunkSize=6, Resolution=768), env, step="Voxelize"))
    out = str(tmp_path / "farm")
    params = job_params(scene, out, ChunkSize=6, Resolution=768)
    command = [OPENJD, "run", job, "--step", "Voxelize"] + [a for k, v in params.items() for a in ("-p", f"{k}={v}")]
    farm = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
    log = []
    for line in farm.stdout:
        log.append(line)
        if "hyvox: frame 1: " in line:
            farm.send_signal(signal.SIGTERM)
            break
    log.extend(farm.stdout)
    assert farm.wait(timeout=120) != 0, "".join(log[-40:])
    assert "cancelled by the farm (SIGTERM)" in "".join(log), "".join(log[-40:])
    kept = frame_files(out)
    assert "Torus_voxels_0001.vdb" in kept and len(kept) < 6, ("the cancel came too late", kept, "".join(log[-40:]))
    assert sorted(os.listdir(out)) == kept  # no staging (.partial) file, nothing else
    for name in kept:
        assert same_file_but_its_uuid(os.path.join(out, name), os.path.join(clean, name))
    check(openjd_run(job, params, env, step="Voxelize"))
    assert sorted(os.listdir(out)) == frame_files(clean)
    for name in frame_files(clean):
        assert same_file_but_its_uuid(os.path.join(out, name), os.path.join(clean, name))
