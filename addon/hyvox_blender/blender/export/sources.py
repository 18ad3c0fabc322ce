# SPDX-License-Identifier: GPL-3.0-or-later
"""Evaluated meshes (modifiers, shape keys, constraints applied, instances included) in
world space as numpy arrays. foreach_get with buffers of the exact RNA types (float32 co, uint32 indices)
takes Blender's raw-copy path; other dtypes fall back to per-element RNA access, several
times slower (docs/why/addon-export.md). The triangles: triangles.py."""

from typing import Dict, List, Optional, Tuple

import bpy
import numpy as np

from ...core import mesh_checks, naming
from ...core.errors import HyvoxError, SelectionError
from ...core.colour import combine as combine_colours
from ...core.pipeline import Group, GroupMesh
from . import colour as colour_export, triangles as mesh_triangles

# Object types whose evaluated geometry is (or converts to) a mesh.
GEOMETRY_TYPES = {"MESH", "CURVE", "SURFACE", "FONT", "META"}
# Types whose Geometry Nodes may make a mesh or instances (faces or not: the export tells).
GENERATED_TYPES = {"CURVES", "POINTCLOUD"}


def _mesh_arrays(evaluated: bpy.types.Object, matrix: np.ndarray, images=None):
    """(vertices (N,3) float32 transformed by matrix, triangles (M,3) uint32, its colour or
    None) of an evaluated object (or instance); the colour only when images (the run's
    colour_export.ImageCache) is given."""
    colour = None
    # A mesh object's evaluated data already is the evaluated mesh: no copy needed. In Edit
    # Mode (Live follows edits there) it wraps the edit mesh and has no faces of its own.
    owned = evaluated.type != "MESH" or getattr(evaluated.data, "is_editmode", False)
    mesh = evaluated.to_mesh() if owned else evaluated.data
    try:
        if mesh is None:
            return np.zeros((0, 3), np.float32), np.zeros((0, 3), np.uint32), None
        vertices = np.empty(len(mesh.vertices) * 3, dtype=np.float32)
        mesh.vertices.foreach_get("co", vertices)
        triangles = mesh_triangles.loop_triangles(mesh)
        if images is not None and len(triangles):
            mesh_triangles.ensure_loop_triangles(mesh)  # colour_export reads them (same order)
            colour = colour_export.mesh_colour(evaluated, mesh, images)
    finally:
        if owned:
            evaluated.to_mesh_clear()
    vertices = vertices.reshape(-1, 3)
    if not np.array_equal(matrix, np.eye(4, dtype=np.float32)):
        vertices = vertices @ matrix[:3, :3].T
        vertices += matrix[:3, 3]
    # uint32 is what the module works in: passed through without a copy.
    return vertices, triangles, colour


def object_triangles(obj: bpy.types.Object, depsgraph) -> Tuple[np.ndarray, np.ndarray]:
    """(vertices (N,3) float32 world space, triangles (M,3) uint32) of obj as evaluated,
    without its instances."""
    evaluated = obj.evaluated_get(depsgraph)
    return _mesh_arrays(evaluated, np.array(evaluated.matrix_world, dtype=np.float32))[:2]


def evaluated_parts(names, depsgraph, images=None) -> Dict[str, List[tuple]]:
    """For each object name: the world-space (vertices, triangles, colour) of everything the depsgraph
    evaluates for it: its own geometry and every instance it makes (collection instances,
    instancing by vertices or faces, Geometry Nodes instances, nested ones), each with its
    own world matrix. A name the depsgraph does not show (hidden there) is left out. colour:
    see _mesh_arrays."""
    wanted = set(names)
    parts: Dict[str, List[tuple]] = {}
    for instance in depsgraph.object_instances:
        # An instance belongs to the object that made it (the top of a nested chain).
        owner = instance.parent if instance.is_instance else instance.object
        name = owner.original.name
        if name not in wanted:
            continue
        found = parts.setdefault(name, [])
        evaluated = instance.object  # valid only during this step of the iteration
        # Curves, text, surfaces and metaballs come twice: as themselves and as the mesh
        # they evaluate to (an instance of type MESH). Only meshes count, so each once.
        if evaluated.type != "MESH":
            continue
        part = _mesh_arrays(evaluated, np.array(instance.matrix_world, dtype=np.float32), images)
        if len(part[1]):
            found.append(part)
    return parts


def voxelizable(obj: bpy.types.Object) -> bool:
    """Geometry, or an object that makes instances (an empty instancing a collection)."""
    instancing = obj.instance_type == "COLLECTION" and obj.instance_collection is not None
    return obj.type in GEOMETRY_TYPES | GENERATED_TYPES or instancing


