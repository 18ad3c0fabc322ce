# SPDX-License-Identifier: GPL-3.0-or-later
"""The meshes of one frame as a run voxelizes them: evaluated at render settings unless the
viewport's are asked for (or the render would show the same), with colour if asked. The
operator exports each frame this way; a farm task also exports the job's first frame to
take its voxel size (farm_task.py)."""

import bpy

from . import render_depsgraph, render_equivalence, sources as export


def export_meshes(groups, evaluation: str, colour: bool, warn):
    """GroupMesh per group at the scene's current frame. evaluation: "RENDER" or "VIEWPORT"."""
    viewport = bpy.context.evaluated_depsgraph_get()
    names = [name for group in groups for name in group.sources]
    if evaluation == "VIEWPORT" or render_equivalence.same_in_renders(names, bpy.context.view_layer):
        return export.export_groups(groups, viewport, warn=warn, colour=colour)
    try:
        return render_depsgraph.with_render_depsgraph(
            bpy.context,
            lambda depsgraph: export.export_groups(
                groups, depsgraph, warn=warn, fallback_depsgraph=viewport, colour=colour
            ),
        )
    except render_depsgraph.RenderEvaluationUnavailable as exc:
        warn(f"Modifiers evaluated at viewport settings: no render evaluation ({exc})")
        return export.export_groups(groups, viewport, warn=warn, colour=colour)
