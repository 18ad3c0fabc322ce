# SPDX-License-Identifier: GPL-3.0-or-later
"""The 3D View sidebar panel (tab "Voxelize"), laid out like Blender's own Remesh and Mesh
to Volume panels: the main choices first, then the sub-panels Output, Animation and
Advanced (closed by default), short labels (the tooltips say the rest), options that do
not apply to the chosen method hidden, and the last run's summary in short lines."""

import bpy

from ...core import backend, panel_rules
from ...core.errors import HyvoxError
from . import properties
from .. import operators


def _resolved_method(context, settings) -> str:
    """The method a run would use: the run's own rule (backend.resolve_method) with the
    preferences' GL device (its probe is cached after the first call)."""
    try:
        module = backend.load_module()
    except HyvoxError:  # not loaded: a run would say why; the panel shows cpu
        module = None
    prefs = properties.preferences(context)
    return backend.resolve_method(module, settings.method, prefs.gl_device_string if prefs is not None else "")


_device_cache = []


def _gl_device():
    if not _device_cache:
        try:
            _device_cache.append(panel_rules.gl_device_summary(backend.load_module().gl_devices()))
        except Exception:
            _device_cache.append(None)
    return _device_cache[0]


def _applies(name, method) -> bool:
    """Whether option `name` does anything for the resolved `method`: the schema's one rule
    (the same the CLI and hyvox.voxelize warn by). Options that do not are hidden."""
    return properties.option_spec(name).applies_to(method)


class _HyvoxPanel:
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Voxelize"
    bl_context = "objectmode"

    def layout_split(self):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        return layout


class _HyvoxSubPanel(_HyvoxPanel):
    """Output, Animation, Advanced: under the main panel, closed until opened."""

    bl_parent_id = "VIEW3D_PT_hyvox_voxelize"
    bl_options = {"DEFAULT_CLOSED"}


class VIEW3D_PT_hyvox_voxelize(_HyvoxPanel, bpy.types.Panel):
    bl_label = "Voxelize"

    def draw(self, context):
        layout = self.layout_split()
        settings = context.scene.hyvox
        col = layout.column()
        col.prop(settings, "size_mode", expand=True)
        col.prop(settings, "resolution" if settings.size_mode == "RESOLUTION" else "voxel_size")
        col.prop(settings, "method")
        method = _resolved_method(context, settings)
        note = panel_rules.method_note(settings.method, method, _gl_device())
        if note:
            software = settings.method in panel_rules.GL_METHODS and (_gl_device() or {}).get("software", True)
            row = col.row()
            row.alignment = "RIGHT"
            row.label(text=note, icon="ERROR" if software else "INFO")
        col.prop(settings, "mode")
        if settings.mode == "solid":
            col.prop(settings, "inside", text="Inside")
        if _applies("tess_gamma", method):
            col.prop(settings, "tess_gamma")
        col.prop(settings, "output", text="Output")
        col.prop(settings, "color")

        layout.operator(operators.OBJECT_OT_hyvox_voxelize.bl_idname, icon="VOLUME_DATA")
        record = operators.last_run_record
        if record.get("volumes"):
            box = layout.box()
            column = box.column(align=True)
            for line in panel_rules.summary_lines(record):
                column.label(text=line)


class VIEW3D_PT_hyvox_output(_HyvoxSubPanel, bpy.types.Panel):
    bl_label = "Output"

    def draw(self, context):
        layout = self.layout_split()
        settings = context.scene.hyvox
        col = layout.column(heading="Volumes")
        col.prop(settings, "separate", text="Per Object")
        col.prop(settings, "parent_to_source", text="Parent")
        col.prop(settings, "hide_source", text="Hide Source")
        col = layout.column(heading="Write")
        col.prop(settings, "signed_distance")
        col.prop(settings, "export_vox", text=".vox File")
        layout.prop(settings, "output_dir", text="Folder")
        layout.operator("wm.hyvox_clean_voxel_files", text="Clean Unused Files", icon="TRASH")


class VIEW3D_PT_hyvox_animation(_HyvoxSubPanel, bpy.types.Panel):
    bl_label = "Animation"

    def draw_header(self, context):
        self.layout.prop(context.scene.hyvox, "use_frame_range", text="")

    def draw(self, context):
        layout = self.layout_split()
        settings = context.scene.hyvox
        col = layout.column(align=True)
        col.enabled = settings.use_frame_range
        col.prop(settings, "frame_start", text="Start")
        col.prop(settings, "frame_end", text="End")


class VIEW3D_PT_hyvox_advanced(_HyvoxSubPanel, bpy.types.Panel):
    bl_label = "Advanced"

    def draw(self, context):
        layout = self.layout_split()
        settings = context.scene.hyvox
        method = _resolved_method(context, settings)
        col = layout.column()
        col.prop(settings, "padding")
        col.prop(settings, "evaluation", text="Modifiers")
        if _applies("hybrid_cutoff", method):
            col.prop(settings, "hybrid_cutoff", text="Cutoff")


CLASSES = (VIEW3D_PT_hyvox_voxelize, VIEW3D_PT_hyvox_output, VIEW3D_PT_hyvox_animation, VIEW3D_PT_hyvox_advanced)
