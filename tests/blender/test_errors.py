# SPDX-License-Identifier: GPL-3.0-or-later
"""Error paths are reported and leave the scene unchanged."""
import os

import bpy

import helpers
from helpers import AddonTestCase


class ErrorTest(AddonTestCase):
    def assert_reported(self, fragment, **kw):
        before = self.scene_state()
        with self.assertRaises(RuntimeError) as caught:  # bpy.ops raises on error reports
            self.voxelize(**kw)
        self.assertIn(fragment, str(caught.exception))
        self.assertEqual(self.scene_state(), before)
        self.assertEqual([f for f in os.listdir(self.out)], [])

    def test_nothing_selected(self):
        helpers.cube()
        helpers.select_only()
        self.assert_reported("Select at least one mesh")

    def test_non_mesh(self):
        empty = bpy.data.objects.new("Empty", None)
        bpy.context.scene.collection.objects.link(empty)
        helpers.select_only(empty)
        self.assert_reported("has no geometry")

    def test_empty_mesh(self):
        obj = helpers.mesh_object("Nothing", [], [])
        helpers.select_only(obj)
        self.assert_reported("has no faces")

    def test_points_only_mesh(self):
        obj = bpy.data.objects.new("Points", bpy.data.meshes.new("Points"))
        obj.data.vertices.add(3)
        bpy.context.scene.collection.objects.link(obj)
        helpers.select_only(obj)
        self.assert_reported("has no faces")

    def test_gl_method_without_its_device(self):
        # A GL method whose device is missing is reported. (This used to run the hybrid on
        # whatever GL there was and passed whether or not it failed; llvmpipe is always
        # there, so ask for an EGL device index that no machine here has.)
        prefs = helpers.addon_preferences()
        prefs.gl_device = "INDEX"
        prefs.gl_device_index = 63
        try:
            cube = helpers.cube()
            helpers.select_only(cube)
            self.assert_reported("does not exist", method="hybrid", resolution=8)
        finally:
            prefs.property_unset("gl_device")
            prefs.property_unset("gl_device_index")

    def test_rerun_failure_keeps_previous(self):
        cube = helpers.cube()
        helpers.select_only(cube)
        self.voxelize(voxel_size=0.25)
        before = self.scene_state()
        path = bpy.path.abspath(self.volumes()[0].data.filepath)
        stamp = os.path.getmtime(path)
        cube.data.clear_geometry()
        with self.assertRaises(RuntimeError):
            self.voxelize(voxel_size=0.25)
        self.assertEqual(self.scene_state(), before)
        self.assertEqual(os.path.getmtime(path), stamp)

    def test_grid_over_memory_budget(self):
        prefs = helpers.addon_preferences()
        prefs.memory_budget_mib = 16
        try:
            cube = helpers.cube()
            helpers.select_only(cube)
            # 8192^3 bits = 64 GiB: refused before allocating, reported, nothing changes.
            self.assert_reported("memory", resolution=8192)
        finally:
            prefs.property_unset("memory_budget_mib")
