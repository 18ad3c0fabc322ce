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
            # 8192^3 bits = 64 GiB: refused before allocating, reported, nothing changes; the
            # setting named where the artist finds it (the preference's own name).
            self.assertEqual(prefs.bl_rna.properties["memory_budget_mib"].name, "Memory Budget")
            self.assert_reported("memory budget of 16 MiB (Preferences \u25b8 Memory Budget)", resolution=8192)
        finally:
            prefs.property_unset("memory_budget_mib")

    def test_a_vertex_that_is_not_a_number_is_named_in_its_object(self):
        # The second object of a group: its own name and index, not the merged mesh's.
        first = helpers.cube("First")
        second = helpers.cube("Second", 1.0, (3, 0, 0))
        for value, fragment in (
            (float("nan"), "not a number or infinite"),
            (float("inf"), "infinite (Blender stores Inf as 3.4e+38)"),
        ):
            with self.subTest(value=value):
                second.data.vertices[5].co.z = value
                helpers.select_only(first, second)
                self.assert_reported("Second: vertex 5 is at ", resolution=8)
                self.assert_reported(fragment, resolution=8)
                second.data.vertices[5].co.z = 0.5

    def test_a_few_far_vertices_are_warned_about(self):
        operators = helpers.addon("blender.operators")
        h = 1.0
        corners = [(x, y, z) for x in (-h, h) for y in (-h, h) for z in (-h, h)]
        quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
        cube = helpers.mesh_object("Cube", corners + [(500.0, 0.0, 0.0)], quads)
        mesh = cube.data
        mesh.polygons[0].vertices = (0, 1, 8, 2)  # one face reaches the stray vertex
        helpers.select_only(cube)
        warnings = []
        original = operators._Run.warn
        operators._Run.warn = lambda run, text: (warnings.append(text), original(run, text))
        try:
            self.assertEqual(self.voxelize(resolution=16), {"FINISHED"})  # still made
            far = [w for w in warnings if "far from the rest" in w]
            self.assertEqual(len(far), 1, warnings)
            self.assertTrue(far[0].startswith("Cube: 1 vertex far from the rest"), far[0])
            warnings.clear()
            mesh.vertices[8].co = (-1.0, 0.0, 0.0)  # back near the rest: no warning
            self.assertEqual(self.voxelize(resolution=16), {"FINISHED"})
            self.assertFalse([w for w in warnings if "far from the rest" in w], warnings)
        finally:
            operators._Run.warn = original
