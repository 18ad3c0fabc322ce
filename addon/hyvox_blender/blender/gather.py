# SPDX-License-Identifier: GPL-3.0-or-later
"""Gather one VoxelizeSettings per run from the scene's settings, the operator's keyword
arguments (those a script set win) and the add-on preferences."""

import os

import bpy

from ..core import naming
from ..core.settings import VoxelizeSettings
from .ui.properties import PREFERENCE_OPTIONS, SCENE_OPTIONS, preferences


def _op_set(op, name) -> bool:
    return op is not None and op.properties.is_property_set(name)


def used_values(context, op=None) -> dict:
    """Every operator property's value for this run: the operator's where a script (or the
    redo panel) set it, else the scene's."""
    scene_settings = context.scene.hyvox
    names = [p.identifier for p in scene_settings.bl_rna.properties if p.identifier not in {"rna_type", "name"}]
    used = {name: getattr(op if _op_set(op, name) else scene_settings, name) for name in names}
    # A script that gives one of the sizes means that one.
    if not _op_set(op, "size_mode"):
        if _op_set(op, "voxel_size"):
            used["size_mode"] = "VOXEL_SIZE"
        elif _op_set(op, "resolution"):
            used["size_mode"] = "RESOLUTION"
    if not _op_set(op, "use_frame_range") and (_op_set(op, "frame_start") or _op_set(op, "frame_end")):
        used["use_frame_range"] = True
    # A frame range nobody set is the scene's.
    for name, scene_value in (("frame_start", context.scene.frame_start), ("frame_end", context.scene.frame_end)):
        if not _op_set(op, name) and not scene_settings.is_property_set(name):
            used[name] = scene_value
    return used


def gather(context, op=None):
    """(settings, output folder, half-voxel override, the values used) for this run."""
    used = used_values(context, op)
    if used["live"]:
        # Live volumes are evaluated as Live evaluates while editing (the viewport's
        # depsgraph), and not parented: their voxels are already where the sources are.
        used = dict(used, evaluation="VIEWPORT", parent_to_source=False)
    return settings_from_used(context, used, live=used["live"]) + (used,)


def settings_from_used(context, used: dict, live: bool = False):
    """(settings, output folder, half-voxel override) from the values of used_values()
    (a Live volume keeps those it was made with); live: the run makes live volumes."""
    options = {name: used[name] for name in SCENE_OPTIONS}
    # Size (the panel's switch) says which of the two the artist set; the other, still in the
    # Scene settings, is not passed on. How the grid follows from it is the module's to say.
    options.pop("resolution" if used["size_mode"] == "VOXEL_SIZE" else "voxel_size")
    frames = list(range(used["frame_start"], used["frame_end"] + 1)) if used["use_frame_range"] else None

    prefs = preferences(context)
    if prefs is not None:
        options["gl_device"] = prefs.gl_device_string
        options.update({name: getattr(prefs, name) for name in PREFERENCE_OPTIONS})
    settings = VoxelizeSettings(
        method=used["method"],
        separate=used["separate"],
        frames=frames,
        blocks=used["output"] == "BLOCKS",
        export_vox=used["export_vox"],
        color=used["color"],
        sdf=used["signed_distance"],
        live=live,
        **options,
    )
    folder = used["output_dir"]
    folder = bpy.path.abspath(folder) if folder else naming.default_output_dir(bpy.data.filepath)
    override = prefs.alignment_fix if prefs is not None else "AUTO"
    return settings, os.path.normpath(folder), override
