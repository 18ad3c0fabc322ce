# SPDX-License-Identifier: GPL-3.0-or-later
"""The triangles Blender renders for an evaluated mesh (its loop triangles) as (M,3) uint32
vertex indices, read the cheapest way each Blender version allows, always the same
triangles in the same order (tests/blender/test_export_triangles.py checks them against
`loop_triangles`' vertices, quads non-planar and concave and n-gons included;
docs/why/addon-export.md says why quads are not split here).

`loop_triangles.foreach_get("vertices")` calls a getter per triangle, and computing the loop
triangles costs more again (docs/why/addon-export.md has the figures). Cheaper:
- a mesh of triangles only needs no triangulation: its face corners, three by three, are
  its loop triangles (Blender makes face f's triangle of corners s, s+1, s+2);
- Blender 3.6 onwards keeps the corners' vertices as the `.corner_vert` attribute, which
  foreach_get copies in one go, and `loop_triangles`' `loops` (the corners of each triangle)
  also copy in one go with a uint32 buffer: their vertices are one numpy gather away.
In Blender 3.4 the loops' `vertex_index` plus loop triangles' `loops` cost more than their
`vertices`, which quads and n-gons keep reading there.
Quads are not split here: which diagonal Blender takes depends on a float32 test (and, in
3.4, on whether face normals were cached), and the other diagonal of a non-planar quad is
another surface."""

import bpy
import numpy as np


def _corner_vert_attribute(mesh: bpy.types.Mesh):
    """Blender 3.6+'s `.corner_vert` (the vertex of each face corner), or None."""
    attributes = getattr(mesh, "attributes", None)
    attribute = attributes.get(".corner_vert") if attributes is not None else None
    return attribute if attribute is not None and attribute.data_type == "INT" else None


def _corner_vertices(mesh: bpy.types.Mesh, corner_vert) -> np.ndarray:
    """The vertex of each face corner, (L,) uint32."""
    if corner_vert is not None:
        corners = np.empty(len(mesh.loops), np.int32)  # an IntAttribute's own type: one copy
        corner_vert.data.foreach_get("value", corners)
        return corners.view(np.uint32)
    corners = np.empty(len(mesh.loops), np.uint32)  # MeshLoop.vertex_index is unsigned
    mesh.loops.foreach_get("vertex_index", corners)
    return corners


def _triangle_faces_in_order(mesh: bpy.types.Mesh) -> bool:
    """True when every face is a triangle and face f starts at corner 3f (ascending face
    offsets by construction from 4.0 on; before, each face stores its start: look)."""
    if len(mesh.loops) != 3 * len(mesh.polygons):  # each face has 3 corners or more
        return False
    starts = np.empty(len(mesh.polygons), np.uint32)  # loop_start is unsigned: a raw copy
    mesh.polygons.foreach_get("loop_start", starts)
    return bool(np.array_equal(starts, np.arange(0, 3 * len(starts), 3, dtype=np.uint32)))


def ensure_loop_triangles(mesh: bpy.types.Mesh) -> None:
    """Blender 3.x computes loop triangles on request; later versions when first read."""
    if hasattr(mesh, "calc_loop_triangles"):
        mesh.calc_loop_triangles()


def loop_triangles(mesh: bpy.types.Mesh) -> np.ndarray:
    """The mesh's loop triangles' vertices, (M,3) uint32, in Blender's order."""
    if len(mesh.polygons) == 0:
        return np.zeros((0, 3), np.uint32)
    corner_vert = _corner_vert_attribute(mesh)
    if _triangle_faces_in_order(mesh):
        return _corner_vertices(mesh, corner_vert).reshape(-1, 3)
    ensure_loop_triangles(mesh)
    count = len(mesh.loop_triangles)
    if corner_vert is not None:
        corners_of_triangles = np.empty(count * 3, np.uint32)
        mesh.loop_triangles.foreach_get("loops", corners_of_triangles)
        return _corner_vertices(mesh, corner_vert)[corners_of_triangles].reshape(-1, 3)
    triangles = np.empty(count * 3, np.uint32)
    mesh.loop_triangles.foreach_get("vertices", triangles)
    return triangles.reshape(-1, 3)
