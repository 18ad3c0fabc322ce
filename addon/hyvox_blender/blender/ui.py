# SPDX-License-Identifier: GPL-3.0-or-later
"""The 3D View sidebar panel (tab "Voxelize")."""
import bpy

from . import operators


class VIEW3D_PT_hyvox_voxelize(bpy.types.Panel):
    bl_label = "Voxelize"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Voxelize"
    bl_context = "objectmode"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        settings = context.scene.hyvox

        col = layout.column()
        col.prop(settings, "size_mode", expand=True)
        if settings.size_mode == "RESOLUTION":
            col.prop(settings, "resolution")
        else:
            col.prop(settings, "voxel_size")
        col.prop(settings, "method")
        col.prop(settings, "fill_interior")
        if settings.fill_interior:
            col.prop(settings, "inside")
        else:
            col.prop(settings, "mode")
        if settings.method == "tessellation":
            col.prop(settings, "tess_gamma")
        if settings.method in {"hybrid", "auto"}:
            col.prop(settings, "hybrid_cutoff")
        col.prop(settings, "padding")
        col.prop(settings, "separate")
        col.prop(settings, "output_dir")

        col = layout.column(heading="Animation")
        col.prop(settings, "use_frame_range")
        sub = col.column(align=True)
        sub.enabled = settings.use_frame_range
        sub.prop(settings, "frame_start")
        sub.prop(settings, "frame_end")

        layout.operator(operators.OBJECT_OT_hyvox_voxelize.bl_idname, icon="VOLUME_DATA")
        if operators.last_summary:
            box = layout.box()
            for line in operators.last_summary:
                box.label(text=line)


CLASSES = (VIEW3D_PT_hyvox_voxelize,)
