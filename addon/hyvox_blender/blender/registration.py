# SPDX-License-Identifier: GPL-3.0-or-later
"""Register every class and hook of the bpy layer, in dependency order."""
import bpy

from . import operators, properties, ui

_CLASSES = properties.CLASSES + operators.CLASSES + ui.CLASSES


def register():
    for cls in _CLASSES:
        bpy.utils.register_class(cls)
    properties.register()
    operators.register()


def unregister():
    operators.unregister()
    properties.unregister()
    for cls in reversed(_CLASSES):
        bpy.utils.unregister_class(cls)
