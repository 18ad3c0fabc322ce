# SPDX-License-Identifier: GPL-3.0-or-later
"""Colour voxels from Blender (issue 12): the colour each object's material shows (render
colour attribute, Base Color image, per-slot Base Color) reaches the .vdb's `color` grid
(read back with pyopenvdb), the volume's material shows it, Blocks carry it, and a render
of the volume has the mesh's colours."""

import os

import bpy
import numpy as np

import helpers
from helpers import AddonTestCase

RED = (0.6, 0.05, 0.02, 1.0)  # linear
GREEN = (0.03, 0.5, 0.1, 1.0)
SIZE = 0.125  # voxel size: 16 voxels across the 2-unit cube


def split_cube(name="Split"):
    """Two 1.5-unit cubes in one mesh, one each side of x = 0 with a gap of 4 voxels, so
    every voxel and every vertex lies in one half: x < 0 or x > 0."""
    h = 0.75
    corners = np.array(
        [(-h, -h, -h), (h, -h, -h), (h, h, -h), (-h, h, -h), (-h, -h, h), (h, -h, h), (h, h, h), (-h, h, h)]
    )
    faces = np.array([(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)])
    vertices = np.concatenate([corners - (1.0, 0, 0), corners + (1.0, 0, 0)])
    return helpers.mesh_object(name, vertices, np.concatenate([faces, faces + 8]))


def face_halves(mesh):
    """(F,) bool: the face lies in the x < 0 half."""
    centres = np.empty(len(mesh.polygons) * 3, np.float32)
    mesh.polygons.foreach_get("center", centres)
    return centres.reshape(-1, 3)[:, 0] < 0


def colour_vdb(path):
    """(world centres (K,3), linear colours (K,3)) of the .vdb's `color` grid."""
    import pyopenvdb as vdb

    grid = vdb.read(path, "color")
    ijk, values = [], []
    for item in grid.citerOnValues():
        assert item.count == 1, "colour tiles are not expected on a surface"
        ijk.append(item.min)
        values.append(item.value)
    ijk = np.array(ijk, np.float64)
    size = np.array(grid.transform.voxelSize())
    zero = np.array(grid.transform.indexToWorld((0, 0, 0)))
    return zero + ijk * size, np.array(values, np.float64)  # the transform maps ijk to voxel centres


def read_vox(path):
    """(XYZI records (K,4) uint8 of the one model, RGBA palette (256,4)) of a .vox file."""
    import struct

    with open(path, "rb") as f:
        data = f.read()
    offset, models, palette = 20, [], None
    while offset < len(data):
        tag, content, children = data[offset : offset + 4], *struct.unpack_from("<ii", data, offset + 4)
        body = data[offset + 12 : offset + 12 + content]
        if tag == b"XYZI":
            count = struct.unpack_from("<i", body)[0]
            models.append(np.frombuffer(body[4 : 4 + 4 * count], np.uint8).reshape(-1, 4))
        elif tag == b"RGBA":
            palette = np.frombuffer(body, np.uint8).reshape(256, 4)
        offset += 12 + content + children
    assert len(models) == 1 and palette is not None
    return models[0], palette


def principled_material(name, base_color):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    tree = material.node_tree
    tree.nodes.clear()
    shader = tree.nodes.new("ShaderNodeBsdfPrincipled")
    shader.inputs["Base Color"].default_value = base_color
    tree.links.new(shader.outputs["BSDF"], tree.nodes.new("ShaderNodeOutputMaterial").inputs["Surface"])
    return material


class _ColourCase(AddonTestCase):
    def voxelize(self, **kw):
        kw.setdefault("color", True)  # (the default: see test_defaults_and_rerun_material)
        return super().voxelize(**kw)


