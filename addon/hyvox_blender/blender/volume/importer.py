# SPDX-License-Identifier: GPL-3.0-or-later
"""Volume objects for a run's results: a Volume data-block reading the .vdb (or the
sequence), an object named "<source>_voxels" carrying the half-voxel correction (and in
Blender 4.2-4.5 the bounds EEVEE Next needs: eevee_bounds.py), a
Principled Volume material reading `density`, and its Color from the `color` grid when the
run made one (material.py; its density: core/volume_look.py).

What a re-run replaces: every earlier volume made from any of the objects it voxelizes (so
changing the grouping, or the selection, never leaves two volumes of one object). From the
earlier volume of exactly the same sources the new one keeps the material, collections
and the artist's location, rotation and scale (relative to the source when parented);
from an overlapping one only the material and collections. By default the new volume is
parented to its source (the active object of a group), so moving the source moves it; a
frame sequence is not parented, as its voxels already follow the animation."""

from typing import Callable, Dict, List, Optional

import bpy
from mathutils import Vector

from ...core import alignment, naming, volume_look
from ...core.pipeline import GroupResult
from . import blocks as blocks_object, eevee_bounds, material as volume_material
from ..files import history as file_history

from ..export.sources import RESULT_KEY as KEY  # custom property: which sources a result came from
from ..export.sources import RESULT_LEAD_KEY as LEAD_KEY


def _configure_volume(volume: bpy.types.Volume, result: GroupResult) -> None:
    volume.filepath = file_history.blend_relative(result.files[0])
    if result.frames:
        first = result.frames[0]
        volume.is_sequence = True
        volume.frame_duration = result.frames[-1] - first + 1
        volume.frame_start = first
        # Blender reads file number = scene frame - frame_start + 1 + frame_offset; the
        # files carry their scene frame number (farm chunks assemble), so offset by first-1.
        volume.frame_offset = first - 1
        volume.sequence_mode = "CLIP"
    display = volume.display
    display.interpolation_method = "CLOSEST"  # show voxels as the blocks they are
    display.density = 1.0
    display.wireframe_type = "BOXES"
    display.wireframe_detail = "FINE"
    volume.render.space = "OBJECT"


def _sources(obj: bpy.types.Object) -> set:
    return set(str(obj.get(KEY, "")).split("\n")) - {""}


def _replaced(sources: set) -> List[bpy.types.Object]:
    """The results (volumes, blocks) a run of these sources replaces: those made from any of them."""
    return [o for o in bpy.data.objects if KEY in o and _sources(o) & sources]


class _Kept:
    """What a new volume takes over from the one it replaces."""

    def __init__(self, old: bpy.types.Object):
        self.key = old[KEY]
        self.sources = _sources(old)
        self.kind = old.type
        self.material = old.data.materials[0] if old.data is not None and old.data.materials else None
        self.voxel_size = float(old.get("hyvox_voxel_size", 0.0))
        self.collections = list(old.users_collection)
        # The offset the add-on set (not the artist); volumes of earlier versions did not
        # record it: theirs was the half-voxel fix of their voxel size.
        if "hyvox_offset" in old:
            self.offset = Vector(old["hyvox_offset"])
        else:
            self.offset = Vector(
                alignment.object_offset(self.voxel_size, bpy.app.version) if old.type == "VOLUME" else (0, 0, 0)
            )
        self.location = Vector(old.location)
        self.rotation_mode = old.rotation_mode
        self.rotation = (tuple(old.rotation_euler), tuple(old.rotation_quaternion), tuple(old.rotation_axis_angle))
        self.scale = tuple(old.scale)

    def apply_transform(self, obj: bpy.types.Object, offset) -> None:
        """The artist's edits: the location less the offset the add-on had set (the
        half-voxel fix of the old voxel size), plus the new one; rotation and scale as they were."""
        obj.location = self.location - self.offset + Vector(offset)
        obj.rotation_mode = self.rotation_mode
        obj.rotation_euler, obj.rotation_quaternion, obj.rotation_axis_angle = self.rotation
        obj.scale = self.scale


def _remove(obj: bpy.types.Object) -> None:
    data = obj.data
    bpy.data.objects.remove(obj, do_unlink=True)
    if data is not None and data.users == 0:
        (bpy.data.meshes if isinstance(data, bpy.types.Mesh) else bpy.data.volumes).remove(data)


def _parent_to(obj: bpy.types.Object, source: Optional[bpy.types.Object]) -> None:
    """Parent keeping the world placement: the parent inverse is the source's matrix now."""
    if source is None:
        return
    obj.parent = source
    obj.matrix_parent_inverse = source.matrix_world.inverted()


def import_results(
    context,
    results: Dict[str, GroupResult],
    alignment_override: str = "AUTO",
    parent_to_source: bool = True,
    warn: Callable[[str], None] = print,
) -> List[bpy.types.Object]:
    """Create one Volume object per result, replacing earlier ones (see the module's
    docstring); returns them. warn(text): what the artist should know (the operator
    reports it), e.g. a volume left without its EEVEE bounds."""
    all_sources = {name for result in results.values() for name in result.group.sources}
    kept = []
    for old in _replaced(all_sources):
        kept.append(_Kept(old))
        _remove(old)

    created = []
    for result in results.values():
        group = result.group
        exact = next((k for k in kept if k.key == group.key), None)
        overlapping = [k for k in kept if k.sources & set(group.sources)]
        donor = exact or (overlapping[0] if overlapping else None)

        if result.blocks is not None:
            material = donor.material if donor is not None and donor.kind == "MESH" else None
            obj, offset = blocks_object.make_blocks_object(group.name, result, material)
        else:
            name = naming.object_name(group.name)
            volume = bpy.data.volumes.new(name)
            _configure_volume(volume, result)
            material = donor.material if donor is not None and donor.kind == "VOLUME" else None
            density = volume_look.result_density(result.stats, result.voxel_size, result.dims)
            volume.materials.append(
                volume_material.for_result(
                    material, name, result.has_color, density, donor.voxel_size if material is not None else 0.0
                )
            )
            obj = bpy.data.objects.new(name, volume)
            offset = alignment.object_offset(result.voxel_size, bpy.app.version, alignment_override)
            if alignment.eevee_clips_last_voxel_layer(bpy.app.version):
                try:
                    eevee_bounds.add_bounds_modifier(obj, result.voxel_size)
                except eevee_bounds.BoundsUnavailable as reason:
                    warn(eevee_bounds.unavailable_message(obj.name, reason))
        obj.location = offset
        obj["hyvox_offset"] = tuple(offset)
        if exact is not None:
            exact.apply_transform(obj, offset)
        obj[KEY] = group.key
        obj[LEAD_KEY] = group.lead  # a re-run from this result keeps its name (export.make_groups)
        if result.vox_files:
            obj[file_history.RESULT_VOX_PROPERTY] = file_history.blend_relative(result.vox_files[0])
        obj["hyvox_voxel_size"] = result.voxel_size
        obj["hyvox_method"] = result.method
        source = bpy.data.objects.get(group.lead)
        collections = list(donor.collections) if donor is not None else []
        if not collections and source is not None:
            collections = list(source.users_collection)
        for collection in collections or [context.scene.collection]:
            collection.objects.link(obj)
        if parent_to_source and not result.frames:
            _parent_to(obj, source)
        created.append(obj)
    file_history.remember_results(results.values())  # undo may bring them back: Clean keeps them
    return created
