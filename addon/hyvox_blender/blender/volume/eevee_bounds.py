# SPDX-License-Identifier: GPL-3.0-or-later
"""Bounds for EEVEE Next in Blender 4.2-4.5, which clips the last voxel layer of a grid's
8^3 leaf on the +x/+y/+z side (core/alignment.py: eevee_clips_last_voxel_layer says why).

The Volume's bounds are the union of its grids' bounds, so a Geometry Nodes modifier adds
a small second grid, `hyvox_bounds`, with a few active voxels two voxels beyond the
corners of the Volume's own bounds (a signed-distance grid of two points). The file and
its `density` grid are untouched; no material reads the new grid, so only the bounds grow.
The corners come from the evaluated Volume (Bounding Box node), so a frame sequence whose
bounds change from frame to frame is covered on every frame.

One node group serves every volume; each modifier passes its voxel size."""

import bpy

from .node_groups import geometry_group

GROUP_NAME = "hyvox EEVEE Bounds"
MODIFIER_NAME = "hyvox EEVEE Bounds"
GRID_NAME = "hyvox_bounds"
VOXEL_SIZE_INPUT = "Voxel Size"
MARGIN_VOXELS = 2.0  # beyond Blender's bounds: the clipped layer plus its fade


def _new_group() -> bpy.types.NodeTree:
    tree = bpy.data.node_groups.new(GROUP_NAME, "GeometryNodeTree")
    tree.interface.new_socket("Volume", in_out="INPUT", socket_type="NodeSocketGeometry")
    size = tree.interface.new_socket(VOXEL_SIZE_INPUT, in_out="INPUT", socket_type="NodeSocketFloat")
    size.default_value, size.min_value = 0.1, 1e-6
    tree.interface.new_socket("Volume", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    nodes, link = tree.nodes, tree.links.new
    group_in, group_out = nodes.new("NodeGroupInput"), nodes.new("NodeGroupOutput")
    group_in.location, group_out.location = (-900, 0), (500, 0)

    def math(operation, a, b, vector=True, location=(0, 0)):
        """a (op) b; b a socket or a constant."""
        node = nodes.new("ShaderNodeVectorMath" if vector else "ShaderNodeMath")
        node.operation, node.location = operation, location
        link(a, node.inputs[0])
        if isinstance(b, bpy.types.NodeSocket):
            link(b, node.inputs[1])
        else:
            node.inputs[1].default_value = b
        return node.outputs[0]

    bounds = nodes.new("GeometryNodeBoundBox")
    bounds.location = (-700, 200)
    link(group_in.outputs["Volume"], bounds.inputs["Geometry"])
    voxel_size = group_in.outputs[VOXEL_SIZE_INPUT]
    margin = math("MULTIPLY", voxel_size, MARGIN_VOXELS, vector=False, location=(-700, -150))
    low = math("SUBTRACT", bounds.outputs["Min"], margin, location=(-450, 250))
    high = math("ADD", bounds.outputs["Max"], margin, location=(-450, 50))
    # Two points, at low and high: a line of two vertices made into a point cloud.
    line = nodes.new("GeometryNodeMeshLine")
    line.mode, line.location = "OFFSET", (-250, 150)
    line.inputs["Count"].default_value = 2
    link(low, line.inputs["Start Location"])
    link(math("SUBTRACT", high, low, location=(-450, -150)), line.inputs["Offset"])
    points = nodes.new("GeometryNodeMeshToPoints")
    points.location = (-50, 150)
    link(line.outputs["Mesh"], points.inputs["Mesh"])
    grid = nodes.new("GeometryNodePointsToSDFGrid")
    grid.location = (150, 150)
    link(points.outputs["Points"], grid.inputs["Points"])
    link(math("MULTIPLY", voxel_size, 0.5, vector=False, location=(-50, -100)), grid.inputs["Radius"])
    link(voxel_size, grid.inputs["Voxel Size"])
    store = nodes.new("GeometryNodeStoreNamedGrid")
    store.data_type, store.location = "FLOAT", (350, 0)
    store.inputs["Name"].default_value = GRID_NAME
    link(group_in.outputs["Volume"], store.inputs["Volume"])
    link(grid.outputs[0], store.inputs["Grid"])
    link(store.outputs["Volume"], group_out.inputs["Volume"])
    return tree


def _group() -> bpy.types.NodeTree:
    return geometry_group(GROUP_NAME, _new_group)


# The nodes the group needs (all in 4.2-4.5; a Blender without them keeps its own bounds).
NODES_NEEDED = ("GeometryNodePointsToSDFGrid", "GeometryNodeStoreNamedGrid", "GeometryNodeBoundBox")


class BoundsUnavailable(Exception):
    """The modifier could not be added; the message says why."""


def add_bounds_modifier(obj: bpy.types.Object, voxel_size: float) -> bpy.types.Modifier:
    """The modifier on a Volume object made from voxels of this size. Raises
    BoundsUnavailable when this Blender or this file does not allow it (nodes missing, a
    node group of this name that is not ours, an object that cannot take modifiers),
    leaving no half-made modifier or node group behind: the volume is fine without it,
    only EEVEE may draw its last voxel layer faint."""
    missing = [name for name in NODES_NEEDED if not hasattr(bpy.types, name)]
    if missing:
        raise BoundsUnavailable("this Blender has no " + ", ".join(missing) + " node")
    groups_before = set(bpy.data.node_groups)
    modifier = None
    try:
        tree = _group()
        modifier = obj.modifiers.new(MODIFIER_NAME, "NODES")
        modifier.node_group = tree
        modifier[tree.interface.items_tree[VOXEL_SIZE_INPUT].identifier] = float(voxel_size)
    except Exception as exc:  # Blender's API raises RuntimeError, TypeError, KeyError...
        if modifier is not None:
            obj.modifiers.remove(modifier)
        for group in set(bpy.data.node_groups) - groups_before:
            bpy.data.node_groups.remove(group)
        raise BoundsUnavailable(f"{type(exc).__name__}: {exc}") from exc
    return modifier


def unavailable_message(object_name: str, reason: BoundsUnavailable) -> str:
    """The operator's warning, for the artist."""
    return (
        f"{object_name}: EEVEE may not draw the last voxel layer on the +X/+Y/+Z side "
        f'(Cycles draws it): the "{MODIFIER_NAME}" modifier that fixes this could not '
        f"be added ({reason})"
    )
