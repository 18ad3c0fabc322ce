# SPDX-License-Identifier: GPL-3.0-or-later
"""Signed Distance (the sdf attribute): the volume holds a float grid `sdf` beside `density`,
its values the module's, and the material still reads `density`."""

import bpy
import numpy as np

import helpers
from helpers import AddonTestCase


def uv_sphere(radius=1.0):
    bpy.ops.mesh.primitive_uv_sphere_add(segments=32, ring_count=16, radius=radius, location=(0, 0, 0))
    return bpy.context.active_object


class SignedDistanceTest(AddonTestCase):
    def test_volume_holds_an_sdf_grid_beside_density(self):
        sphere = uv_sphere()
        helpers.select_only(sphere)
        self.assertEqual(self.voxelize(voxel_size=0.1, signed_distance=True), {"FINISHED"})
        (obj,) = self.volumes()
        volume = obj.data
        self.assertTrue(volume.grids.load(), volume.grids.error_message)
        self.assertEqual({g.name for g in volume.grids}, {"density", "sdf"})
        self.assertEqual(volume.grids["sdf"].data_type, "FLOAT")
        # The file's level set is the module's for the same triangles.
        export = helpers.addon("blender.export.sources").object_triangles
        vertices, triangles = export(sphere, bpy.context.evaluated_depsgraph_get())
        grid = helpers.hyvox_module().voxelize(vertices, triangles, voxel_size=0.1, method="cpu", attributes="sdf")
        coords, size, zero, _ = helpers.read_vdb(bpy.path.abspath(volume.filepath), "sdf")
        ijk, distance = grid.sdf()
        self.assertEqual(len(coords), len(ijk))
        np.testing.assert_allclose(
            helpers.sorted_rows(zero + coords * size),
            helpers.sorted_rows(np.asarray(grid.origin) + (ijk + 0.5) * grid.voxel_size),
            atol=1e-6,
        )
        self.assertLess(np.abs(distance).max(), 3 * 0.1)
        self.assertGreater((distance < 0).sum(), 100)
        # The material renders the density, as without the sdf.
        material = obj.active_material
        shader = next(n for n in material.node_tree.nodes if n.type == "PRINCIPLED_VOLUME")
        attribute = (
            shader.inputs["Density Attribute"].default_value
            if "Density Attribute" in shader.inputs
            else shader.density_attribute
        )
        self.assertEqual(attribute, "density")

    def test_off_by_default(self):
        sphere = uv_sphere()
        helpers.select_only(sphere)
        self.assertEqual(self.voxelize(voxel_size=0.1), {"FINISHED"})
        (obj,) = self.volumes()
        self.assertTrue(obj.data.grids.load(), obj.data.grids.error_message)
        self.assertEqual({g.name for g in obj.data.grids}, {"density"})
