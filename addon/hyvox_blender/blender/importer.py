# SPDX-License-Identifier: GPL-3.0-or-later
"""Volume objects for a run's results: a Volume data-block reading the .vdb (or the
sequence), an object named "<source>_voxels" carrying the half-voxel correction, a
Principled Volume material reading `density`. Re-running replaces the previous result of
the same source and keeps the material the artist may have tweaked."""
from typing import Dict, List

import bpy

from ..core import alignment, naming
from ..core.pipeline import GroupResult

KEY = "hyvox_key"  # custom property: which sources a volume object came from


def find_previous(key: str) -> List[bpy.types.Object]:
    return [o for o in bpy.data.objects if o.type == "VOLUME" and o.get(KEY) == key]


def _file_path(path: str) -> str:
    """Relative to the .blend when it is saved (the project folder can move)."""
    if bpy.data.filepath:
        try:
            return bpy.path.relpath(path)
        except ValueError:  # another drive on Windows
            pass
    return path


def _make_material(name: str, voxel_size: float) -> bpy.types.Material:
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    output = nodes.new("ShaderNodeOutputMaterial")
    output.location = (300, 0)
    shader = nodes.new("ShaderNodeVolumePrincipled")
    shader.location = (0, 0)
    # density is 1 in occupied voxels; scale so light crossing one voxel is about 60%
    # absorbed whatever the scene's units are.
    shader.inputs["Density"].default_value = 1.0 / max(voxel_size, 1e-9)
    shader.inputs["Color"].default_value = (0.8, 0.8, 0.8, 1.0)
    if "Density Attribute" in shader.inputs:  # a socket in Blender 4.x
        shader.inputs["Density Attribute"].default_value = "density"
    elif hasattr(shader, "density_attribute"):
        shader.density_attribute = "density"
    material.node_tree.links.new(shader.outputs["Volume"], output.inputs["Volume"])
    return material


def _configure_volume(volume: bpy.types.Volume, result: GroupResult) -> None:
    volume.filepath = _file_path(result.files[0])
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


def import_results(context, results: Dict[str, GroupResult], alignment_override: str = "AUTO"
                   ) -> List[bpy.types.Object]:
    """Create (or replace) one Volume object per result; returns them."""
    created = []
    for result in results.values():
        group = result.group
        previous = find_previous(group.key)
        material = None
        collections = None
        for old in previous:
            if material is None and old.data is not None and old.data.materials:
                material = old.data.materials[0]
            if collections is None:
                collections = list(old.users_collection)
            old_data = old.data
            bpy.data.objects.remove(old, do_unlink=True)
            if old_data is not None and old_data.users == 0:
                bpy.data.volumes.remove(old_data)

        name = naming.object_name(group.name)
        volume = bpy.data.volumes.new(name)
        _configure_volume(volume, result)
        if material is None:
            material = _make_material(name, result.voxel_size)
        volume.materials.append(material)

        obj = bpy.data.objects.new(name, volume)
        obj.location = alignment.object_offset(result.voxel_size, bpy.app.version, alignment_override)
        obj[KEY] = group.key
        obj["hyvox_voxel_size"] = result.voxel_size
        obj["hyvox_method"] = result.method
        if not collections:
            source = bpy.data.objects.get(group.sources[0])
            collections = list(source.users_collection) if source is not None else []
        if not collections:
            collections = [context.scene.collection]
        for collection in collections:
            collection.objects.link(obj)
        created.append(obj)
    return created

