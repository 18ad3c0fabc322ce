# SPDX-License-Identifier: GPL-3.0-or-later
"""Live volumes and files (this test saves and opens .blend files: its own Blender process):
saving keeps the voxels shown with the .blend as a run's are kept; opening a file cancels
Live and deletes what only the closed session showed, never what a saved .blend refers to;
disabling the add-on leaves every volume with its voxels."""

import addon_utils
import os

import bpy

import helpers
from helpers import AddonTestCase


def live():
    return helpers.addon("blender.live.driver")


def voxel_files(folder):
    """The files of a session folder but the marker naming its owner (core/session_folder.py)."""
    owner = helpers.addon("core.session_folder").OWNER_FILE
    return sorted(n for n in os.listdir(folder) if n != owner) if os.path.isdir(folder) else []


def volume_file(obj):
    return os.path.realpath(bpy.path.abspath(obj.data.filepath))


class LiveFilesTest(AddonTestCase):
    def test_save_then_open_keeps_what_the_blend_refers_to(self):
        naming = helpers.addon("core.naming")
        self.assertEqual(bpy.data.filepath, "")
        cube = helpers.cube(size=1.0)
        helpers.select_only(cube)
        self.assertEqual(self.voxelize(live=True, resolution=12, output_dir=""), {"FINISHED"})
        volume = bpy.data.objects["Cube_voxels"]
        unsaved = naming.unsaved_output_dir(create=False)
        cube.location.x = 0.5
        bpy.context.view_layer.update()
        self.assertEqual(len(voxel_files(unsaved)), 2, os.listdir(unsaved))  # the first run's and the edit's

        blend = os.path.join(self.out, "shot.blend")
        bpy.ops.wm.save_as_mainfile(filepath=blend)
        cache = os.path.join(self.out, "hyvox_cache", "shot")
        self.assertTrue(volume.data.filepath.startswith("//hyvox_cache/shot/"), volume.data.filepath)
        saved_file = volume_file(volume)
        self.assertTrue(os.path.exists(saved_file))
        # Live goes on next to the .blend.
        cube.location.x = 1.0
        bpy.context.view_layer.update()
        edited_file = volume_file(volume)
        self.assertEqual(os.path.dirname(edited_file), os.path.realpath(cache))
        self.assertNotEqual(edited_file, saved_file)

        # Opening the saved file (unsaved changes dropped): what the .blend refers to stays,
        # what only the closed session showed goes.
        bpy.ops.wm.open_mainfile(filepath=blend)
        self.assertTrue(os.path.exists(saved_file))
        self.assertFalse(os.path.exists(edited_file))
        self.assertEqual(voxel_files(unsaved), [])
        volume, cube = bpy.data.objects["Cube_voxels"], bpy.data.objects["Cube"]
        self.assertTrue(volume.hyvox_live)
        self.assertEqual(volume_file(volume), saved_file)
        cube.location.x = -0.5  # still live after opening
        bpy.context.view_layer.update()
        self.assertNotEqual(volume_file(volume), saved_file)
        self.assertTrue(os.path.exists(volume_file(volume)))

    def test_disabling_the_addon_keeps_the_voxels(self):
        cube = helpers.cube(size=1.0)
        helpers.select_only(cube)
        self.voxelize(live=True, resolution=12)
        volume = bpy.data.objects["Cube_voxels"]
        cube.location.x = 0.5
        bpy.context.view_layer.update()
        shown = volume_file(volume)
        addon_utils.disable(helpers.ADDON_PACKAGE, default_set=False)
        try:
            self.assertEqual(os.listdir(self.out), [os.path.basename(shown)])
            cube.location.x = 1.0
            bpy.context.view_layer.update()  # no add-on, no handler: nothing happens
            self.assertEqual(volume_file(volume), shown)
        finally:
            addon_utils.enable(helpers.ADDON_PACKAGE, default_set=False, handle_error=None)
        cube.location.x = 1.5
        bpy.context.view_layer.update()
        self.assertNotEqual(volume_file(volume), shown)
