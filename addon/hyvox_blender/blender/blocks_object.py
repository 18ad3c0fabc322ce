# SPDX-License-Identifier: GPL-3.0-or-later
"""The Blocks output as a mesh object: the faces core/blocks.py built (quads, welded,
normals outwards), each face's colour in the colour attribute "Col" (the same on the
face's corners) that the material reads, so the blocks render with their voxels' colours."""
from typing import Optional, Tuple

import bpy
import numpy as np

from ..core import naming
from ..core.pipeline import GroupResult

BLOCKS_SUFFIX = "_blocks"
COLOR_ATTRIBUTE = "Col"


def _material(name: str, colored: bool) -> bpy.types.Material:
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    shader = nodes.get("Principled BSDF")
    if colored and shader is not None:
        attribute = nodes.new("ShaderNodeAttribute")
        attribute.attribute_name = COLOR_ATTRIBUTE
        attribute.location = (-300, 200)
        material.node_tree.links.new(attribute.outputs["Color"], shader.inputs["Base Color"])
    return material


def make_blocks_object(group_name: str, result: GroupResult,
                       material: Optional[bpy.types.Material]) -> Tuple[bpy.types.Object, tuple]:
    """(a new, unlinked mesh object of the result's blocks, the location the add-on gives it:
    none, the vertices are in world space)."""
    blocks = result.blocks
    name = naming.object_name(group_name).replace(naming.VOXELS_SUFFIX, BLOCKS_SUFFIX)
    mesh = bpy.data.meshes.new(name)
    fill_mesh(mesh, blocks)
    mesh.materials.append(material or _material(name, blocks.face_colors is not None))
    obj = bpy.data.objects.new(name, mesh)
    obj["hyvox_faces"] = len(blocks.faces)
    return obj, (0.0, 0.0, 0.0)


def fill_mesh(mesh: bpy.types.Mesh, blocks) -> None:
    """The mesh's geometry replaced by the blocks' faces and colours (a new mesh, or Live's
    update of the one shown: its materials and the object stay)."""
    mesh.clear_geometry()
    faces = len(blocks.faces)
    mesh.vertices.add(len(blocks.vertices))
    mesh.vertices.foreach_set("co", blocks.vertices.ravel())
    mesh.loops.add(faces * 4)
    mesh.loops.foreach_set("vertex_index", blocks.faces.ravel())
    mesh.polygons.add(faces)
    mesh.polygons.foreach_set("loop_start", np.arange(0, faces * 4, 4, dtype=np.int32))
    mesh.polygons.foreach_set("loop_total", np.full(faces, 4, np.int32))
    if COLOR_ATTRIBUTE in mesh.color_attributes:
        mesh.color_attributes.remove(mesh.color_attributes[COLOR_ATTRIBUTE])
    if blocks.face_colors is not None:
        # Per face, stored on the face's four corners: Blender 3.4's colour attributes (the
        # ones the viewport shows and both renderers read) live on points or corners.
        attribute = mesh.color_attributes.new(COLOR_ATTRIBUTE, "FLOAT_COLOR", "CORNER")
        rgba = np.ones((faces, 4, 4), np.float32)
        rgba[:, :, :3] = blocks.face_colors[:, None, :]
        attribute.data.foreach_set("color", rgba.ravel())
        mesh.color_attributes.active_color = attribute
    mesh.update()
    mesh.validate(clean_customdata=False)
