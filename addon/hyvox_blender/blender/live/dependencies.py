# SPDX-License-Identifier: GPL-3.0-or-later
"""A live volume depends on its sources in Blender's dependency graph, through one
pass-through Geometry Nodes modifier per source ("hyvox Live Source": an Object Info node
whose output nothing uses; the volume's own geometry goes through unchanged).

Why: a render evaluates only what it shows and what that depends on. A source hidden in
renders (the usual set-up: only the voxels render) is otherwise not evaluated for the
rendered frame at all, and Live would voxelize it as it was when last evaluated. With the
relation Blender evaluates it for every rendered frame, at render settings, and Live's
render-time run (live.py) exports it from the render's own evaluation."""

import bpy

from ..volume.node_groups import geometry_group

GROUP_NAME = "hyvox Live Source"
MODIFIER_NAME = "hyvox Live Source"
SOURCE_INPUT = "Source"


def _new_group() -> bpy.types.NodeTree:
    tree = bpy.data.node_groups.new(GROUP_NAME, "GeometryNodeTree")
    if hasattr(tree, "interface"):  # Blender 4.0+
        tree.interface.new_socket("Geometry", in_out="INPUT", socket_type="NodeSocketGeometry")
        tree.interface.new_socket(SOURCE_INPUT, in_out="INPUT", socket_type="NodeSocketObject")
        tree.interface.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    else:
        tree.inputs.new("NodeSocketGeometry", "Geometry")
        tree.inputs.new("NodeSocketObject", SOURCE_INPUT)
        tree.outputs.new("NodeSocketGeometry", "Geometry")
    group_in, group_out = tree.nodes.new("NodeGroupInput"), tree.nodes.new("NodeGroupOutput")
    group_in.location, group_out.location = (-300, 0), (300, 0)
    info = tree.nodes.new("GeometryNodeObjectInfo")  # its output unused: only the relation counts
    info.location = (0, -150)
    tree.links.new(group_in.outputs[SOURCE_INPUT], info.inputs["Object"])
    tree.links.new(group_in.outputs["Geometry"], group_out.inputs["Geometry"])
    return tree


def _group() -> bpy.types.NodeTree:
    return geometry_group(GROUP_NAME, _new_group)


def _source_identifier(tree) -> str:
    if hasattr(tree, "interface"):
        return tree.interface.items_tree[SOURCE_INPUT].identifier
    return tree.inputs[SOURCE_INPUT].identifier


def _ours(obj):
    return [
        m for m in obj.modifiers if m.type == "NODES" and m.node_group is not None and m.node_group.name == GROUP_NAME
    ]


def follow(obj, sources) -> None:
    """One modifier per source on obj (volume or Blocks mesh), none for a source gone."""
    unfollow(obj)
    sources = [s for s in sources if s is not None]
    if not sources:
        return
    tree = _group()
    identifier = _source_identifier(tree)
    for source in sources:
        modifier = obj.modifiers.new(MODIFIER_NAME, "NODES")
        modifier.node_group = tree
        modifier[identifier] = source
        modifier.show_expanded = False


def unfollow(obj) -> None:
    for modifier in _ours(obj):
        obj.modifiers.remove(modifier)
