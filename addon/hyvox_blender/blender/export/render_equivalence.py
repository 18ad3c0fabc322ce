# SPDX-License-Identifier: GPL-3.0-or-later
"""Whether a render evaluation would give exactly the viewport's geometry, so that a run at
render settings can take the viewport's depsgraph and skip render_depsgraph.py's render
call (on a 1M-triangle mesh that call costs about twice the export itself: the scene is
copied and evaluated once more).

Render and viewport evaluations differ only through modifiers (Subdivision levels,
Simplify, Geometry Nodes' Is Viewport, particles), the conversion of curves, text,
surfaces and metaballs (their render resolutions), instancing (instanced objects' own
visibility) and visibility (hidden in renders, or in the viewport). So the answer is yes
only for plain mesh objects without modifiers, not instancing nor instanced by a parent,
shown both in the viewport and in renders; anything else keeps the render evaluation."""

from typing import Iterable, Set

import bpy


def _collections_shown_in_renders(view_layer: bpy.types.ViewLayer) -> Set[int]:
    """The view layer's collections (as_pointer) whose objects renders show."""
    shown: Set[int] = set()

    def walk(layer_collection, parent_shown):
        collection = layer_collection.collection
        here = parent_shown and not layer_collection.exclude and not collection.hide_render
        if here:
            shown.add(collection.as_pointer())
        for child in layer_collection.children:
            walk(child, here)

    walk(view_layer.layer_collection, True)
    return shown


def _instanced_by_parent(obj: bpy.types.Object) -> bool:
    parent = obj.parent
    while parent is not None:
        if parent.instance_type != "NONE":
            return True
        parent = parent.parent
    return False


def _plain_mesh(obj: bpy.types.Object) -> bool:
    return (
        obj.type == "MESH" and len(obj.modifiers) == 0 and obj.instance_type == "NONE" and not _instanced_by_parent(obj)
    )


def same_in_renders(names: Iterable[str], view_layer: bpy.types.ViewLayer) -> bool:
    """True when rendering would evaluate every named object exactly as the viewport does."""
    shown = None
    for name in names:
        obj = bpy.data.objects.get(name)
        if obj is None or not _plain_mesh(obj):
            return False
        if obj.hide_render or obj.hide_viewport or not obj.visible_get(view_layer=view_layer):
            return False
        if shown is None:
            shown = _collections_shown_in_renders(view_layer)
        if not any(collection.as_pointer() in shown for collection in obj.users_collection):
            return False
    return True
