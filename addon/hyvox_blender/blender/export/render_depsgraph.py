# SPDX-License-Identifier: GPL-3.0-or-later
"""The scene as a render evaluates it (modifiers and Geometry Nodes at render settings,
objects hidden in renders left out).

Blender's Python API gives a script only the viewport's depsgraph; a render-mode one exists
only inside a render engine's render(). So for one run a tiny engine is registered, the scene
is "rendered" with it (it draws nothing; no compositing), its render() hands the depsgraph to
the caller's function, and engine and settings are put back. It costs a few milliseconds
plus the render-level evaluation itself. Render handlers of other add-ons do run."""

from typing import Callable, Optional, TypeVar

import bpy

T = TypeVar("T")
ENGINE_ID = "HYVOX_RENDER_EVALUATION"


class _Call:
    """What the engine should do and what came out; one call at a time (main thread)."""

    function: Optional[Callable] = None
    result = None
    error: Optional[BaseException] = None
    called = False


class HYVOX_RenderEvaluation(bpy.types.RenderEngine):
    bl_idname = ENGINE_ID
    bl_label = "hyvox (evaluation only)"
    bl_use_postprocess = False  # no compositing of the (empty) image

    def render(self, depsgraph):
        _Call.called = True
        try:
            _Call.result = _Call.function(depsgraph)
        except BaseException as exc:  # re-raised in the caller: Blender would only print it
            _Call.error = exc


class RenderEvaluationUnavailable(RuntimeError):
    """The scene cannot be render-evaluated now (another render runs, the view layer is
    disabled for rendering, ...); the message says why."""


def with_render_depsgraph(context, function: Callable[[bpy.types.Depsgraph], T]) -> T:
    """function(depsgraph) with the current frame and view layer evaluated for rendering."""
    scene = context.scene
    engine = scene.render.engine
    registered = False
    _Call.function, _Call.result, _Call.error, _Call.called = function, None, None, False
    try:
        bpy.utils.register_class(HYVOX_RenderEvaluation)  # only for this call: never in the engine list
        registered = True
        scene.render.engine = ENGINE_ID
        try:
            bpy.ops.render.render(layer=context.view_layer.name, scene=scene.name)
        except RuntimeError as exc:
            raise RenderEvaluationUnavailable(str(exc).strip()) from None
    finally:
        scene.render.engine = engine
        if registered:
            bpy.utils.unregister_class(HYVOX_RenderEvaluation)
        _Call.function = None
    if _Call.error is not None:
        error, _Call.error = _Call.error, None
        raise error
    if not _Call.called:
        raise RenderEvaluationUnavailable("the scene has nothing to render (is the view layer or camera disabled?)")
    result, _Call.result = _Call.result, None
    return result
