# SPDX-License-Identifier: GPL-3.0-or-later
"""Output as Blocks in Blender: a mesh with one cube per voxel and only exposed faces (face
counts against a dense numpy count of the .vdb's voxels read with pyopenvdb), per-face
colours from the voxels' colours, a .vox beside the .vdb, and re-runs replacing across
output kinds."""

import os
import struct
from collections import Counter

import bpy
import numpy as np

import helpers
from helpers import AddonTestCase


def dense_exposed_faces(ijk):
    low = ijk.min(axis=0)
    occ = np.zeros(ijk.max(axis=0) - low + 3, bool)
    occ[tuple((ijk - low + 1).T)] = True
    return sum(int(np.count_nonzero(occ & ~np.roll(occ, step, axis))) for axis in range(3) for step in (1, -1))


def vox_voxel_count(path):
    """Sum of the XYZI chunks' voxel counts, walking the chunk list of MAIN."""
    with open(path, "rb") as f:
        data = f.read()
    assert data[:4] == b"VOX "
    offset, total = 20, 0
    while offset < len(data):
        tag, content, children = data[offset : offset + 4], *struct.unpack_from("<ii", data, offset + 4)
        if tag == b"XYZI":
            total += struct.unpack_from("<i", data, offset + 12)[0]
        offset += 12 + content + children
    return total


class BlocksOutputTest(AddonTestCase):
    def test_blocks_have_only_the_exposed_faces(self):
        bunny = helpers.bunny()
        helpers.select_only(bunny)
        self.assertEqual(self.voxelize(resolution=40, output="BLOCKS", export_vox=True), {"FINISHED"})
        obj = bpy.data.objects["Bunny_blocks"]
        self.assertEqual(obj.type, "MESH")
        operators = helpers.addon("blender.operators")
        (record,) = operators.last_run_record["volumes"]
        vdb = record["files"][0]
        ijk, size, zero, _ = helpers.read_vdb(vdb)
        mesh = obj.data
        self.assertEqual(len(mesh.polygons), dense_exposed_faces(ijk))
        self.assertEqual(record["blocks_faces"], len(mesh.polygons))
        self.assertTrue(all(p.loop_total == 4 for p in mesh.polygons))
        # The blocks cover exactly the voxels' boxes: index i spans [centre - s/2, centre + s/2].
        co = np.empty(len(mesh.vertices) * 3, np.float32)
        mesh.vertices.foreach_get("co", co)
        co = co.reshape(-1, 3)
        np.testing.assert_allclose(co.min(axis=0), zero + ijk.min(axis=0) * size - size / 2, atol=1e-4)
        np.testing.assert_allclose(co.max(axis=0), zero + ijk.max(axis=0) * size + size / 2, atol=1e-4)
        # Closed: every edge is shared by an even number of faces (2, or 4 where two voxels
        # touch along an edge only).
        uses = Counter(key for p in mesh.polygons for key in p.edge_keys)
        self.assertTrue(all(n % 2 == 0 for n in uses.values()))
        self.assertEqual(record["vox_files"], [os.path.splitext(vdb)[0] + ".vox"])
        self.assertEqual(vox_voxel_count(record["vox_files"][0]), len(ijk))

        # A re-run as a volume replaces the blocks of the same object.
        self.voxelize(resolution=40)
        self.assertNotIn("Bunny_blocks", bpy.data.objects)
        self.assertEqual([o.name for o in bpy.data.objects if "hyvox_key" in o], ["Bunny_voxels"])

    def test_face_colours_from_the_voxels(self):
        backend = helpers.addon("core.backend")
        cube = helpers.cube()
        helpers.select_only(cube)
        real = backend.voxel_colors

        def colors_from_position(grid):  # stands in for the colour grid: a known colour per voxel
            return (grid.coords() % 7 / 6.0).astype(np.float32)

        backend.voxel_colors = colors_from_position
        try:
            self.voxelize(resolution=12, output="BLOCKS")
        finally:
            backend.voxel_colors = real
        mesh = bpy.data.objects["Cube_blocks"].data
        attribute = mesh.color_attributes["Col"]
        self.assertEqual(attribute.domain, "CORNER")
        corners = np.empty(len(mesh.loops) * 4, np.float32)
        attribute.data.foreach_get("color", corners)
        corners = corners.reshape(-1, 4, 4)  # (face, corner, rgba): quads, loops in face order
        self.assertTrue(np.all(corners == corners[:, :1]))  # one colour per face
        rgba = corners[:, 0]
        operators = helpers.addon("blender.operators")
        ijk, size, zero, _ = helpers.read_vdb(operators.last_run_record["volumes"][0]["files"][0])
        origin = zero - size / 2
        for polygon, color in zip(mesh.polygons, rgba.reshape(-1, 4)):
            # The voxel behind the face: half a voxel inwards from its centre.
            inside = np.floor((np.array(polygon.center) - np.array(polygon.normal) * size[0] / 2 - origin) / size)
            np.testing.assert_allclose(color[:3], inside.astype(int) % 7 / 6.0, atol=1e-6)

    def test_blocks_are_flat_shaded(self):
        """Every face flat (a new face is smooth from Blender 4.1 on), so a render shows one
        shade per face direction: Workbench's studio light depends on the normal only, and
        with anti-aliasing off the blocks of a sphere, seen along an axis, take at most the
        six values of the six directions; smooth shading interpolates normals across faces
        and makes many."""
        bpy.ops.mesh.primitive_uv_sphere_add(radius=1.0, segments=16, ring_count=8)
        source = bpy.context.active_object
        helpers.select_only(source)
        self.assertEqual(self.voxelize(resolution=10, output="BLOCKS"), {"FINISHED"})
        blocks = bpy.data.objects["Sphere_blocks"]
        smooth = np.empty(len(blocks.data.polygons), bool)
        blocks.data.polygons.foreach_get("use_smooth", smooth)
        self.assertFalse(smooth.any(), f"{smooth.sum()} of {len(smooth)} faces smooth")
        source.hide_render = True
        scene = bpy.context.scene
        camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
        camera.data.type, camera.data.ortho_scale = "ORTHO", 2.6
        camera.location, camera.rotation_euler = (4.0, -6.0, 3.0), (1.1, 0.0, 0.6)
        scene.collection.objects.link(camera)
        scene.camera = camera
        scene.render.engine = "BLENDER_WORKBENCH"
        scene.display.shading.light = "STUDIO"
        scene.display.shading.color_type = "SINGLE"
        scene.display.render_aa = "OFF"
        scene.render.resolution_x = scene.render.resolution_y = 64
        scene.render.resolution_percentage = 100
        scene.render.film_transparent = True
        scene.render.image_settings.file_format = "OPEN_EXR"
        scene.render.image_settings.color_depth = "32"
        scene.view_settings.view_transform = "Standard"
        pixels = helpers.render_pixels(os.path.join(self.out, "blocks.exr"))
        shown = pixels[..., 3] > 0.999
        shades = np.unique(np.round(pixels[shown][:, :3], 3), axis=0)
        print(f"blocks: {shown.sum()} pixels in {len(shades)} shades")
        self.assertGreater(shown.sum(), 500)
        self.assertLessEqual(len(shades), 6, shades)

    def test_blocks_refuse_a_frame_range(self):
        cube = helpers.cube()
        helpers.select_only(cube)
        with self.assertRaises(RuntimeError) as caught:
            self.voxelize(resolution=8, output="BLOCKS", frame_start=1, frame_end=3)
        self.assertIn("turn off the frame range", str(caught.exception))
