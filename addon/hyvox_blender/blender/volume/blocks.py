# SPDX-License-Identifier: GPL-3.0-or-later
"""The Blocks output as a mesh object: the faces core/blocks.py built (quads, welded,
normals outwards, flat shaded), each face's colour in the colour attribute "Col" (the same on
the face's corners) that the material reads, so the blocks render with their voxels' colours.

Flat shading is set on every face: a new face is flat in Blender 3.x but smooth from 4.1 on
(no `sharp_face` attribute means smooth), and smooth blocks show dark triangles at every
step. A kept material (a re-run) gets or loses the add-on's colour node with the grids, as
the volume's does (material.py): a missing "Col" attribute would read black."""

from typing import Optional, Tuple

import bpy
import numpy as np

from ...core import naming
from ...core.pipeline import GroupResult
from . import material as volume_material

BLOCKS_SUFFIX = "_blocks"
COLOR_ATTRIBUTE = "Col"
COLOR_NODE = "hyvox Color"
DEFAULT_BASE_COLOR = (0.8, 0.8, 0.8, 1.0)  # a new Principled BSDF's


def sync_material(material, colored: bool) -> None:
    """The add-on's colour node linked to Base Color when the blocks have colours (and the
    Base Color is still the default grey), taken out when they have none; a Base Color the
    artist set or linked to something else stays."""
    shader = volume_material.output_shader(material, "Surface", "BSDF_PRINCIPLED")
    if shader is None:
        return
    tree = material.node_tree
    socket = shader.inputs["Base Color"]
    source = socket.links[0].from_node if socket.links else None
    ours = source is not None and (
        source.name == COLOR_NODE or (source.type == "ATTRIBUTE" and source.attribute_name == COLOR_ATTRIBUTE)
    )  # or an earlier version's
    at_default = source is None and all(abs(a - b) < 1e-6 for a, b in zip(socket.default_value, DEFAULT_BASE_COLOR))
    if colored and at_default:
        attribute = tree.nodes.get(COLOR_NODE) or tree.nodes.new("ShaderNodeAttribute")
        attribute.name, attribute.label = COLOR_NODE, "Block colors"
        attribute.attribute_name = COLOR_ATTRIBUTE
        attribute.location = (shader.location[0] - 300, shader.location[1] + 200)
        tree.links.new(attribute.outputs["Color"], socket)
    elif not colored and ours:
        tree.links.remove(socket.links[0])
        if not any(output.links for output in source.outputs):
            tree.nodes.remove(source)


def _material(name: str, colored: bool) -> bpy.types.Material:
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    sync_material(material, colored)
    return material


def make_blocks_object(
    group_name: str, result: GroupResult, material: Optional[bpy.types.Material]
) -> Tuple[bpy.types.Object, tuple]:
    """(a new, unlinked mesh object of the result's blocks, the location the add-on gives it:
    none, the vertices are in world space)."""
    blocks = result.blocks
    name = naming.object_name(group_name).replace(naming.VOXELS_SUFFIX, BLOCKS_SUFFIX)
    mesh = bpy.data.meshes.new(name)
    fill_mesh(mesh, blocks)
    colored = blocks.face_colors is not None
    if material is not None:
        sync_material(material, colored)
    mesh.materials.append(material or _material(name, colored))
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
    mesh.polygons.foreach_set("use_smooth", np.zeros(faces, bool))
    mesh.update()
    mesh.validate(clean_customdata=False)