class ColourTest(_ColourCase):
    def assert_halves(self, path, left, right, tol=0.01):
        """Every voxel has the colour of its half."""
        centres, colours = colour_vdb(path)
        density, *_ = helpers.read_vdb(path)
        self.assertEqual(len(centres), len(density), "a colour for every occupied voxel")
        for side, expected in ((centres[:, 0] < 0, left), (centres[:, 0] > 0, right)):
            self.assertGreater(side.sum(), 100)
            np.testing.assert_allclose(colours[side], np.tile(expected[:3], (side.sum(), 1)), atol=tol, rtol=0)

    def volume_file(self):
        (obj,) = self.volumes()
        return bpy.path.abspath(obj.data.filepath), obj

    def test_colour_attribute_byte_corner_and_float_point(self):
        for data_type, domain in (("BYTE_COLOR", "CORNER"), ("FLOAT_COLOR", "POINT")):
            with self.subTest(data_type=data_type, domain=domain):
                helpers.clear_scene()
                obj = split_cube()
                mesh = obj.data
                left = face_halves(mesh)
                # Another attribute first, so the render one must be picked, not the first.
                decoy = mesh.color_attributes.new("Decoy", "FLOAT_COLOR", "POINT")
                decoy.data.foreach_set("color", np.ones(len(mesh.vertices) * 4, np.float32))
                attribute = mesh.color_attributes.new("Col", data_type, domain)
                mesh.color_attributes.render_color_index = list(mesh.color_attributes).index(attribute)
                if domain == "CORNER":
                    per_loop = np.repeat(left, [p.loop_total for p in mesh.polygons])
                    values = np.where(per_loop[:, None], RED, GREEN)
                else:
                    co = np.empty(len(mesh.vertices) * 3, np.float32)
                    mesh.vertices.foreach_get("co", co)
                    values = np.where((co.reshape(-1, 3)[:, 0] < 0)[:, None], RED, GREEN)
                attribute.data.foreach_set("color", np.asarray(values, np.float32).ravel())
                helpers.select_only(obj)
                self.assertEqual(self.voxelize(voxel_size=SIZE), {"FINISHED"})
                path, volume = self.volume_file()
                # Bytes hold sRGB-encoded colours: a linear value comes back within rounding.
                self.assert_halves(path, RED, GREEN, tol=0.01 if data_type == "BYTE_COLOR" else 1e-5)
                volume_material = helpers.addon("blender.volume.material")
                nodes = volume.data.materials[0].node_tree.nodes
                self.assertEqual(nodes[volume_material.COLOR].attribute_name, "color")
                shader = next(n for n in nodes if n.type == "PRINCIPLED_VOLUME")
                self.assertEqual(shader.inputs["Color"].links[0].from_node.name, volume_material.ALBEDO)

    def test_per_slot_base_colours_and_combined_with_an_attribute(self):
        obj = split_cube()
        mesh = obj.data
        mesh.materials.append(principled_material("Red", RED))
        mesh.materials.append(principled_material("Green", GREEN))
        mesh.polygons.foreach_set("material_index", np.where(face_halves(mesh), 0, 1).astype(np.int32))
        helpers.select_only(obj)
        self.assertEqual(self.voxelize(voxel_size=SIZE), {"FINISHED"})
        self.assert_halves(self.volume_file()[0], RED, GREEN, tol=1e-5)

        # One volume of two objects with different sources: per-slot + colour attribute.
        other = helpers.cube("Painted", size=1.0, location=(0, 0, 3))
        painted = other.data.color_attributes.new("Col", "FLOAT_COLOR", "POINT")
        painted.data.foreach_set("color", np.tile(np.float32([0.1, 0.2, 0.7, 1.0]), len(other.data.vertices)))
        helpers.select_only(obj, other)
        self.assertEqual(self.voxelize(voxel_size=SIZE), {"FINISHED"})
        path = self.volume_file()[0]
        centres, colours = colour_vdb(path)
        top = centres[:, 2] > 2.0
        self.assertGreater(top.sum(), 50)
        np.testing.assert_allclose(colours[top], np.tile([0.1, 0.2, 0.7], (top.sum(), 1)), atol=1e-5)
        low = ~top
        for side, expected in ((centres[:, 0] < 0, RED), (centres[:, 0] > 0, GREEN)):
            np.testing.assert_allclose(colours[low & side], np.tile(expected[:3], ((low & side).sum(), 1)), atol=1e-5)

    def test_colour_off_and_no_material_make_no_colour_grid(self):
        import pyopenvdb as vdb

        obj = split_cube()
        helpers.select_only(obj)
        self.assertEqual(self.voxelize(voxel_size=SIZE), {"FINISHED"})  # no material, no attribute
        names = [g["name"] for g in vdb.readAllGridMetadata(self.volume_file()[0])]
        self.assertEqual(names, ["density"])
        obj.data.materials.append(principled_material("Red", RED))
        self.assertEqual(self.voxelize(voxel_size=SIZE, color=False), {"FINISHED"})
        names = [g["name"] for g in vdb.readAllGridMetadata(self.volume_file()[0])]
        self.assertEqual(names, ["density"])

    def test_texture_matches_hyvox_with_the_same_texture(self):
        hyvox = helpers.hyvox_module()
        png = os.path.join(helpers.MESH_DIR, "spot_texture.png")
        vertices, triangles, attributes = hyvox.read_mesh(
            os.path.join(helpers.MESH_DIR, "spot_uv.ply"), attributes=True
        )
        uvs = attributes["uvs"]
        obj = helpers.mesh_object("Spot", vertices, triangles)
        layer = obj.data.uv_layers.new(name="UVMap")
        layer.data.foreach_set("uv", uvs[triangles.reshape(-1)].astype(np.float32).ravel())
        obj.data.uv_layers.new(name="Decoy")  # not the render UV map
        material = principled_material("Spot", (1, 0, 1, 1))
        tree = material.node_tree
        texture = tree.nodes.new("ShaderNodeTexImage")
        texture.image = bpy.data.images.load(png)
        shader = next(n for n in tree.nodes if n.type == "BSDF_PRINCIPLED")
        tree.links.new(texture.outputs["Color"], shader.inputs["Base Color"])
        obj.data.materials.append(material)
        helpers.select_only(obj)
        self.assertEqual(self.voxelize(resolution=48), {"FINISHED"})
        centres, colours = colour_vdb(self.volume_file()[0])

        expected = hyvox.voxelize(
            vertices, triangles, resolution=48, method="cpu", uvs=uvs, texture=png, attributes="color"
        )
        size = expected.voxel_size
        self.assertAlmostEqual(size, float(self.volumes()[0]["hyvox_voxel_size"]), places=6)
        want = {tuple(k): c for k, c in zip(np.asarray(expected.coords()), expected.attributes()["color"])}
        got_ijk = np.round((centres - np.asarray(expected.origin)) / size - 0.5).astype(np.int64)
        self.assertEqual(set(map(tuple, got_ijk)), set(want))
        difference = np.abs(colours - np.array([want[tuple(k)] for k in got_ijk]))
        print("texture: max colour difference to hyvox.voxelize", difference.max(), "voxels", len(got_ijk))
        self.assertLess(difference.max(), 1e-5)
        self.assertGreater(colours.std(axis=0).min(), 0.05)  # a real texture, not one colour

    def test_blocks_faces_take_their_voxel_colour(self):
        obj = split_cube()
        obj.data.materials.append(principled_material("Red", RED))
        obj.data.materials.append(principled_material("Green", GREEN))
        obj.data.polygons.foreach_set("material_index", np.where(face_halves(obj.data), 0, 1).astype(np.int32))
        helpers.select_only(obj)
        self.assertEqual(self.voxelize(voxel_size=SIZE, output="BLOCKS", export_vox=True), {"FINISHED"})
        blocks = next(o for o in bpy.data.objects if o.type == "MESH" and o.name != obj.name)
        mesh = blocks.data
        attribute = mesh.color_attributes[0]
        colours = np.empty(len(attribute.data) * 4, np.float32)
        attribute.data.foreach_get("color", colours)
        colours = colours.reshape(-1, 4)[:, :3]
        loop_face = np.repeat(np.arange(len(mesh.polygons)), [p.loop_total for p in mesh.polygons])
        centres = np.empty(len(mesh.polygons) * 3, np.float32)
        mesh.polygons.foreach_get("center", centres)
        x = centres.reshape(-1, 3)[loop_face, 0] + blocks.matrix_world.translation.x
        for side, expected in ((x < 0, RED), (x > 0, GREEN)):
            self.assertGreater(side.sum(), 100)
            np.testing.assert_allclose(colours[side], np.tile(expected[:3], (side.sum(), 1)), atol=1e-5)
        # The .vox beside the .vdb: each voxel's palette entry is its half's colour, sRGB-encoded.
        (vox_path,) = [os.path.join(self.out, f) for f in os.listdir(self.out) if f.endswith(".vox")]
        records, palette = read_vox(vox_path)
        x_of_seam = records[:, 0].max() / 2.0  # one model spans both cubes
        for side, expected in ((records[:, 0] < x_of_seam, RED), (records[:, 0] > x_of_seam, GREEN)):
            encoded = [255 * (12.92 * c if c <= 0.0031308 else 1.055 * c ** (1 / 2.4) - 0.055) for c in expected[:3]]
            used = palette[records[side, 3] - 1, :3].astype(np.float64)
            self.assertGreater(side.sum(), 100)
            np.testing.assert_allclose(used, np.tile(encoded, (side.sum(), 1)), atol=0.51)


