# SPDX-License-Identifier: GPL-3.0-or-later
"""The Volume's voxels are exactly the module's voxels, in the right place."""

import os
import subprocess
import tempfile

import bpy
import numpy as np

import helpers
from helpers import AddonTestCase


def module_centres(vertices, triangles, **kw):
    """World voxel centres the module gives for a world-space mesh."""
    grid = helpers.hyvox_module().voxelize(vertices, triangles, **kw)
    origin = np.asarray(grid.origin, np.float64)
    return origin + (grid.coords().astype(np.float64) + 0.5) * grid.voxel_size, grid


class VoxelSetTest(AddonTestCase):
    def check_volume(self, obj):
        volume = obj.data
        self.assertTrue(volume.grids.load(), volume.grids.error_message)
        grid = volume.grids.get("density")
        self.assertIsNotNone(grid, [g.name for g in volume.grids])
        self.assertEqual(grid.data_type, "FLOAT")
        return bpy.path.abspath(volume.filepath)

    def test_bunny_equals_module(self):
        bunny = helpers.bunny()
        helpers.select_only(bunny)
        self.assertEqual(self.voxelize(resolution=128), {"FINISHED"})
        (obj,) = self.volumes()
        self.assertEqual(obj.name, "Bunny_voxels")
        path = self.check_volume(obj)
        self.assertTrue(os.path.isfile(path))
        # The file's own arrays (the bunny sits at the identity transform), not the
        # add-on's export, so a wrong export cannot agree with itself.
        vertices, triangles = helpers.bunny_arrays()
        expected, grid = module_centres(vertices, triangles, resolution=128, method="cpu")
        got = helpers.vdb_world_centres(path)
        self.assertEqual(len(got), len(expected))
        np.testing.assert_allclose(
            helpers.sorted_rows(got), helpers.sorted_rows(expected), atol=1e-5 * grid.voxel_size + 1e-7
        )
        self.assertAlmostEqual(obj["hyvox_voxel_size"], grid.voxel_size, places=9)

    def test_bunny_equals_the_reference_oracle(self):
        # The brute-force double-precision method of the build tree's own hyvox command (not
        # the add-on's module, which may be a release built by another compiler).
        build_dir = os.environ.get("HYVOX_BUILD_DIR", "")
        command = os.path.join(build_dir, "hyvox")
        self.assertTrue(os.access(command, os.X_OK), f"no build tree hyvox command in {build_dir!r}")
        bunny = helpers.bunny()
        helpers.select_only(bunny)
        self.assertEqual(self.voxelize(resolution=96, method="cpu"), {"FINISHED"})
        (obj,) = self.volumes()
        with tempfile.TemporaryDirectory(prefix="hyvox-oracle-") as tmp:
            oracle = os.path.join(tmp, "oracle.vdb")
            mesh = os.path.join(helpers.MESH_DIR, "bunny_stanford_69k.ply")
            subprocess.run(
                [command, "voxelize", mesh, "-o", oracle, "-q", "--resolution", "96", "--mode", "conservative"]
                + ["--method", "reference"],
                check=True,
                timeout=300,
            )
            expected = helpers.vdb_world_centres(oracle)
        got = helpers.vdb_world_centres(self.check_volume(obj))
        self.assertGreater(len(expected), 1000)
        self.assertEqual(len(got), len(expected))
        np.testing.assert_allclose(
            helpers.sorted_rows(got), helpers.sorted_rows(expected), atol=1e-5 * obj["hyvox_voxel_size"] + 1e-7
        )

    def test_cube_covers_its_bounds(self):
        cube = helpers.cube(size=2.0)
        helpers.select_only(cube)
        size = 0.25
        self.assertEqual(self.voxelize(voxel_size=size), {"FINISHED"})
        (obj,) = self.volumes()
        path = self.check_volume(obj)
        centres = helpers.vdb_world_centres(path)
        np.testing.assert_allclose(centres.min(axis=0) - size / 2, [-1, -1, -1], atol=1e-6)
        np.testing.assert_allclose(centres.max(axis=0) + size / 2, [1, 1, 1], atol=1e-6)
        # A hollow shell: 8^3 minus the 6^3 interior.
        self.assertEqual(len(centres), 8**3 - 6**3)
        object_triangles = helpers.addon("blender.export.sources").object_triangles
        vertices, triangles = object_triangles(cube, bpy.context.evaluated_depsgraph_get())
        expected, _ = module_centres(vertices, triangles, voxel_size=size, method="cpu")
        np.testing.assert_allclose(helpers.sorted_rows(centres), helpers.sorted_rows(expected), atol=1e-6)

    def test_object_carries_half_voxel_correction(self):
        alignment = helpers.addon("core.alignment")
        cube = helpers.cube()
        helpers.select_only(cube)
        self.voxelize(voxel_size=0.25)
        (obj,) = self.volumes()
        np.testing.assert_allclose(tuple(obj.location), alignment.object_offset(0.25, bpy.app.version))
        material = obj.data.materials[0]
        self.assertTrue(any(n.bl_idname == "ShaderNodeVolumePrincipled" for n in material.node_tree.nodes))
