# SPDX-License-Identifier: GPL-3.0-or-later
"""The add-on's own exceptions. The operator turns every HyvoxError into
self.report({'ERROR'}, ...) + {'CANCELLED'}; anything else is a bug."""

from .messages import in_addon_words


class HyvoxError(Exception):
    """A failure the artist can act on (bad selection, bad settings, native error), in the
    add-on's words (messages.py: settings named as the panel and preferences name them)."""

    def __init__(self, message: str = ""):
        super().__init__(in_addon_words(str(message)))


class SettingsError(HyvoxError):
    """Settings that cannot be voxelized (resolution out of range, bad frame range...)."""


class SelectionError(HyvoxError):
    """Nothing voxelizable selected: no mesh, only empty meshes, non-mesh objects."""


class ModuleMissingError(HyvoxError):
    """The compiled hyvox module is neither bundled with the add-on nor installed."""


class CancelledError(HyvoxError):
    """The artist pressed Esc (or a script cancelled the token)."""
