# SPDX-License-Identifier: GPL-3.0-or-later
"""Mode Solid (the default, like Mesh to Volume's Fill Volume) fills the inside: the
Volume holds exactly the module's solid voxels, and renders as a filled body: seen through
its middle a filled sphere absorbs far more light than its hollow shell. The render is kept
as a PNG in $HYVOX_RENDER_DIR when that is set (to look at it). With Colour, the inside takes
the colour of the surface around it: the `color` grid has the density's voxels and tiles."""

import os

import bpy
import numpy as np

import helpers
from helpers import AddonTestCase
from test_colour import GREEN, RED, face_halves, split_cube
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
        self.assertEqual(
            bpy.ops.object.hyvox_voxelize(output_dir=self.out, method="cpu", resolution=32, **kw), {"FINISHED"}
        )
        (volume,) = self.volumes()
        return obj, volume

    def test_default_is_solid_and_equals_the_module(self):
        self.assertEqual(bpy.context.scene.hyvox.mode, "solid")
        obj, volume = self.voxelize_sphere()
        vertices, triangles = sphere_arrays(obj)
        solid = helpers.hyvox_module().voxelize(vertices, triangles, resolution=32, mode="solid")
        surface = helpers.hyvox_module().voxelize(vertices, triangles, resolution=32)
        got = helpers.vdb_world_centres(bpy.path.abspath(volume.data.filepath))
        self.assertEqual(len(got), solid.voxel_count)
        self.assertGreater(solid.voxel_count, 2 * surface.voxel_count)
        expected = np.array(solid.origin) + (solid.coords() + 0.5) * solid.voxel_size
        np.testing.assert_allclose(
            helpers.sorted_rows(got), helpers.sorted_rows(expected), atol=1e-5 * solid.voxel_size + 1e-7
        )

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
        return pixels[mid - 3 : mid + 3, mid - 3 : mid + 3].mean()

    def test_filled_sphere_renders_as_a_body(self):
        # setup_render's absorber: ln 2 per unit of density and length. Through the middle:
        # the filled sphere is 2 units deep (exp(-2 ln 2) = 1/4 before the PNG's sRGB curve),
        # the shell two walls of a voxel or two.
        _, filled = self.voxelize_sphere()
        solid = self.centre_transmittance(filled, "filled_sphere")
        helpers.clear_scene()
        _, hollow = self.voxelize_sphere(mode="conservative")
        shell = self.centre_transmittance(hollow, "hollow_sphere")
        print("centre transmittance (sRGB): filled %.3f, hollow %.3f" % (solid, shell))
        self.assertLess(solid, 0.6)
        self.assertGreater(shell, 0.85)
        self.assertGreater(shell - solid, 0.3)

    def test_colour_when_solid_colours_every_voxel(self):
        import pyopenvdb as vdb

        obj = split_cube()
        mesh = obj.data
        attribute = mesh.color_attributes.new("Col", "FLOAT_COLOR", "CORNER")
        per_loop = np.repeat(face_halves(mesh), [p.loop_total for p in mesh.polygons])
        attribute.data.foreach_set("color", np.where(per_loop[:, None], RED, GREEN).astype(np.float32).ravel())
        helpers.select_only(obj)
        self.assertEqual(bpy.context.scene.hyvox.mode, "solid")
        self.assertEqual(
            bpy.ops.object.hyvox_voxelize(output_dir=self.out, method="cpu", voxel_size=0.0625, color=True),
            {"FINISHED"},
        )
        (volume,) = self.volumes()
        path = bpy.path.abspath(volume.data.filepath)
        grids = {name: vdb.read(path, name) for name in ("density", "color")}

        def tiles(grid):
            return sorted((tuple(i.min), tuple(i.max)) for i in grid.citerOnValues() if i.count > 1)

        density, color = grids["density"], grids["color"]
        self.assertEqual(color.activeVoxelCount(), density.activeVoxelCount())
        self.assertEqual(tiles(color), tiles(density))
        self.assertTrue(tiles(color), "two 24-voxel solid cubes have whole-brick tiles")
        # Solid: far more than the two shells (24³ each, 6 · 24² on the surface).
        self.assertGreater(density.activeVoxelCount(), 2 * 20**3)
        # Each cube's inside has its surface's one colour, tiles included.
        to_world = density.transform.indexToWorld
        for item in color.citerOnValues():
            centre = np.add(item.min, item.max) / 2.0
            expected = RED if to_world(tuple(centre))[0] < 0 else GREEN
            np.testing.assert_allclose(item.value, expected[:3], atol=1e-5)
        volume_material = helpers.addon("blender.volume.material")
        nodes = volume.data.materials[0].node_tree.nodes
        self.assertEqual(nodes[volume_material.COLOR].attribute_name, "color")
        shader = next(n for n in nodes if n.type == "PRINCIPLED_VOLUME")
        self.assertEqual(shader.inputs["Color"].links[0].from_node.name, volume_material.ALBEDO)
