# SPDX-License-Identifier: GPL-3.0-or-later
"""Live in the sidebar and on the keyboard: the Live sub-panel (the active volume's switch
and what its updates are doing, or the setting for new volumes when no volume is active)
and Esc, which cancels the Live runs going on and passes the key on to whatever else uses
it (stopping playback, closing a menu)."""

import bpy

from . import driver as live, volumes as live_volumes
from ..ui.panels import _HyvoxSubPanel


class VIEW3D_PT_hyvox_live(_HyvoxSubPanel, bpy.types.Panel):
    bl_label = "Live"
    bl_options = set()

    def draw_header(self, context):
        obj = context.active_object
        if live_volumes.is_result(obj):
            self.layout.prop(obj, "hyvox_live", text="")

    def draw(self, context):
        layout = self.layout_split()
        obj = context.active_object
        if not live_volumes.is_result(obj):
            layout.prop(context.scene.hyvox, "live", text="New Volumes")
            return
        if not obj.hyvox_live:
            layout.label(text="Off: the voxels are kept")
            return
        line = live.status_line(obj)
        row = layout.row()
        row.alert = line.startswith("Error")
        row.label(text=line, icon="ERROR" if row.alert else "TIME" if line.startswith("Updating") else "CHECKMARK")


class WM_OT_hyvox_live_cancel(bpy.types.Operator):
    """Cancel the Live updates going on (the volumes keep their last voxels)"""

    bl_idname = "wm.hyvox_live_cancel"
    bl_label = "Cancel Live Updates"
    bl_options = {"INTERNAL"}

    def execute(self, context):
        return {"FINISHED"} if live.cancel_runs("Esc") else {"CANCELLED"}

    def invoke(self, context, event):
        live.cancel_runs("Esc")
        return {"PASS_THROUGH"}  # Esc goes on to stop playback, close a menu...


CLASSES = (VIEW3D_PT_hyvox_live, WM_OT_hyvox_live_cancel)
_keymaps = []


def register():
    keyconfig = bpy.context.window_manager.keyconfigs.addon if bpy.context.window_manager else None
    if keyconfig is None:  # background mode: no keyboard
        return
    keymap = keyconfig.keymaps.new(name="Window", space_type="EMPTY")
    item = keymap.keymap_items.new(WM_OT_hyvox_live_cancel.bl_idname, "ESC", "PRESS")
    _keymaps.append((keymap, item))


def unregister():
    for keymap, item in _keymaps:
        keymap.keymap_items.remove(item)
    _keymaps.clear()
