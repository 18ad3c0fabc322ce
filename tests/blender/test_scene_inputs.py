# SPDX-License-Identifier: GPL-3.0-or-later
"""What gets voxelized: modifiers and world transforms applied, selections grouped as
asked, re-running replaces."""

import math

import bpy
import numpy as np

import helpers
from helpers import AddonTestCase


def centres(obj):
    return helpers.vdb_world_centres(bpy.path.abspath(obj.data.filepath))


class SceneInputTest(AddonTestCase):
    def test_modifiers_applied(self):
        cube = helpers.cube()
        helpers.select_only(cube)
        self.voxelize(voxel_size=0.1)
        plain = len(centres(self.volumes()[0]))
        modifier = cube.modifiers.new("Subdivision", "SUBSURF")
        modifier.levels = 2
        self.voxelize(voxel_size=0.1)
        (obj,) = self.volumes()
        smooth = centres(obj)
        # Subdivision rounds the cube towards a sphere: fewer, inner voxels.
        self.assertNotEqual(len(smooth), plain)
        self.assertLess(np.abs(smooth).max(), 1.0)

    def test_world_transform_applied(self):
        cube = helpers.cube(size=2.0)
        cube.location = (5.0, -3.0, 2.0)
        cube.rotation_euler = (0.0, 0.0, math.radians(45))
        cube.scale = (1.0, 1.0, 0.5)
        helpers.select_only(cube)
        self.voxelize(voxel_size=0.1)
        c = centres(self.volumes()[0])
        lo, hi = c.min(axis=0) - 0.05, c.max(axis=0) + 0.05
        r = math.sqrt(2.0)  # half-diagonal of the rotated square
        np.testing.assert_allclose(lo, [5 - r, -3 - r, 1.5], atol=0.1 + 1e-6)
        np.testing.assert_allclose(hi, [5 + r, -3 + r, 2.5], atol=0.1 + 1e-6)
        # Rotated 45 degrees, the square is a diamond: |dx| + |dy| <= sqrt(2), so the corners
        # of its bounding square stay empty (up to one voxel diagonal).
        manhattan = np.abs(c[:, 0] - 5) + np.abs(c[:, 1] + 3)
        self.assertLessEqual(manhattan.max(), r + 0.1 + 1e-6)

    def test_several_objects_one_volume(self):
        a = helpers.cube("A", 1.0, (0, 0, 0))
        b = helpers.cube("B", 1.0, (3, 0, 0))
        helpers.select_only(a, b)
        self.voxelize(voxel_size=0.1, separate=False)
        (obj,) = self.volumes()
        self.assertEqual(obj.name, "A_and_1_more_voxels")
        c = centres(obj)
        self.assertTrue(np.any(c[:, 0] < 0.6) and np.any(c[:, 0] > 2.4))

    def test_several_objects_one_volume_each(self):
        a = helpers.cube("A", 1.0, (0, 0, 0))
        b = helpers.cube("B", 1.0, (3, 0, 0))
        helpers.select_only(a, b)
        self.voxelize(voxel_size=0.1, separate=True)
        self.assertEqual([o.name for o in self.volumes()], ["A_voxels", "B_voxels"])
        self.assertLess(centres(bpy.data.objects["A_voxels"])[:, 0].max(), 0.6)
        self.assertGreater(centres(bpy.data.objects["B_voxels"])[:, 0].min(), 2.4)

    def test_rerun_replaces(self):
        cube = helpers.cube()
        helpers.select_only(cube)
        self.voxelize(voxel_size=0.25)
        first = self.volumes()[0]
        first.data.materials[0].name = "Tweaked"
        self.voxelize(voxel_size=0.125)
        (obj,) = self.volumes()
        self.assertEqual(obj.name, "Cube_voxels")
        self.assertEqual(len(bpy.data.volumes), 1)
        self.assertAlmostEqual(obj["hyvox_voxel_size"], 0.125)
        self.assertEqual(obj.data.materials[0].name, "Tweaked")  # the artist's material stays

    def test_scene_settings_used_and_overridden(self):
        cube = helpers.cube()
        helpers.select_only(cube)
        settings = bpy.context.scene.hyvox
        settings.size_mode = "RESOLUTION"
        settings.resolution = 4
        settings.output_dir = self.out
        bpy.ops.object.hyvox_voxelize(method="cpu")
        self.assertAlmostEqual(self.volumes()[0]["hyvox_voxel_size"], 0.5)
        bpy.ops.object.hyvox_voxelize(method="cpu", resolution=8)
        self.assertAlmostEqual(self.volumes()[0]["hyvox_voxel_size"], 0.25)
