# SPDX-License-Identifier: GPL-3.0-or-later
"""The add-on's own Geometry Nodes groups, one per purpose, shared by every object that uses it."""

import bpy


def geometry_group(name, make) -> bpy.types.NodeTree:
    """The Geometry Nodes group of this name, made by make() when the file has none (or only
    another kind of tree of that name)."""
    tree = bpy.data.node_groups.get(name)
    if tree is None or tree.bl_idname != "GeometryNodeTree":
        tree = make()
    return tree
