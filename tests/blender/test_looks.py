# SPDX-License-Identifier: GPL-3.0-or-later
"""How a hyvox volume looks, measured by small renders (64 pixels, few samples: the means
compared are over a thousand pixels), lit by a white world (test_looks.scattering_engines
says which engines show what here):

- Color: a grey 0.8 object voxelized with Color renders as the same volume without Color
  (the add-on's grey albedo): the `color` grid's fade at the surface is
  divided out (core/volume_look.py), where the grid alone renders darker.
- A re-run follows the grids: Color is on by default, a volume made without it shows the
  objects' colours (their albedo's hue, rendered) once re-run with it, and loses the colour
  nodes when re-run without, keeping the artist's own settings and links.
Density: test_looks_density.py."""

import math
import os

import bpy
import numpy as np

import helpers
from helpers import AddonTestCase
from test_render_alignment import eevee_engine

PIXELS = 64
GREY = (0.8, 0.8, 0.8, 1.0)
INNER = 0.8  # the part of the sphere's outline where voxels of 48 and 256 have the same surface


def sphere(name="Sphere"):
    """A UV sphere of radius 1 with Blender's default grey material (Principled BSDF 0.8)."""
    bpy.ops.mesh.primitive_uv_sphere_add(radius=1.0, segments=24, ring_count=12)
    obj = bpy.context.active_object
    obj.name = name
    material = bpy.data.materials.new("Grey")
    material.use_nodes = True
    material.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = GREY
    obj.data.materials.append(material)
    return obj


def setup(engine, backdrop=False):
    """Orthographic camera along +y at the unit sphere, a white world the only light, film
    opaque. The background the camera sees is black (the volume's own light alone), or with
    `backdrop` white (what the volume lets through). Made once, set again on each call."""
    scene = bpy.context.scene
    camera = bpy.data.objects.get("Camera")
    if camera is None:
        camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
        camera.data.type = "ORTHO"
        camera.data.ortho_scale = 2.6
        camera.location = (0.0, -10.0, 0.0)
        camera.rotation_euler = (math.pi / 2, 0.0, 0.0)
        scene.collection.objects.link(camera)
        world = scene.world = bpy.data.worlds.new("World")
        world.use_nodes = True
        nodes = world.node_tree.nodes
        seen = nodes.new("ShaderNodeMixRGB")
        seen.name = "Seen"
        seen.inputs["Color1"].default_value = (1, 1, 1, 1)  # the light
        world.node_tree.links.new(nodes.new("ShaderNodeLightPath").outputs["Is Camera Ray"], seen.inputs["Fac"])
        world.node_tree.links.new(seen.outputs["Color"], nodes["Background"].inputs["Color"])
    scene.camera = camera
    scene.world.node_tree.nodes["Seen"].inputs["Color2"].default_value = (1, 1, 1, 1) if backdrop else (0, 0, 0, 1)
    scene.render.engine = engine
    helpers.measured_render(scene, PIXELS)
    scene.cycles.samples = 8
    scene.eevee.taa_render_samples = 4


def disc(radius=1.0 - 2.6 / PIXELS):
    """(PIXELS, PIXELS) bool: the pixels inside a circle around the unit sphere's centre (by
    default its outline less a pixel)."""
    centres = (np.arange(PIXELS) + 0.5) / PIXELS * 2.6 - 1.3
    x, z = np.meshgrid(centres, centres)
    return x * x + z * z < radius**2


def scattering_engines():
    """The engines whose renders show a volume's scattered light in its albedo's hue: Cycles
    from 4.x on, and Debian 12's 3.4 EEVEE. EEVEE 4.2-5.0 draws no scattered light of a
    volume on this machine's software GL (world or sun light, transparent film or not: black;
    measured), only what it lets through. Cycles 3.4 biases the colour / density ratio where
    both grids fade, toward the weaker channels (a red 0.6, 0.05, 0.02 rendered at
    chromaticity 0.70, 0.21, 0.09 against the albedo's 0.78, 0.15, 0.06, at any step rate or
    sample count; the `color` grid alone renders the exact hue there): docs/artist.md says so."""
    return ["CYCLES"] if bpy.app.version >= (4, 0, 0) else [eevee_engine()]


class LooksCase(AddonTestCase):
    """Renders of a volume (shared with test_looks_density)."""

    def voxelize(self, **kw):
        kw.setdefault("mode", "solid")
        return super().voxelize(**kw)

    def render(self, name):
        pixels = helpers.render_pixels(os.path.join(self.out, name + ".exr"))
        self.assertEqual(pixels.shape, (PIXELS, PIXELS, 4))
        return pixels

    def mean(self, name, radius=None):
        """Mean RGB brightness inside the outline (or a smaller circle)."""
        return float(self.render(name)[..., :3][disc() if radius is None else disc(radius)].mean())

    def volume(self):
        (volume,) = self.volumes()
        return volume

    def shader(self, volume=None):
        tree = (volume or self.volume()).data.materials[0].node_tree
        return tree, next(n for n in tree.nodes if n.type == "PRINCIPLED_VOLUME")