RENDER_PIXELS = 72
RENDER_WIDTH = 4.5  # world units across the image


class ColourRenderTest(_ColourCase):
    """EEVEE, lit by a white world only, no bounces, so a pixel's colour is the albedo times
    a light factor that is the same for every channel: for the mesh a diffuse surface
    (Principled BSDF without specular), for the volume single scattering (Principled
    Volume: extinction = density in every channel, scattering albedo = 4 c / (1 + c)^2 of
    the `color` grid's colour c, which multiple scattering brings back to c). The test
    compares chromaticity (rgb / (r + g + b)) of each region's mean colour with those albedos,
    within 0.03."""

    def render(self, path):
        pixels = helpers.render_pixels(path)
        self.assertEqual(pixels.shape, (RENDER_PIXELS, RENDER_PIXELS, 4))
        return pixels

    def setup_scene(self):
        scene = bpy.context.scene
        camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
        camera.data.type = "ORTHO"
        camera.data.ortho_scale = RENDER_WIDTH
        camera.location = (0, -10, 0)
        camera.rotation_euler = (np.pi / 2, 0, 0)  # looking along +y, z up
        scene.collection.objects.link(camera)
        scene.camera = camera
        world = bpy.data.worlds.new("White")
        world.use_nodes = True
        world.node_tree.nodes["Background"].inputs["Color"].default_value = (1, 1, 1, 1)
        scene.world = world
        # EEVEE: Cycles 3.4, the Blender this test runs in, biases the hue where the grids
        # fade (test_looks.chroma_engines), Cycles 4.x and 5.x do not (tested there).
        scene.render.engine = "BLENDER_EEVEE"
        scene.eevee.taa_render_samples = 4
        scene.cycles.device = "CPU"
        scene.cycles.samples = 32
        scene.cycles.use_denoising = False
        scene.cycles.max_bounces = 0
        scene.render.resolution_x = scene.render.resolution_y = RENDER_PIXELS
        scene.render.resolution_percentage = 100
        scene.render.film_transparent = True  # the background adds nothing to a region
        scene.render.image_settings.file_format = "OPEN_EXR"
        scene.render.image_settings.color_depth = "32"
        scene.view_settings.view_transform = "Standard"
        scene.render.threads_mode = "FIXED"
        scene.render.threads = 2

    def test_rendered_volume_has_the_mesh_colours(self):
        obj = split_cube()
        for name, colour in (("Red", RED), ("Green", GREEN)):
            material = principled_material(name, colour)
            shader = next(n for n in material.node_tree.nodes if n.type == "BSDF_PRINCIPLED")
            specular = "Specular" if "Specular" in shader.inputs else "Specular IOR Level"  # 4.0 renamed it
            shader.inputs[specular].default_value = 0.0
            shader.inputs["Roughness"].default_value = 1.0
            obj.data.materials.append(material)
        obj.data.polygons.foreach_set("material_index", np.where(face_halves(obj.data), 0, 1).astype(np.int32))
        helpers.select_only(obj)
        self.assertEqual(self.voxelize(voxel_size=SIZE), {"FINISHED"})
        (volume,) = self.volumes()
        self.setup_scene()
        volume.hide_render = True
        mesh_image = self.render(os.path.join(self.out, "mesh.exr"))
        volume.hide_render, obj.hide_render = False, True
        volume_image = self.render(os.path.join(self.out, "volume.exr"))
        keep = os.environ.get("HYVOX_TEST_KEEP_RENDERS")
        if keep:  # for a person to look at: mesh | volume, display-encoded
            side_by_side = np.concatenate([mesh_image, volume_image], axis=1)[::-1]
            rgb = np.clip(side_by_side[..., :3], 0, 1)
            encoded = np.where(rgb <= 0.0031308, rgb * 12.92, 1.055 * rgb ** (1 / 2.4) - 0.055)
            out = bpy.data.images.new("keep", RENDER_PIXELS * 2, RENDER_PIXELS)
            alpha = side_by_side[..., 3:4]
            out.pixels.foreach_set(
                np.concatenate([encoded * alpha + (1 - alpha), np.ones_like(alpha)], axis=-1)[::-1]
                .astype(np.float32)
                .ravel()
            )
            out.filepath_raw, out.file_format = keep, "PNG"
            out.save()

        def region(image, x):
            """Mean RGB of a square of 12 pixels around world (x, 0) (image row 0 = bottom)."""
            column = int((x + RENDER_WIDTH / 2) / RENDER_WIDTH * RENDER_PIXELS)
            middle = RENDER_PIXELS // 2
            return image[middle - 6 : middle + 6, column - 6 : column + 6, :3].reshape(-1, 3).mean(axis=0)

        for x, expected in ((-1.0, RED), (1.0, GREEN)):
            mesh_rgb, volume_rgb = region(mesh_image, x), region(volume_image, x)
            mesh_chroma, volume_chroma = mesh_rgb / mesh_rgb.sum(), volume_rgb / volume_rgb.sum()
            albedo = np.array(expected[:3]) / sum(expected[:3])
            # The volume's albedo for the surface colour c (core/volume_look.py); without
            # bounces a pixel shows single scattering, in proportion to it.
            volume_albedo = 4 * np.array(expected[:3]) / (1 + np.array(expected[:3])) ** 2
            volume_albedo /= volume_albedo.sum()
            print(
                f"region x={x}: mesh {mesh_rgb.round(4)} volume {volume_rgb.round(4)} "
                f"chromaticity mesh {mesh_chroma.round(3)} volume {volume_chroma.round(3)} albedo {albedo.round(3)}"
                f" volume albedo {volume_albedo.round(3)}"
            )
            self.assertGreater(volume_rgb.sum(), 0.02, "the volume is seen")
            np.testing.assert_allclose(mesh_chroma, albedo, atol=0.03)  # the set-up shows albedo
            np.testing.assert_allclose(volume_chroma, volume_albedo, atol=0.03)
