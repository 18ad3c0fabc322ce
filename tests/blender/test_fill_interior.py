# SPDX-License-Identifier: GPL-3.0-or-later
"""Fill Interior (on by default, like Mesh to Volume's Fill Volume) makes the run solid: the
Volume holds exactly the module's solid voxels, and renders as a filled body: seen through
its middle a filled sphere absorbs far more light than its hollow shell. The render is kept
as a PNG in $HYVOX_RENDER_DIR when that is set (to look at it)."""
import math
import os

import bpy
import numpy as np

import helpers
from helpers import AddonTestCase
from test_render_alignment import PIXELS, setup_render


def sphere():
    bpy.ops.mesh.primitive_uv_sphere_add(radius=1.0, segments=32, ring_count=16, location=(0, 0, 0))
    return bpy.context.active_object


def sphere_arrays(obj):
    mesh = obj.data
    mesh.calc_loop_triangles()
    vertices = np.array([v.co[:] for v in mesh.vertices], np.float32)
    triangles = np.array([t.vertices[:] for t in mesh.loop_triangles], np.uint32)
    return vertices, triangles


class FillInteriorTest(AddonTestCase):
    def voxelize_sphere(self, **kw):
        obj = sphere()
        helpers.select_only(obj)
        self.assertEqual(bpy.ops.object.hyvox_voxelize(output_dir=self.out, method="cpu", resolution=32, **kw),
                         {"FINISHED"})
        (volume,) = self.volumes()
        return obj, volume

    def test_default_is_solid_and_equals_the_module(self):
        self.assertTrue(bpy.context.scene.hyvox.fill_interior)
        obj, volume = self.voxelize_sphere()
        vertices, triangles = sphere_arrays(obj)
        solid = helpers.hyvox_module().voxelize(vertices, triangles, resolution=32, mode="solid")
        surface = helpers.hyvox_module().voxelize(vertices, triangles, resolution=32)
        got = helpers.vdb_world_centres(bpy.path.abspath(volume.data.filepath))
        self.assertEqual(len(got), solid.voxel_count)
        self.assertGreater(solid.voxel_count, 2 * surface.voxel_count)
        expected = np.array(solid.origin) + (solid.coords() + 0.5) * solid.voxel_size
        np.testing.assert_allclose(helpers.sorted_rows(got), helpers.sorted_rows(expected),
                                   atol=1e-5 * solid.voxel_size + 1e-7)

    def centre_transmittance(self, volume, name):
        bpy.data.objects["Sphere"].hide_render = True
        scene = bpy.context.scene
        setup_render(scene, volume, "CYCLES")
        scene.render.image_settings.file_format = "PNG"
        scene.render.image_settings.color_depth = "8"
        folder = os.environ.get("HYVOX_RENDER_DIR", self.out)
        pixels = helpers.render_pixels(os.path.join(folder, name + ".png"))[:, :, 0]
        self.assertEqual(pixels.shape, (PIXELS, PIXELS))
        mid = PIXELS // 2
        return pixels[mid - 3:mid + 3, mid - 3:mid + 3].mean()

    def test_filled_sphere_renders_as_a_body(self):
        # setup_render's absorber: ln 2 per unit of density and length. Through the middle:
        # the filled sphere is 2 units deep (exp(-2 ln 2) = 1/4 before the PNG's sRGB curve),
        # the shell two walls of a voxel or two.
        _, filled = self.voxelize_sphere()
        solid = self.centre_transmittance(filled, "filled_sphere")
        helpers.clear_scene()
        _, hollow = self.voxelize_sphere(fill_interior=False)
        shell = self.centre_transmittance(hollow, "hollow_sphere")
        print("centre transmittance (sRGB): filled %.3f, hollow %.3f" % (solid, shell))
        self.assertLess(solid, 0.6)
        self.assertGreater(shell, 0.85)
        self.assertGreater(shell - solid, 0.3)
