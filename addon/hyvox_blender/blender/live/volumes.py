# SPDX-License-Identifier: GPL-3.0-or-later
"""What makes a hyvox result live, in Blender data (custom properties, so that saving,
undo and redo keep them with the object):

- `Object.hyvox_live` (the switch; registered by live.py) and `hyvox_live_id`, the
  identity the scheduler knows the volume by (a duplicated object gets a new one);
- `hyvox_live_settings`: the settings the volume was made with (gather.used_values, as
  JSON): a live volume keeps its resolution, method, mode and colour whatever the scene's
  settings say next, and its voxel size from the first evaluation (`hyvox_voxel_size`);
- `hyvox_live_sources`: pointers to the source objects, so a renamed source is followed;
- `hyvox_live_key` and `hyvox_live_files`: the key of the voxels shown and their files.

And the two things done to a live volume on the main thread: its export (the sources'
evaluated triangles and colours) and its swap (the new file shown, or the Blocks mesh
refilled in place)."""

import json
import os
import time
import uuid
from typing import Dict, List, Optional

import bpy

from ...core import live_key, naming
from ...core.errors import HyvoxError
from ...core.pipeline import Group, GroupMesh
from . import dependencies as live_dependencies
from ..export import sources as export
from ..files import history as file_history
from ..volume import blocks as blocks_object
from ..export.sources import RESULT_KEY
from ..gather import settings_from_used, used_values

LIVE_ID = "hyvox_live_id"
LIVE_SETTINGS = "hyvox_live_settings"
LIVE_SOURCES = "hyvox_live_sources"
LIVE_GROUP = "hyvox_live_group"
LIVE_KEY = "hyvox_live_key"
LIVE_FILES = "hyvox_live_files"


class SourcesUnavailable(HyvoxError):
    """A source is gone or cannot be evaluated: Live waits, showing the last voxels."""


def is_result(obj) -> bool:
    return obj is not None and RESULT_KEY in obj and obj.type in {"VOLUME", "MESH"}


def is_live(obj) -> bool:
    return is_result(obj) and bool(getattr(obj, "hyvox_live", False))


def live_objects(scene) -> Dict[str, bpy.types.Object]:
    """The scene's live volumes by id; an id met twice (a duplicated object) is renewed on
    the second object, which then starts with a run of its own."""
    found = {}
    for obj in scene.objects:
        if not is_live(obj):
            continue
        ident = obj.get(LIVE_ID)
        if not ident or ident in found:
            ident = obj[LIVE_ID] = uuid.uuid4().hex
            if LIVE_KEY in obj:
                del obj[LIVE_KEY]
        found[ident] = obj
    return found


# -- what a live volume was made from -------------------------------------------------
def remember(obj, used: dict, group: Group, files: List[str] = ()) -> None:
    """Record on a new result what Live needs (the operator calls this for live=True)."""
    obj[LIVE_SETTINGS] = json.dumps(dict(used, use_frame_range=False, live=True), sort_keys=True)
    # The lead by its place among the sources: a rename keeps it.
    obj[LIVE_GROUP] = json.dumps({"name": group.name, "lead": group.sources.index(group.lead)})
    obj[LIVE_SOURCES] = {
        str(i): bpy.data.objects.get(name)
        for i, name in enumerate(group.sources)
        if bpy.data.objects.get(name) is not None
    }
    obj[LIVE_FILES] = list(files)
    obj[LIVE_ID] = obj.get(LIVE_ID) or uuid.uuid4().hex


def prepare_for_live(obj, context) -> None:
    """A result whose switch is turned on: what Live needs is recorded (a result made
    without Live takes the scene's settings), and it is unparented: its voxels follow the
    sources by themselves, so the parent would move them twice."""
    if LIVE_SETTINGS not in obj:
        names = [n for n in str(obj[RESULT_KEY]).split("\n") if n]
        name = obj.name
        for suffix in (naming.VOXELS_SUFFIX, blocks_object.BLOCKS_SUFFIX):
            name = name[: -len(suffix)] if name.endswith(suffix) else name
        remember(obj, used_values(context), Group(name, names))
    obj[LIVE_ID] = obj.get(LIVE_ID) or uuid.uuid4().hex
    if obj.parent is not None:
        obj.parent = None
        obj.matrix_parent_inverse.identity()
    live_dependencies.follow(obj, sources(obj))


def stored_used(obj, context) -> dict:
    """The settings a live volume keeps; a result made before Live takes the scene's."""
    used = used_values(context)
    if LIVE_SETTINGS in obj:
        used.update(json.loads(obj[LIVE_SETTINGS]))
    used.update(use_frame_range=False, live=True)
    return used


def sources(obj) -> List[Optional[bpy.types.Object]]:
    """The source objects (None for one that was deleted), renames followed."""
    pointers = obj.get(LIVE_SOURCES)
    if pointers is not None and len(pointers):
        return [pointers[k] for k in sorted(pointers.keys(), key=int)]
    return [bpy.data.objects.get(n) for n in str(obj[RESULT_KEY]).split("\n") if n]