class LooksTest(LooksCase):
    def test_color_volume_renders_as_bright_as_without_color(self):
        volume_material = helpers.addon("blender.volume.material")
        source = sphere()
        helpers.select_only(source)
        # A shell: its every voxel is where the grids fade.
        self.assertEqual(self.voxelize(resolution=32, color=True, mode="conservative"), {"FINISHED"})
        source.hide_render = True
        tree, shader = self.shader()
        albedo = shader.inputs["Color"].links[0].from_socket
        undivided = self.undivided_albedo(tree, tree.nodes[volume_material.COLOR].outputs["Vector"])
        for engine in sorted({"CYCLES"} | set(scattering_engines())):
            with self.subTest(engine=engine):
                setup(engine)
                tree.links.new(albedo, shader.inputs["Color"])
                colored = self.mean("color")
                tree.links.remove(shader.inputs["Color"].links[0])
                shader.inputs["Color"].default_value = volume_material.GREY
                grey = self.mean("grey")
                tree.links.new(undivided, shader.inputs["Color"])
                darker = self.mean("undivided")
                print(
                    f"{engine}: mean brightness with color {colored:.4f}, grey {grey:.4f}, "
                    f"color grid undivided {darker:.4f}"
                )
                self.assertAlmostEqual(colored, grey, delta=0.02 * grey)
                self.assertLess(darker, 0.9 * grey)  # what the division makes up for

    @staticmethod
    def undivided_albedo(tree, color):
        """4 c / (1 + c)^2 of the grid's colour c, not divided by the density."""

        def node(operation, *inputs):
            math_node = tree.nodes.new("ShaderNodeVectorMath")
            math_node.operation = operation
            for socket, value in zip(math_node.inputs, inputs):
                if isinstance(value, tuple):
                    socket.default_value = value
                else:
                    tree.links.new(value, socket)
            return math_node.outputs["Vector"]

        total = node("ADD", color, (1.0, 1.0, 1.0))
        return node("DIVIDE", node("MULTIPLY", color, (4.0, 4.0, 4.0)), node("MULTIPLY", total, total))

    def test_color_is_on_by_default_and_a_rerun_follows_the_grids(self):
        volume_material = helpers.addon("blender.volume.material")
        from test_colour import GREEN, RED, face_halves, principled_material, split_cube

        source = split_cube()
        source.data.materials.append(principled_material("Red", RED))
        source.data.materials.append(principled_material("Green", GREEN))
        source.data.polygons.foreach_set("material_index", np.where(face_halves(source.data), 0, 1).astype(np.int32))
        helpers.select_only(source)
        self.assertTrue(bpy.context.scene.hyvox.color)
        self.assertEqual(self.voxelize(voxel_size=0.125, color=False), {"FINISHED"})

        def state():
            volume = self.volume()
            volume.data.grids.load()
            return (volume,) + self.shader(volume) + (sorted(g.name for g in volume.data.grids),)

        volume, tree, shader, grids = state()
        self.assertEqual(grids, ["density"])
        self.assertFalse(shader.inputs["Color"].links)
        shader.inputs["Anisotropy"].default_value = 0.25  # the artist's

        self.assertEqual(self.voxelize(voxel_size=0.125), {"FINISHED"})  # the default: Color on
        volume, tree, shader, grids = state()
        self.assertEqual(grids, ["color", "density"])
        self.assertEqual(shader.inputs["Color"].links[0].from_node.name, volume_material.ALBEDO)
        self.assertEqual(shader.inputs["Anisotropy"].default_value, 0.25)
        source.hide_render = True
        for engine in scattering_engines():
            setup(engine)
            bpy.context.scene.cycles.max_bounces = 0
            image = self.render("rerun_color")
            for x, expected in ((-1.0, RED), (1.0, GREEN)):
                column = int((x + 1.3) / 2.6 * PIXELS)
                rgb = image[PIXELS // 2 - 4 : PIXELS // 2 + 4, column - 4 : column + 4, :3].reshape(-1, 3).mean(axis=0)
                # Filled, nearly opaque: single scattering of the world's white light shows
                # the albedo of each half's colour c.
                albedo = 4 * np.array(expected[:3]) / (1 + np.array(expected[:3])) ** 2
                print(
                    f"{engine}: re-run with Color, x={x}: rgb {rgb.round(4)}, chromaticity "
                    f"{(rgb / rgb.sum()).round(3)}, albedo's {(albedo / albedo.sum()).round(3)}"
                )
                np.testing.assert_allclose(rgb / rgb.sum(), albedo / albedo.sum(), atol=0.03)

        self.assertEqual(self.voxelize(voxel_size=0.125, color=False), {"FINISHED"})
        volume, tree, shader, grids = state()
        self.assertEqual(grids, ["density"])
        self.assertFalse(shader.inputs["Color"].links)
        np.testing.assert_allclose(shader.inputs["Color"].default_value, volume_material.GREY, rtol=1e-6)
        self.assertFalse([n.name for n in tree.nodes if n.name in volume_material.COLOR_NODES])
        self.assertEqual(shader.inputs["Anisotropy"].default_value, 0.25)

        # The artist's own Color (a link of theirs) stays whatever the grids.
        mine = tree.nodes.new("ShaderNodeRGB")
        tree.links.new(mine.outputs["Color"], shader.inputs["Color"])
        self.assertEqual(self.voxelize(voxel_size=0.125), {"FINISHED"})
        volume, tree, shader, grids = state()
        self.assertEqual((grids, shader.inputs["Color"].links[0].from_node.name), (["color", "density"], mine.name))
