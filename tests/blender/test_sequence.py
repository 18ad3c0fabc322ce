# SPDX-License-Identifier: GPL-3.0-or-later
"""A frame range writes one .vdb per frame and plays back as a volume sequence."""

import os

import bpy
import numpy as np

import helpers
from helpers import AddonTestCase


class SequenceTest(AddonTestCase):
    def test_frame_range_sequence(self):
        cube = helpers.cube(size=1.0)
        cube.location = (0, 0, 0)
        cube.keyframe_insert("location", frame=1)
        cube.location = (3, 0, 0)
        cube.keyframe_insert("location", frame=4)
        helpers.select_only(cube)
        bpy.context.scene.frame_set(2)
        self.assertEqual(self.voxelize(voxel_size=0.1, frame_start=1, frame_end=4), {"FINISHED"})
        self.assertEqual(bpy.context.scene.frame_current, 2)  # frame restored
        # Exactly the four frames' files: no staging (.partial) file is left behind.
        names = sorted(os.listdir(self.out))
        tag = names[0][len("Cube_voxels_") : -len("_0001.vdb")]  # this run's own tag
        self.assertEqual(names, [f"Cube_voxels_{tag}_{f:04d}.vdb" for f in range(1, 5)])

        (obj,) = self.volumes()
        volume = obj.data
        self.assertTrue(volume.is_sequence)
        self.assertEqual((volume.frame_start, volume.frame_duration), (1, 4))
        xs = []
        for frame in range(1, 5):
            bpy.context.scene.frame_set(frame)
            evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get()).data
            self.assertEqual(evaluated.grids.frame, frame)
            self.assertTrue(
                evaluated.grids.frame_filepath.endswith(f"Cube_voxels_{tag}_{frame:04d}.vdb"),
                evaluated.grids.frame_filepath,
            )
            centres = helpers.vdb_world_centres(bpy.path.abspath(evaluated.grids.frame_filepath))
            xs.append(centres[:, 0].mean())
            # Every frame shares one voxel size.
            _, size, _, _ = helpers.read_vdb(bpy.path.abspath(evaluated.grids.frame_filepath))
            np.testing.assert_allclose(size, [0.1] * 3, rtol=1e-6)
        self.assertTrue(all(b > a for a, b in zip(xs, xs[1:])), xs)  # the cube moves along +x
        self.assertAlmostEqual(xs[0], 0.0, delta=0.06)
        self.assertAlmostEqual(xs[-1], 3.0, delta=0.06)

    def test_sequence_starting_later(self):
        cube = helpers.cube(size=1.0)
        helpers.select_only(cube)
        self.voxelize(resolution=8, frame_start=10, frame_end=12)
        volume = self.volumes()[0].data
        for frame in (10, 11, 12):
            bpy.context.scene.frame_set(frame)
            evaluated = self.volumes()[0].evaluated_get(bpy.context.evaluated_depsgraph_get()).data
            self.assertTrue(
                evaluated.grids.frame_filepath.endswith(f"_{frame:04d}.vdb"),
                (frame, evaluated.grids.frame_filepath, volume.frame_offset),
            )

    def test_a_static_part_keeps_its_voxels_while_another_moves(self):
        """The lattice is fixed in world space (voxels do not swim): a static cube grouped
        with a sphere moving by fractions of a voxel on its left (so the bounds' minimum
        follows the sphere) has the same voxels in every frame's file."""
        cube = helpers.cube(size=0.8, location=(0.7, 0.0, 0.0))
        bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=2, radius=0.4, location=(-0.6, 0.0, 0.0))
        sphere = bpy.context.active_object
        for frame, x in ((1, -0.6), (2, -0.6 + 0.07), (3, -0.6 - 0.2)):
            sphere.location.x = x
            sphere.keyframe_insert("location", frame=frame)
        helpers.select_only(cube, sphere)
        bpy.context.scene.frame_set(1)
        self.assertEqual(self.voxelize(voxel_size=0.15, frame_start=1, frame_end=3), {"FINISHED"})
        path = bpy.path.abspath(self.volumes()[0].data.filepath)
        files = sorted(os.path.join(self.out, n) for n in os.listdir(self.out))
        self.assertEqual(len(files), 3, files)
        cube_voxels, all_voxels = [], []
        for file in files:
            coords, size, zero, _ = helpers.read_vdb(file)
            # World lattice index of each voxel: its min corner over the voxel size.
            world = np.rint((zero - size / 2) / size).astype(np.int64) + coords
            np.testing.assert_allclose((zero - size / 2) / size, np.rint((zero - size / 2) / size), atol=1e-6)
            cube_voxels.append({tuple(p) for p in world if p[0] * 0.15 >= 0.2})  # the cube: x 0.3..1.1
            all_voxels.append({tuple(p) for p in world})
        self.assertTrue(all_voxels[0] != all_voxels[1] and all_voxels[0] != all_voxels[2], "the sphere moved")
        self.assertTrue(cube_voxels[0])
        self.assertTrue(cube_voxels[0] == cube_voxels[1] == cube_voxels[2], "the cube's voxels swam")
        self.assertTrue(path.endswith("_0001.vdb"), path)
