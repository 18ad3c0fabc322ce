# SPDX-License-Identifier: GPL-3.0-or-later
"""OBJECT_OT_hyvox_voxelize. In the UI (invoke) the native work runs on a worker thread
polled by a modal timer, with a progress bar, a status bar message and Esc to cancel.
execute() runs synchronously: background mode, scripts, and redo from the Adjust panel.
Every HyvoxError becomes a report and {'CANCELLED'} with the scene unchanged."""

import time
import traceback
import warnings

import bpy

from ..core import backend, naming, summary
from ..core.errors import CancelledError, HyvoxError
from ..core.pipeline import Pipeline
from .export import frames as frame_export, sources as export
from .live import driver as live
from .ui import legacy_settings, properties
from .volume import importer
from .gather import gather

# The last run's summary lines (shown in the panel) and record (for scripts).
last_summary = []
last_run_record = {}


def _hide_in_layer(obj, hide: bool, layer) -> bool:
    """obj.hide_set(hide) in `layer`; False when obj is not in that layer (its collection is
    excluded there), which Blender reports by RuntimeError."""
    try:
        obj.hide_set(hide, view_layer=layer)
    except RuntimeError:
        return False
    return True


class _Run:
    """One run's state shared by execute() and the modal path."""

    def __init__(self, context, op):
        settings, folder, self.override, used = gather(context, op)
        self.scene = context.scene
        self.original_frame = context.scene.frame_current
        self.op = op
        sources = export.pick_sources(context.selected_objects, warn=self.warn)
        self.groups = export.make_groups(sources, settings.separate, context.view_layer.objects.active)
        # New file names per run, so that undo never brings back a volume whose file a later
        # run overwrote (farm chunks ask for fixed names to assemble one sequence).
        run_tag = naming.new_run_tag() if op.unique_file_names else None
        self.pipeline = Pipeline(settings, folder, self.export_frame, run_tag=run_tag)  # validates the settings
        if self.pipeline.ignored_options:
            op.report({"INFO"}, backend.ignored_message(self.pipeline.ignored_options, self.pipeline.method))
        # The redo panel shows, and a redo repeats, exactly what this run used.
        for name, value in used.items():
            setattr(op, name, value)
        self.used = used

    def warn(self, text):
        self.op.report({"WARNING"}, text)

    def export_frame(self, frame):
        if frame is not None and frame != self.scene.frame_current:
            self.scene.frame_set(frame)
        return frame_export.export_meshes(self.groups, self.used["evaluation"], bool(self.used["color"]), self.warn)

    def restore_frame(self):
        if self.scene.frame_current != self.original_frame:
            self.scene.frame_set(self.original_frame)

    def show_results(self, context, objects):
        """The new results selected, active and visible; the sources hidden if asked."""
        layer = context.view_layer
        # Objects are found through the scene's collections, not layer.objects: after objects
        # are removed (a re-run replaces its results) Blender 4.5/5.0 can list them there as
        # None until the layer resyncs, and reading their names crashes.
        for obj in context.scene.objects:
            if obj.select_get(view_layer=layer):
                obj.select_set(False, view_layer=layer)
        shown = [obj for obj in objects if _hide_in_layer(obj, False, layer)]
        for obj in shown:
            obj.select_set(True, view_layer=layer)
        if shown:
            layer.objects.active = shown[0]
        if self.used["hide_source"]:
            for name in {name for group in self.groups for name in group.sources}:
                source = context.scene.objects.get(name)
                if source is not None:
                    _hide_in_layer(source, True, layer)

    def finish(self, context):
        """Commit the files and import them as volumes (main thread)."""
        pipeline = self.pipeline
        pipeline.commit()
        start = time.perf_counter()
        objects = importer.import_results(
            context, pipeline.results, self.override, parent_to_source=self.used["parent_to_source"], warn=self.warn
        )
        pipeline.timings.import_ms += (time.perf_counter() - start) * 1000.0
        self.show_results(context, objects)
        live.take_over(objects, pipeline.results, self.used)
        lines = summary.long_report(pipeline.results, pipeline.timings)
        last_summary[:] = lines
        last_run_record.clear()
        last_run_record.update(summary.as_dict(pipeline.results, pipeline.timings))
        last_run_record["settings"] = dict(self.used)
        for line in lines:
            print("hyvox:", line)
        self.op.report({"INFO"}, summary.short_report(pipeline.results, pipeline.timings))
        return objects


