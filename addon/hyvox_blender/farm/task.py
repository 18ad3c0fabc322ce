# SPDX-License-Identifier: GPL-3.0-or-later
"""A farm task inside Blender: `run` voxelizes frames, `assemble` checks them and saves the
.blend that plays them back. Both take the job's options as the headless script does
(cli_blender.py), plus the job's own (the farm task's table, farm/arguments.py):

    run      --frames CHUNK --job-frames ALL --output DIR [--objects A,B] [--blend FILE]
             [--resolution N] [--voxel-size S] [cli_blender.py's other options]
    assemble --job-frames ALL --output DIR [--objects A,B] [--blend FILE]
             [--resolution N] [--voxel-size S] [--viewport]

Every frame of the job has the voxel size of the job's first frame (as one run over the
whole range gives them), also in a chunk that does not hold that frame: from --voxel-size,
else from the first frame's meshes and --resolution (hyvox.plan_grid). Each frame is its
own operator run, renamed into place when it is written, so a chunk stopped half way keeps
the frames it finished and a re-run rewrites only its own. --voxel-size 0 means unset (a
farm parameter always has a value). --blend: open this file first (a session's Blender
runs task after task; each starts from the file as saved)."""

import contextlib
import importlib
import os
import signal
import sys
import time

import bpy

from ..core import backend, frame_ranges, naming
from ..core.errors import CancelledError, HyvoxError
from ..core.pipeline import GroupResult
from ..blender.export import frames as frame_export, sources as export
from ..blender.ui import properties
from ..blender.volume import importer
from .arguments import parse as parse_arguments

PACKAGE = __package__.rpartition(".")[0]  # the add-on: hyvox_blender or bl_ext.<repo>.hyvox_blender


class FarmError(HyvoxError):
    """A task that cannot do its work (a frame missing, a file unreadable)."""


class Cancelled(CancelledError):
    """SIGTERM: the farm cancelled the task (the operator reports it as a cancel)."""


_cancelled = []  # set once SIGTERM came: the task's exit status says so


def _cancel(signum, frame):
    _cancelled.append(signum)
    raise Cancelled("cancelled by the farm (SIGTERM); no partial file is left")


@contextlib.contextmanager
def cancel_on_sigterm():
    """SIGTERM raises Cancelled in the task's code (Python runs the handler once the native
    call in progress returns); the run being written is discarded by the operator."""
    previous = signal.signal(signal.SIGTERM, _cancel)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def _cli():
    return importlib.import_module(PACKAGE + ".cli_blender")


def _sources(object_names):
    """The objects the job voxelizes, chosen as the headless script chooses them (the file's
    selection or every visible mesh when none are named), and their one group."""
    chosen = _cli().choose_objects(object_names.split(",") if object_names else None)
    sources = export.pick_sources(chosen)
    (group,) = export.make_groups(sources, separate=False, active=bpy.context.view_layer.objects.active)
    return group


def job_voxel_size(args, group):
    """--voxel-size, else the voxel size the job's first frame gets at --resolution."""
    if args.voxel_size > 0:
        return args.voxel_size
    scene = bpy.context.scene
    if args.resolution is None and scene.hyvox.size_mode == "VOXEL_SIZE":
        return scene.hyvox.voxel_size  # the scene's size, as the headless script would take it
    resolution = args.resolution if args.resolution is not None else scene.hyvox.resolution
    first = frame_ranges.parse_frames(args.job_frames)[0]
    current = scene.frame_current
    scene.frame_set(first)
    try:
        (mesh,) = frame_export.export_meshes(
            [group], "VIEWPORT" if args.viewport else "RENDER", False, lambda text: None
        )
    finally:
        scene.frame_set(current)
    plan = backend.load_module().plan_grid(mesh.vertices, mesh.triangles, resolution=resolution)
    return plan["voxel_size"]


def run_frames(args, rest):
    operators = importlib.import_module(PACKAGE + ".blender.operators")
    group = _sources(args.objects)
    size = job_voxel_size(args, group)
    frames = frame_ranges.parse_frames(args.frames)
    fixed = ["--objects", ",".join(group.sources), "--voxel-size", repr(size), "--output", args.output]
    if args.viewport:
        fixed.append("--viewport")
    for done, frame in enumerate(frames):
        print(f"openjd_status: frame {frame} ({done + 1} of {len(frames)})", flush=True)
        start = time.perf_counter()
        _cli().main(rest + fixed + ["--frames", f"{frame}-{frame}"])
        (volume,) = operators.last_run_record["volumes"]
        ms = operators.last_run_record["timings_ms"]
        print(
            f"hyvox: frame {frame}: {volume['voxel_counts'][0]:,} voxels in {time.perf_counter() - start:.2f} s "
            f"(voxelize {ms['voxelize'] / 1000:.2f} s, write {ms['write'] / 1000:.2f} s) -> {volume['files'][0]}",
            flush=True,
        )
        print(f"openjd_progress: {100.0 * (done + 1) / len(frames):.1f}", flush=True)