RESULT_KEY = "hyvox_key"  # importer.KEY: a result names its sources
RESULT_LEAD_KEY = "hyvox_lead"  # ... and the one it is named after and parented to


def sources_of_results(objects) -> List[bpy.types.Object]:
    """The objects with every selected hyvox result replaced by the objects it was made
    from, so that Voxelize with the result selected (as a run leaves it) runs again."""
    out = []
    for obj in objects:
        if RESULT_KEY in obj:
            named = [bpy.data.objects.get(n) for n in str(obj[RESULT_KEY]).split("\n")]
            out.extend(o for o in named if o is not None)
        else:
            out.append(obj)
    return list(dict.fromkeys(out))  # first occurrence kept, order kept


def pick_sources(objects, warn=None) -> List[bpy.types.Object]:
    """The objects to voxelize (a selected result stands for its sources); non-geometry
    objects are skipped with a warning, and an empty result is an error."""
    objects = sources_of_results(objects)
    if not objects:
        raise SelectionError("Select at least one mesh object to voxelize")
    sources = [o for o in objects if voxelizable(o)]
    skipped = [o.name for o in objects if not voxelizable(o)]
    if not sources:
        raise SelectionError(
            "Nothing to voxelize: " + ", ".join(f"{o.name} ({o.type.lower()}) has no geometry" for o in objects[:3])
        )
    if skipped and warn is not None:
        warn("Skipped objects without geometry: " + ", ".join(skipped))
    return sources


def make_groups(sources, separate: bool, active: Optional[bpy.types.Object]) -> List[Group]:
    names = [o.name for o in sources]
    if separate or len(names) == 1:
        return [Group(name, [name]) for name in names]
    active_name = active.name if active is not None else None
    if active is not None and RESULT_KEY in active:  # re-run from the result: the same name
        active_name = str(active.get(RESULT_LEAD_KEY, ""))
    lead = active_name if active_name in names else sorted(names)[0]
    return [Group(naming.group_name(names, active_name), names, lead)]


def check_parts(parts: Dict[str, List[tuple]], warn=None) -> None:
    """Refuse a vertex that is not a finite coordinate, naming its object and its index in
    that object's mesh; warn when a few far vertices make an object's grid mostly empty
    (core/mesh_checks.py)."""
    for name, found in parts.items():
        for vertices, _triangles, _colour in found:
            index = mesh_checks.first_bad_vertex(vertices)
            if index is not None:
                raise HyvoxError(mesh_checks.bad_vertex_message(name, index, vertices[index]))
        if warn is not None and found:
            warning = mesh_checks.object_far_vertices_warning(name, [(v, t) for v, t, _ in found])
            if warning:
                warn(warning)


def export_groups(
    groups: List[Group],
    depsgraph,
    warn=None,
    fallback_depsgraph=None,
    colour: bool = False,
    images: Optional[dict] = None,
) -> List[GroupMesh]:
    """One GroupMesh per group; objects without faces are skipped with a warning, and a
    group left without triangles is an error (the scene stays unchanged). An object the
    depsgraph leaves out (hidden in renders) is taken from fallback_depsgraph (the
    viewport's) with a warning, or without one when there is no fallback. colour: also
    export what the objects' materials show (colour.py), combined per group by
    core/colour.combine. images: the textures' pixels already read (colour_export.ImageCache;
    Live keeps one across its exports), else read afresh."""
    names = [name for group in groups for name in group.sources if name in bpy.data.objects]
    images = (images if images is not None else {}) if colour else None
    parts = evaluated_parts(names, depsgraph, images)
    hidden = [name for name in names if name not in parts]
    if hidden and fallback_depsgraph is not None and warn is not None:
        warn("Hidden in renders, voxelized as the viewport shows them: " + ", ".join(hidden))
    for name in hidden:
        obj = bpy.data.objects[name]
        evaluated = obj.evaluated_get(fallback_depsgraph or depsgraph)
        part = _mesh_arrays(evaluated, np.array(evaluated.matrix_world, dtype=np.float32), images)
        parts[name] = [part] if len(part[1]) else []
    check_parts(parts, warn)
    meshes = []
    empty = []
    for group in groups:
        found = []
        for name in group.sources:
            if name not in parts:
                continue
            if not parts[name]:
                empty.append(name)
            found.extend(parts[name])
        if found:
            vertices, triangles, colour_kwargs, colour_warning = combine_colours(found)
            if colour_warning and warn is not None:
                warn(colour_warning)
            meshes.append(GroupMesh(group, vertices, triangles, colour_kwargs))
    if not meshes:
        raise SelectionError("Nothing to voxelize: " + ", ".join(empty) + " has no faces")
    if empty and warn is not None:
        warn("Skipped objects without faces: " + ", ".join(empty))
    return meshes
