# SPDX-License-Identifier: GPL-3.0-or-later
"""One control for what the voxels hold: Mode (Surface, Thin Surface, Solid; Solid by
default). A .blend saved with the Fill Interior switch of earlier versions opens with the
Mode it meant; one saved by this version opens as saved. Grouped volumes are named after the
active object and their files after the volume, stable across re-runs. (This test opens
files: its own Blender process.)"""

import os
import re

import bpy

import helpers
from helpers import AddonTestCase

# (stored Fill Interior or None, stored Mode or None) -> the Mode it meant
OLD_FILES = [
    ((1, "thin"), "solid"),
    ((0, "thin"), "thin"),
    ((None, None), "solid"),
    ((0, None), "conservative"),
    ((None, "thin"), "solid"),
    ((1, None), "solid"),
]


class ControlsTest(AddonTestCase):
    def test_mode_is_the_one_control(self):
        scene = bpy.context.scene.hyvox.bl_rna.properties
        operator = bpy.ops.object.hyvox_voxelize.get_rna_type().properties
        self.assertNotIn("fill_interior", scene)
        # The operator still takes the old keyword from scripts (test_old_keywords.py), never
        # shown in its panel.
        self.assertTrue(operator["fill_interior"].is_hidden)
        self.assertEqual((scene["mode"].default, operator["mode"].default), ("solid", "solid"))

    def save_as_earlier_version(self, path, fill_interior, mode):
        """A .blend as earlier versions saved it: no settings stamp, the old switch stored."""
        legacy_settings = helpers.addon("blender.ui.legacy_settings")
        settings = bpy.context.scene.hyvox
        settings.property_unset("mode")
        if mode is not None:
            settings.mode = mode
        if fill_interior is not None:
            settings[legacy_settings.OLD_FILL_INTERIOR_KEY] = fill_interior
        if legacy_settings.SETTINGS_VERSION_KEY in settings:
            del settings[legacy_settings.SETTINGS_VERSION_KEY]
        bpy.app.handlers.save_pre.remove(legacy_settings.stamp_before_save)
        try:
            bpy.ops.wm.save_as_mainfile(filepath=path)
        finally:
            bpy.app.handlers.save_pre.append(legacy_settings.stamp_before_save)

    def test_files_of_earlier_versions_open_with_the_mode_they_meant(self):
        legacy_settings = helpers.addon("blender.ui.legacy_settings")
        for (fill_interior, mode), meant in OLD_FILES:
            with self.subTest(fill_interior=fill_interior, mode=mode):
                path = os.path.join(self.out, "old.blend")
                self.save_as_earlier_version(path, fill_interior, mode)
                bpy.ops.wm.open_mainfile(filepath=path)
                settings = bpy.context.scene.hyvox
                self.assertEqual(settings.mode, meant)
                self.assertNotIn(legacy_settings.OLD_FILL_INTERIOR_KEY, settings)
        # Saved by this version: opened as saved, Thin stays Thin.
        bpy.context.scene.hyvox.mode = "thin"
        path = os.path.join(self.out, "new.blend")
        bpy.ops.wm.save_as_mainfile(filepath=path)
        bpy.ops.wm.open_mainfile(filepath=path)
        self.assertEqual(bpy.context.scene.hyvox.mode, "thin")

    def test_group_names(self):
        a, b = helpers.cube("A", 1.0), helpers.cube("B", 1.0, (3, 0, 0))
        helpers.select_only(b, a)  # B active
        names = []
        for resolution in (8, 12):
            self.assertEqual(self.voxelize(resolution=resolution), {"FINISHED"})
            (volume,) = self.volumes()
            names.append((volume.name, os.path.basename(bpy.path.abspath(volume.data.filepath))))
        for name, file_name in names:
            self.assertEqual(name, "B_and_1_more_voxels")
            self.assertRegex(file_name, r"^B_and_1_more_voxels_r[0-9a-f]{6}x\.vdb$")
        self.assertNotEqual(names[0][1], names[1][1], "each run its own file (undo)")
        self.assertIsNone(re.search(r"_[0-9a-f]{8}_", names[0][1]), "no hash in the name")
