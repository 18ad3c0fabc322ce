# SPDX-License-Identifier: GPL-3.0-or-later
"""Files and state across runs: what a re-run replaces, the artist's transform kept
relative to the source, parenting, new files per run (undo safety), and the session's own
folder for unsaved results. Cleaning unused files: test_clean_files.py."""

import hashlib
import math
import os
import tempfile

import bpy
import numpy as np
from mathutils import Vector

import helpers
from helpers import AddonTestCase


def file_of(obj):
    return bpy.path.abspath(obj.data.filepath)


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


class FilesAndStateTest(AddonTestCase):
    def test_unsaved_results_go_to_this_sessions_own_folder(self):
        from hyvox_blender.core import naming

        self.assertEqual(bpy.data.filepath, "")
        cube = helpers.cube()
        helpers.select_only(cube)
        self.voxelize(resolution=8, output_dir="")
        folder = os.path.dirname(file_of(self.volumes()[0]))
        self.assertEqual(folder, naming.unsaved_output_dir(create=False))
        # Not the shared temp folder of earlier versions, and made by mkdtemp for this session.
        self.assertNotEqual(folder, os.path.join(tempfile.gettempdir(), "hyvox_cache", "unsaved"))
        self.assertTrue(os.path.basename(folder).startswith("hyvox_cache_unsaved_"))

    def test_rerun_with_another_grouping_replaces_every_volume_of_those_objects(self):
        a, b = helpers.cube("A", 1.0), helpers.cube("B", 1.0, (3, 0, 0))
        helpers.select_only(a, b)
        self.voxelize(resolution=8)
        self.assertEqual([o.name for o in self.volumes()], ["A_and_1_more_voxels"])
        self.voxelize(resolution=8, separate=True)
        self.assertEqual([o.name for o in self.volumes()], ["A_voxels", "B_voxels"])
        helpers.select_only(b)
        self.voxelize(resolution=8)  # B alone: A's volume is not B's to replace
        self.assertEqual([o.name for o in self.volumes()], ["A_voxels", "B_voxels"])
        helpers.select_only(a, b)
        self.voxelize(resolution=8)
        self.assertEqual([o.name for o in self.volumes()], ["A_and_1_more_voxels"])
        self.assertEqual(len(bpy.data.volumes), 1)

    def test_parented_to_the_source_and_the_artists_edits_kept(self):
        from hyvox_blender.core import alignment

        cube = helpers.cube()
        helpers.select_only(cube)
        self.voxelize(voxel_size=0.25)
        (first,) = self.volumes()
        self.assertIs(first.parent, cube)
        np.testing.assert_allclose(np.array(first.matrix_world), np.array(first.matrix_basis), atol=1e-6)
        # The artist lifts, turns and scales the volume, then moves the source: it follows.
        first.location += Vector((0.0, 0.0, 2.0))
        first.rotation_euler.z = math.radians(30)
        first.scale = (1.0, 1.0, 2.0)
        bpy.context.view_layer.update()
        before = first.matrix_world.copy()
        cube.location = (5.0, 0.0, 0.0)
        bpy.context.view_layer.update()
        np.testing.assert_allclose(np.array(first.matrix_world.translation - before.translation), [5, 0, 0], atol=1e-6)

        self.voxelize(voxel_size=0.125)  # a re-run at the new place, with another voxel size
        (second,) = self.volumes()
        self.assertIs(second.parent, cube)
        version = bpy.app.version
        expected = Vector((0.0, 0.0, 2.0)) + Vector(alignment.object_offset(0.125, version))
        np.testing.assert_allclose(tuple(second.location), tuple(expected), atol=1e-6)
        self.assertAlmostEqual(second.rotation_euler.z, math.radians(30), places=6)
        self.assertEqual(tuple(second.scale), (1.0, 1.0, 2.0))
        # Its voxels are the source's where the source is now.
        centres = helpers.vdb_world_centres(file_of(second))
        self.assertAlmostEqual(float(centres[:, 0].mean()), 5.0, delta=0.07)

        second.parent = None
        self.voxelize(voxel_size=0.125, parent_to_source=False)
        self.assertIsNone(self.volumes()[0].parent)

    def test_rerun_writes_new_files_and_leaves_the_earlier_ones_intact(self):
        """So an undo that brings back the earlier volume finds its own voxels."""
        cube = helpers.cube()
        helpers.select_only(cube)
        self.voxelize(voxel_size=0.25)
        first_path = file_of(self.volumes()[0])
        first_digest = digest(first_path)
        self.voxelize(voxel_size=0.125)
        second_path = file_of(self.volumes()[0])
        self.assertNotEqual(second_path, first_path)
        self.assertEqual(digest(first_path), first_digest)
        self.assertNotEqual(digest(second_path), first_digest)