def group_of(obj) -> Group:
    """The volume's group with the sources' current names (a rename updates the result's
    key too, so that Voxelize with the volume selected finds its sources)."""
    objects = sources(obj)
    missing = [i for i, o in enumerate(objects) if o is None]
    if missing or not objects:
        raise SourcesUnavailable("a source of this volume was deleted")
    names = [o.name for o in objects]
    key = naming.group_key(names)
    if obj[RESULT_KEY] != key:
        obj[RESULT_KEY] = key
    info = json.loads(obj[LIVE_GROUP]) if LIVE_GROUP in obj else {}
    lead = info.get("lead", 0)
    return Group(info.get("name") or names[0], names, names[lead] if 0 <= lead < len(names) else names[0])


def watched_names(obj) -> set:
    """The objects whose updates concern this volume: its sources and what they instance."""
    names = set()
    for source in sources(obj):
        if source is None:
            continue
        names.add(source.name)
        collection = source.instance_collection if source.instance_type == "COLLECTION" else None
        if collection is not None:
            names.update(o.name for o in collection.all_objects)
    return names


def settings_of(context, obj):
    """(settings, folder, fingerprint) of a live run: the stored settings with the voxel size
    the volume keeps and a lattice fixed in world space."""
    used = stored_used(obj, context)
    size = float(obj.get("hyvox_voxel_size", 0.0))
    if size > 0.0:
        used.update(size_mode="VOXEL_SIZE", voxel_size=size)
    settings, folder, _ = settings_from_used(context, used)
    settings.fixed_lattice = True
    return settings, folder, fingerprint(settings)


def fingerprint(settings) -> str:
    return live_key.options_fingerprint(
        dict(
            settings.options,
            method=settings.method,
            color=settings.color,
            sdf=settings.sdf,
            blocks=settings.blocks,
            export_vox=settings.export_vox,
        )
    )


# -- main thread: export and swap -------------------------------------------------------
class ImagePixels:
    """The textures' pixels kept across Live's exports (reading a 1024x1024 image costs more
    than exporting 100k triangles). An image's pixels are read again when Blender reports it
    changed (forget(), from a depsgraph update of the Image) or when what they were read
    with changes (its file, size, colour space, float or not, unsaved edits)."""

    pixels: dict = {}  # image name -> (key, pixels), colour_export.ImageCache
    signatures: dict = {}  # image name -> what the pixels were read with

    @staticmethod
    def _signature(image):
        return (
            image.filepath_raw,
            tuple(image.size),
            image.is_float,
            image.colorspace_settings.name,
            image.source,
            image.is_dirty,
            image.channels,
        )

    @classmethod
    def current(cls) -> dict:
        for name in list(cls.pixels):
            image = bpy.data.images.get(name)
            if image is None or cls.signatures.get(name) != cls._signature(image):
                cls.forget(name)
        return cls.pixels

    @classmethod
    def record(cls) -> None:
        for name in cls.pixels:
            image = bpy.data.images.get(name)
            if image is not None and name not in cls.signatures:
                cls.signatures[name] = cls._signature(image)

    @classmethod
    def forget(cls, name=None) -> None:
        if name is None:
            cls.pixels.clear()
            cls.signatures.clear()
        else:
            cls.pixels.pop(name, None)
            cls.signatures.pop(name, None)


def export_meshes(obj, group: Group, depsgraph, colour: bool, warn) -> List[GroupMesh]:
    """The sources as the depsgraph evaluates them (viewport while editing, render
    while rendering)."""
    for source in sources(obj):
        evaluated = source.evaluated_get(depsgraph)
        if not evaluated.is_evaluated:
            raise SourcesUnavailable(f"{source.name} is not evaluated here (disabled in viewports?)")
    meshes = export.export_groups(
        [group], depsgraph, warn=warn, colour=colour, images=ImagePixels.current() if colour else None
    )
    ImagePixels.record()
    return meshes


def shown_files(obj) -> List[str]:
    files = [bpy.path.abspath(p) for p in obj.get(LIVE_FILES, [])]
    if obj.type == "VOLUME" and obj.data is not None and obj.data.filepath:
        files.append(bpy.path.abspath(obj.data.filepath))
    return files


def swap(obj, output) -> float:
    """Show a run's voxels on the volume (main thread); returns the milliseconds it took.
    Nothing is done when they are shown already (an undo step back, a static frame)."""
    start = time.perf_counter()
    result = output.result
    if obj.get(LIVE_KEY) == output.key and all(os.path.exists(p) for p in shown_files(obj)):
        return 0.0
    if obj.type == "VOLUME":
        volume = obj.data
        if volume.is_sequence:
            volume.is_sequence = False
        volume.filepath = file_history.blend_relative(result.files[0])
    elif result.blocks is not None:
        blocks_object.fill_mesh(obj.data, result.blocks)
        obj["hyvox_faces"] = len(result.blocks.faces)
    obj[LIVE_KEY] = output.key
    obj[LIVE_FILES] = [file_history.blend_relative(p) for p in output.files]
    return (time.perf_counter() - start) * 1000.0
