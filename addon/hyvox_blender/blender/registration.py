# SPDX-License-Identifier: GPL-3.0-or-later
"""Register every class and hook of the bpy layer, in dependency order."""

import bpy

from . import operators
from .files import clean as clean_files, handlers as file_handlers, history as file_history
from .live import driver as live, panel as live_ui
from .ui import legacy_settings, panels as ui, properties

_CLASSES = properties.CLASSES + operators.CLASSES + clean_files.CLASSES + ui.CLASSES + live_ui.CLASSES


def register():
    for cls in _CLASSES:
        bpy.utils.register_class(cls)
    properties.register()
    operators.register()
    legacy_settings.register()
    file_history.register()
    file_handlers.register()
    live.register()  # after file_handlers: its save_post sees the files moved next to the .blend
    live_ui.register()


def unregister():
    live_ui.unregister()
    live.unregister()
    file_handlers.unregister()
    file_history.unregister()
    legacy_settings.unregister()
    operators.unregister()
    properties.unregister()
    for cls in reversed(_CLASSES):
        bpy.utils.unregister_class(cls)