class OBJECT_OT_hyvox_voxelize(bpy.types.Operator):
    """Voxelize the selected meshes into OpenVDB volumes aligned with them"""

    bl_idname = "object.hyvox_voxelize"
    bl_label = "Voxelize"
    bl_options = {"REGISTER", "UNDO"}

    # Keyword arguments override the scene's settings for one call (unset ones don't); the
    # same definitions as the Scene's, from the options schema (limits as soft limits: see
    # properties.schema_property).
    __annotations__ = dict(
        properties.scene_and_operator_properties(operator=True),
        unique_file_names=bpy.props.BoolProperty(
            name="New File Names",
            default=True,
            options={"HIDDEN", "SKIP_SAVE"},
            description="Write this run's files under new names (off: rewrite the same names each run)",
        ),
        # Deprecated (docs/compatibility.md): the switch Mode replaced, kept so that scripts
        # written against earlier versions still run; execute() maps it onto mode.
        fill_interior=bpy.props.BoolProperty(
            name="Fill Interior",
            default=True,
            options={"HIDDEN", "SKIP_SAVE"},
            description="Deprecated: use mode='solid' (on) or a surface mode (off)",
        ),
    )

    _active = None  # the running modal operator's _Run: one run at a time

    @classmethod
    def poll(cls, context):
        # Selection problems are reported by execute(), not hidden by a failing poll.
        return context.scene is not None and context.mode == "OBJECT"

    def _map_old_keywords(self, context):
        """fill_interior=, the switch Mode replaced, mapped onto mode once
        (legacy_settings.fill_interior_mode), with a deprecation warning naming mode=."""
        props = self.properties
        if not props.is_property_set("fill_interior"):
            return
        given = self.mode if props.is_property_set("mode") else None
        mode = legacy_settings.fill_interior_mode(props.fill_interior, given, context.scene.hyvox.mode)
        text = legacy_settings.FILL_INTERIOR_DEPRECATED.format(value=props.fill_interior, mode=mode)
        warnings.warn(text, FutureWarning, stacklevel=2)  # shown by default: meant for scripts
        self.report({"WARNING"}, text)
        self.mode = mode
        props.property_unset("fill_interior")  # a redo keeps the mode, not the old switch

    # -- synchronous ------------------------------------------------------------------
    def execute(self, context):
        if OBJECT_OT_hyvox_voxelize._active is not None:
            self.report({"ERROR"}, "A voxelization is already running")
            return {"CANCELLED"}
        self._map_old_keywords(context)
        run = None
        try:
            run = _Run(context, self)
            run.pipeline.run()
            run.restore_frame()
            run.finish(context)
        except Exception as exc:
            if run is not None:
                run.pipeline.discard()
                run.restore_frame()
            self._report_failure(exc)
            return {"CANCELLED"}
        return {"FINISHED"}

    def _report_failure(self, exc):
        """A HyvoxError is the artist's to read; anything else is a bug in hyvox, reported
        with its traceback on the console instead of leaving a half-finished run behind."""
        if isinstance(exc, HyvoxError):
            self.report({"WARNING"} if isinstance(exc, CancelledError) else {"ERROR"}, str(exc))
            return
        traceback.print_exception(type(exc), exc, exc.__traceback__)
        self.report({"ERROR"}, f"hyvox failed unexpectedly ({type(exc).__name__}: {exc}); see the console")

    # -- interactive ------------------------------------------------------------------
    def invoke(self, context, event):
        if bpy.app.background or context.window is None:
            return self.execute(context)
        if OBJECT_OT_hyvox_voxelize._active is not None:
            self.report({"ERROR"}, "A voxelization is already running")
            return {"CANCELLED"}
        self._map_old_keywords(context)
        try:
            self._run = _Run(context, self)
            self._run.pipeline.start_next_frame()
        except Exception as exc:
            self._report_failure(exc)
            if getattr(self, "_run", None) is not None:
                self._run.restore_frame()
            return {"CANCELLED"}
        OBJECT_OT_hyvox_voxelize._active = self._run
        wm = context.window_manager
        self._timer = wm.event_timer_add(0.1, window=context.window)
        wm.progress_begin(0, 100)
        wm.modal_handler_add(self)
        self._status(context)
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        run = self._run
        pipeline = run.pipeline
        if event.type == "ESC" and event.value == "PRESS":
            # Not waiting for the worker: whatever stage it is in (the start before any
            # progress, voxelizing, writing the .vdb), the operator ends now; the worker
            # stops at its next check and deletes what it staged.
            pipeline.abandon()
            run.restore_frame()
            self._end(context)
            self.report({"WARNING"}, "Voxelization cancelled")
            return {"CANCELLED"}
        if event.type != "TIMER":  # any timer tick is a fine moment to poll
            return {"PASS_THROUGH"}  # the UI stays usable while the worker runs
        if pipeline.worker_busy():
            self._status(context)
            return {"RUNNING_MODAL"}
        try:
            pipeline.finish_frame()
            if pipeline.start_next_frame():
                self._status(context)
                return {"RUNNING_MODAL"}
            run.restore_frame()
            run.finish(context)
        except Exception as exc:  # whatever it is, the run ends here: no operator left locked
            pipeline.discard()
            run.restore_frame()
            self._end(context)
            self._report_failure(exc)
            return {"CANCELLED"}
        self._end(context)
        return {"FINISHED"}

    def _status(self, context):
        pipeline = self._run.pipeline
        percent = int(round(pipeline.progress * 100))
        context.window_manager.progress_update(percent)
        frame = pipeline.current_frame
        where = f" frame {frame}," if frame is not None else ""
        context.workspace.status_text_set(f"Voxelizing ({pipeline.method}){where} {percent}%  -  Esc to cancel")

    def _end(self, context):
        wm = context.window_manager
        wm.event_timer_remove(self._timer)
        wm.progress_end()
        context.workspace.status_text_set(None)
        OBJECT_OT_hyvox_voxelize._active = None


def menu_entry(self, context):
    self.layout.separator()
    self.layout.operator(OBJECT_OT_hyvox_voxelize.bl_idname, icon="VOLUME_DATA")


CLASSES = (OBJECT_OT_hyvox_voxelize,)


def register():
    bpy.types.VIEW3D_MT_object.append(menu_entry)


def unregister():
    bpy.types.VIEW3D_MT_object.remove(menu_entry)
