# SPDX-License-Identifier: GPL-3.0-or-later
"""Scene settings saved by earlier versions of the add-on, and the operator keyword their
scripts used, read as they were meant.

Earlier versions had a Fill Interior switch beside Mode: on (its default) the run was solid
whatever Mode said, off Mode decided. Mode is now the one control (Solid by default). A .blend
saved before that carries no SETTINGS_VERSION stamp in its Scene settings; when it loads, Mode
becomes Solid where Fill Interior was on (stored, or left at its default), else the Mode it
had (stored, or that version's default, Conservative), and the old switch is dropped. Every
save stamps the settings, so a file saved by this version is read as it is."""

import bpy
from bpy.app.handlers import persistent

SETTINGS_VERSION_KEY = "hyvox_settings_version"
SETTINGS_VERSION = 2
OLD_FILL_INTERIOR_KEY = "fill_interior"
OLD_MODE_DEFAULT = "conservative"  # the schema's default, which Mode had beside Fill Interior

# Scripts of earlier versions: the operator's fill_interior= keyword (operators.py).
FILL_INTERIOR_DEPRECATED = (
    "hyvox: fill_interior= is deprecated and will be removed; use mode= instead "
    "(fill_interior={value} runs as mode='{mode}')"
)


def fill_interior_mode(fill_interior: bool, given_mode, scene_mode: str) -> str:
    """The mode a run with the old fill_interior= keyword meant. On, the run was solid
    whatever Mode said; off, Mode decided: the mode= a script gave beside it, else the
    scene's unless that is the Solid this version defaults to (then the surface mode that
    version defaulted to)."""
    if fill_interior:
        return "solid"
    if given_mode is not None:
        return given_mode
    return scene_mode if scene_mode != "solid" else OLD_MODE_DEFAULT


def upgrade(settings) -> bool:
    """Map one Scene's settings of an earlier version (no stamp) onto this version's; True
    when it did. Stamped settings are left alone."""
    if settings.get(SETTINGS_VERSION_KEY) is not None:
        return False
    fill_interior = settings.get(OLD_FILL_INTERIOR_KEY)
    old_mode = settings.mode if settings.is_property_set("mode") else OLD_MODE_DEFAULT
    settings.mode = "solid" if fill_interior is None or bool(fill_interior) else old_mode
    if fill_interior is not None:
        del settings[OLD_FILL_INTERIOR_KEY]
    settings[SETTINGS_VERSION_KEY] = SETTINGS_VERSION
    return True


@persistent
def upgrade_loaded_file(*_args):
    for scene in bpy.data.scenes:
        upgrade(scene.hyvox)


@persistent
def stamp_before_save(*_args):
    for scene in bpy.data.scenes:
        scene.hyvox[SETTINGS_VERSION_KEY] = SETTINGS_VERSION


def register():
    bpy.app.handlers.load_post.append(upgrade_loaded_file)
    bpy.app.handlers.save_pre.append(stamp_before_save)


def unregister():
    for handlers, handler in (
        (bpy.app.handlers.load_post, upgrade_loaded_file),
        (bpy.app.handlers.save_pre, stamp_before_save),
    ):
        if handler in handlers:
            handlers.remove(handler)
