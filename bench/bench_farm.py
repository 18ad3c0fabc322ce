# SPDX-License-Identifier: GPL-3.0-or-later
"""Benchmark (not a test): one 24-frame voxelize job run three ways on this machine, the
Voxelize work only (the Open Job Description job's Assemble is timed on its own):

  loop      a shell loop of `blender -b SCENE --python cli_blender.py -- --frames F-F` per frame
  per task  `openjd run` of hyvox job-template openjd, SessionBlender=false: a Blender per task
  session   the same job with SessionBlender=true: one Blender for the session's tasks

    python3 bench/bench_farm.py [--build build] [--frames 24] [--resolution 128] [--chunks 1,4]
        [--out bench/results]

Prints frames per minute and the per-frame overhead beside the voxelize time (export +
voxelize + write of the add-on's own timings), and writes farm.json and farm.md. The job
gets a fixed voxel size so every way does the same work. openjd-cli comes from the farm
venv (scripts/setup_venvs.sh)."""

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time

from bench_results import Column, Table, add_out_argument

SCENE = """
import bpy, sys
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.mesh.primitive_torus_add(major_segments=48, minor_segments=24)
torus = bpy.context.active_object
torus.name = "Torus"
last = int(sys.argv[-2])
for frame, location, angle in ((1, (0, 0, 0), 0.0), (last, (3, 1, 0.5), 2.0)):
    torus.location, torus.rotation_euler = location, (angle, 0, angle / 2)
    torus.keyframe_insert("location", frame=frame)
    torus.keyframe_insert("rotation_euler", frame=frame)
bpy.ops.wm.save_as_mainfile(filepath=sys.argv[-1])
"""
# The add-on's per-run summary line: what a frame's own work took.
WORK = re.compile(r"hyvox: export (\d+) ms, voxelize (\d+) ms, write (\d+) ms")


def worker_env(build, scripts):
    os.makedirs(os.path.join(scripts, "addons"), exist_ok=True)
    link = os.path.join(scripts, "addons", "hyvox_blender")
    if not os.path.islink(link):
        os.symlink(os.path.abspath(os.path.join(build, "addon", "hyvox_blender")), link)
    env = dict(os.environ, BLENDER_USER_SCRIPTS=scripts)
    env["PATH"] = "/usr/bin:/bin:" + env.get("PATH", "")
    return env


def timed(command, env):
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True, env=env)
    seconds = time.perf_counter() - start
    if done.returncode:
        sys.exit(f"failed: {' '.join(command[:4])}...\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}")
    work_ms = sum(sum(map(int, m.groups())) for m in WORK.finditer(done.stdout))
    return seconds, work_ms / 1000.0, done.stdout


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", default="build")
    parser.add_argument("--frames", type=int, default=24)
    parser.add_argument("--resolution", type=int, default=128)
    parser.add_argument("--chunks", default="1,4", help="frames per task of the OpenJD runs")
    add_out_argument(parser)
    args = parser.parse_args()
    build = os.path.abspath(args.build)
    openjd = os.path.join(build, "venv", "farm", "bin", "openjd")
    cli = os.path.join(build, "hyvox")
    work = tempfile.mkdtemp(prefix="hyvox_bench_farm_")
    env = worker_env(build, os.path.join(work, "scripts"))
    scene = os.path.join(work, "torus.blend")
    subprocess.run(
        ["blender", "-b", "--factory-startup", "-noaudio", "--python-expr", SCENE, "--", str(args.frames), scene],
        check=True,
        capture_output=True,
        env=env,
    )
    template = os.path.join(work, "hyvox.openjd.yaml")
    subprocess.run([cli, "job-template", "openjd", "-o", template], check=True)
    voxel_size = 4.0 / args.resolution  # about the torus' longest side over the resolution
    frames = f"1-{args.frames}"
    rows = []

    loop_out = os.path.join(work, "loop")
    cli_blender = os.path.join(build, "addon", "hyvox_blender", "cli_blender.py")
    start, work_s = time.perf_counter(), 0.0
    for frame in range(1, args.frames + 1):
        _, w, _ = timed(
            [
                "blender",
                "-b",
                "-noaudio",
                scene,
                "--python",
                cli_blender,
                "--",
                "--frames",
                f"{frame}-{frame}",
                "--output",
                loop_out,
                "--voxel-size",
                repr(voxel_size),
                "--method",
                "cpu",
                "--mode",
                "conservative",
                "--objects",
                "Torus",
            ],
            env,
        )
        work_s += w
    rows.append(
        {
            "way": "shell loop, blender -b per frame",
            "tasks": args.frames,
            "blenders": args.frames,
            "seconds": time.perf_counter() - start,
            "work_seconds": work_s,
        }
    )

    for session in ("false", "true"):
        for chunk in (int(c) for c in args.chunks.split(",")):
            out = os.path.join(work, f"openjd_{session}_{chunk}")
            command = [openjd, "run", template, "--step", "Voxelize"]
            params = {
                "BlendFile": scene,
                "OutputDir": out,
                "Frames": frames,
                "ChunkSize": chunk,
                "ChunkSeconds": 0,
                "VoxelSize": repr(voxel_size),
                "Method": "cpu",
                "Mode": "conservative",
                "Objects": "Torus",
                "SessionBlender": session,
            }
            for key, value in params.items():
                command += ["-p", f"{key}={value}"]
            seconds, work_s, _ = timed(command, env)
            tasks = -(-args.frames // chunk)
            rows.append(
                {
                    "way": ("OpenJD, one Blender per session" if session == "true" else "OpenJD, one Blender per task")
                    + f", chunks of {chunk}",
                    "tasks": tasks,
                    "blenders": 1 if session == "true" else tasks,
                    "seconds": seconds,
                    "work_seconds": work_s,
                }
            )
    assemble = [openjd, "run", template, "--step", "Assemble"]
    for key, value in {
        "BlendFile": scene,
        "OutputDir": os.path.join(work, "openjd_true_1"),
        "Frames": frames,
        "VoxelSize": repr(voxel_size),
        "Objects": "Torus",
    }.items():
        assemble += ["-p", f"{key}={value}"]
    assemble_seconds, _, _ = timed(assemble, env)

    for row in rows:
        row["frames_per_minute"] = 60.0 * args.frames / row["seconds"]
        row["overhead_per_frame_s"] = (row["seconds"] - row["work_seconds"]) / args.frames
        row["work_per_frame_s"] = row["work_seconds"] / args.frames
    blender = subprocess.run(["blender", "--version"], capture_output=True, text=True).stdout.split("\n")[0]
    table = Table(
        "farm",
        f"The farm job three ways ({blender}, torus, {args.frames} frames, voxel size "
        f"{voxel_size:g} (~{args.resolution}^3), cpu)",
        [
            Column("way"),
            Column("tasks"),
            Column("Blender starts"),
            Column("seconds", 1),
            Column("frames / min", 0),
            Column("overhead / frame (s)", 3),
            Column("voxelize / frame (s)", 3),
        ],
    )
    for r in rows:
        table.add(
            [
                r["way"],
                r["tasks"],
                r["blenders"],
                r["seconds"],
                r["frames_per_minute"],
                r["overhead_per_frame_s"],
                r["work_per_frame_s"],
            ]
        )
    table.note(
        f"Assemble step (one Blender: check {args.frames} files, save the .blend): {assemble_seconds:.1f} s. "
        "voxelize / frame: the add-on's export + voxelize + write; overhead: the rest (Blender start-up, "
        "file load, the add-on, the farm runner)."
    )
    table.write(args.out)


if __name__ == "__main__":
    main()