def _frame_files(args, group):
    stem = naming.result_stem(group.name, group.key, len(group.sources))
    frames = frame_ranges.parse_frames(args.job_frames)
    return frames, [os.path.join(os.path.abspath(args.output), naming.volume_file_name(stem, f)) for f in frames]


def _check_volume_file(path, voxel_size):
    """The grid names of a readable .vdb with a density grid of this voxel size, or FarmError."""
    volume = bpy.data.volumes.new("hyvox_check")
    volume.filepath = path
    try:
        if not volume.grids.load():
            raise FarmError(f"{path} is not a readable OpenVDB file: {volume.grids.error_message}")
        names = {grid.name for grid in volume.grids}
        density = volume.grids.get("density")
        if density is None:
            raise FarmError(f"{path} has no density grid (grids: {', '.join(sorted(names)) or 'none'})")
        size = abs(density.matrix_object[0][0])
        if abs(size - voxel_size) > 1e-6 * voxel_size:
            raise FarmError(f"{path} has voxel size {size:.9g}, the job {voxel_size:.9g}: a file of another job?")
        return names
    finally:
        bpy.data.volumes.remove(volume)


def assemble(args):
    group = _sources(args.objects)
    size = job_voxel_size(args, group)
    frames, files = _frame_files(args, group)
    missing = [frame for frame, path in zip(frames, files) if not os.path.isfile(path)]
    if missing:
        raise FarmError(
            f"{len(missing)} of {len(frames)} frames have no file in {args.output} "
            f"(frames {', '.join(map(str, missing[:20]))}{' ...' if len(missing) > 20 else ''})"
        )
    grids = [_check_volume_file(path, size) for path in files]
    has_color = "color" in grids[0]
    if any(("color" in names) != has_color for names in grids):
        raise FarmError("some frames have a color grid and others not: the chunks ran with different options")
    save = os.path.abspath(
        args.save
        or os.path.join(
            args.output,
            os.path.splitext(os.path.basename(bpy.data.filepath) or "scene")[0] + naming.VOXELS_SUFFIX + ".blend",
        )
    )
    filepaths = bpy.context.preferences.filepaths
    versions, filepaths.save_version = filepaths.save_version, 0  # no .blend1 beside it
    try:
        # Saved first where it goes, so the volume's file paths are relative to it.
        bpy.ops.wm.save_as_mainfile(filepath=save)
        result = GroupResult(group, files=files, frames=frames, voxel_size=size, has_color=has_color)
        prefs = properties.preferences(bpy.context)
        importer.import_results(
            bpy.context,
            {group.key: result},
            prefs.alignment_fix if prefs is not None else "AUTO",
            parent_to_source=False,
        )
        bpy.ops.wm.save_as_mainfile(filepath=save)
    finally:
        filepaths.save_version = versions
    print(f"hyvox: assembled {len(frames)} frames of {group.name} ({frames[0]}-{frames[-1]}) -> {save}", flush=True)


def _remove_partial_files(folder):
    """This process's staging files (naming.staging_path), should a write have been cut."""
    suffix = f".{os.getpid()}.partial"
    try:
        names = os.listdir(folder)
    except OSError:
        return
    for name in names:
        if name.startswith(".") and name.endswith(suffix):
            with contextlib.suppress(OSError):
                os.remove(os.path.join(folder, name))


def run_command(argv) -> int:
    """Runs `run` or `assemble`; 0, or 1 with "hyvox: error: <reason>" on stderr (143 when
    cancelled)."""
    command, args = (argv[0], argv[1:]) if argv else ("", [])
    if command not in ("run", "assemble"):
        print(f"hyvox: error: unknown farm command {command!r} (run, assemble, serve)", file=sys.stderr)
        return 2
    output = None
    _cancelled.clear()
    try:
        with cancel_on_sigterm():
            known, rest = parse_arguments(command, args, backend.load_module()._core.FARM_TASK_ARGUMENTS)
            output = known.output
            if known.blend:
                bpy.ops.wm.open_mainfile(filepath=os.path.abspath(known.blend))
            if command == "run":
                run_frames(known, rest)
            else:
                assemble(known)
        return 0
    except Cancelled as exc:
        reason = str(exc)
        print(
            f"hyvox: error: {reason[len('hyvox: ') :] if reason.startswith('hyvox: ') else reason}",
            file=sys.stderr,
            flush=True,
        )
        return 143
    except (Exception, SystemExit) as exc:  # every failure: its reason and a non-zero exit
        if isinstance(exc, SystemExit) and exc.code in (0, None):
            return 0
        reason = str(exc)
        print(
            f"hyvox: error: {reason[len('hyvox: ') :] if reason.startswith('hyvox: ') else reason}",
            file=sys.stderr,
            flush=True,
        )
        return 143 if _cancelled else 1
    finally:
        if output:
            _remove_partial_files(os.path.abspath(output))
