# SPDX-License-Identifier: GPL-3.0-or-later
"""Gather one VoxelizeSettings per run from the scene's settings, the operator's keyword
arguments (those a script set win) and the add-on preferences."""
import os

import bpy

from ..core import naming
from ..core.settings import VoxelizeSettings
from .properties import preferences


def _op_set(op, name) -> bool:
    return op is not None and op.properties.is_property_set(name)


def gather(context, op=None):
    """(settings, output folder, half-voxel override) for this run."""
    scene_settings = context.scene.hyvox

    def pick(name):
        return getattr(op if _op_set(op, name) else scene_settings, name)

    if _op_set(op, "voxel_size") and op.voxel_size > 0:
        voxel_size = op.voxel_size
    elif _op_set(op, "resolution"):
        voxel_size = 0.0
    elif scene_settings.size_mode == "VOXEL_SIZE":
        voxel_size = scene_settings.voxel_size
    else:
        voxel_size = 0.0

    if _op_set(op, "hybrid_cutoff"):
        cutoff = op.hybrid_cutoff  # negative: auto
    else:
        cutoff = -1.0 if scene_settings.hybrid_cutoff_auto else scene_settings.hybrid_cutoff

    use_range = pick("use_frame_range")
    if not _op_set(op, "use_frame_range") and (_op_set(op, "frame_start") or _op_set(op, "frame_end")):
        use_range = True
    frames = None
    if use_range:
        start, end = pick("frame_start"), pick("frame_end")
        frames = list(range(start, end + 1))

    prefs = preferences(context)
    settings = VoxelizeSettings(
        resolution=pick("resolution"),
        voxel_size=voxel_size,
        method=pick("method"),
        mode=pick("mode"),
        tessellation_gamma=pick("tessellation_gamma"),
        hybrid_cutoff=cutoff,
        padding=pick("padding"),
        separate=pick("separate"),
        frames=frames,
        gl_device=prefs.gl_device_string if prefs is not None else "",
        memory_budget_mb=prefs.memory_budget_mb if prefs is not None else 4096,
    )
    folder = pick("output_dir")
    folder = bpy.path.abspath(folder) if folder else naming.default_output_dir(bpy.data.filepath)
    override = prefs.alignment_fix if prefs is not None else "AUTO"
    return settings, os.path.normpath(folder), override
