# SPDX-License-Identifier: GPL-3.0-or-later
"""Rendered alignment: Cycles and EEVEE draw the voxelized 2x2x2 cube where the cube is.

Orthographic camera straight down -z, white background, the volume a pure absorber.
Along a row through the cube's middle, the side wall (one voxel thick, 2 units deep)
fades in over one voxel around the true edge with trilinear interpolation; its density
at the edge is 1/2, so with absorption D = ln 2 the transmittance there is
exp(-D * 1/2 * 2) = 1/2. The 50% crossings of the image must therefore sit on the cube's
edges; a half-voxel offset would move them by half a voxel. Tolerance: a quarter voxel."""
import math
import os

import bpy
import numpy as np

import helpers
from helpers import AddonTestCase

SIZE = 0.25        # voxel size: 8 voxels across the cube
PIXELS = 96        # image width and height
ORTHO = 3.0        # world units across the image


def setup_render(scene, volume_obj, engine="CYCLES"):
    material = bpy.data.materials.new("Absorber")
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    absorb = nodes.new("ShaderNodeVolumeAbsorption")
    absorb.inputs["Color"].default_value = (0, 0, 0, 1)   # absorbs every channel
    attribute = nodes.new("ShaderNodeAttribute")
    attribute.attribute_name = "density"
    scale = nodes.new("ShaderNodeMath")
    scale.operation = "MULTIPLY"
    scale.inputs[1].default_value = math.log(2.0)
    material.node_tree.links.new(attribute.outputs["Fac"], scale.inputs[0])
    material.node_tree.links.new(scale.outputs[0], absorb.inputs["Density"])
    material.node_tree.links.new(absorb.outputs["Volume"], out.inputs["Volume"])
    volume_obj.data.materials.clear()
    volume_obj.data.materials.append(material)

    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.data.type = "ORTHO"
    camera.data.ortho_scale = ORTHO
    camera.data.clip_end = 100
    camera.location = (0, 0, 10)
    scene.collection.objects.link(camera)
    scene.camera = camera

    world = bpy.data.worlds.new("White")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (1, 1, 1, 1)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
    scene.world = world

    scene.render.engine = engine
    # EEVEE: fine froxels, so its volume edges are sharp enough to measure.
    scene.eevee.volumetric_tile_size = "2"
    scene.eevee.volumetric_samples = 128
    scene.eevee.volumetric_start, scene.eevee.volumetric_end = 5.0, 15.0
    scene.eevee.taa_render_samples = 8
    scene.cycles.device = "CPU"
    scene.cycles.samples = 16
    scene.cycles.use_denoising = False  # Debian's Blender has no OpenImageDenoise
    scene.cycles.volume_step_rate = 0.25
    scene.cycles.max_bounces = 0
    scene.render.resolution_x = scene.render.resolution_y = PIXELS
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.view_settings.view_transform = "Standard"
    scene.render.threads_mode = "FIXED"
    scene.render.threads = 2


def eevee_engine():
    """EEVEE's engine id: BLENDER_EEVEE in 3.x and 5.x, BLENDER_EEVEE_NEXT in 4.2-4.5."""
    ids = {item.identifier for item in bpy.types.RenderSettings.bl_rna.properties["engine"].enum_items}
    return "BLENDER_EEVEE_NEXT" if "BLENDER_EEVEE_NEXT" in ids else "BLENDER_EEVEE"


def crossing(profile, reverse=False):
    """Sub-pixel position (pixel-centre units) where profile first falls below 0.5."""
    values = profile[::-1] if reverse else profile
    below = np.nonzero(values < 0.5)[0]
    assert len(below) and below[0] > 0, "no edge in the profile"
    k = below[0]
    a, b = values[k - 1], values[k]
    pos = (k - 1) + (a - 0.5) / (a - b)
    return len(values) - 1 - pos if reverse else pos


def world_x(pixel):
    """World coordinate of a pixel-centre position along a row (camera at x=0)."""
    return (pixel + 0.5 - PIXELS / 2) * ORTHO / PIXELS


class RenderAlignmentTest(AddonTestCase):
    def render_edges(self):
        pixels = helpers.render_pixels(os.path.join(self.out, "render.exr"))[:, :, 0]
        self.assertEqual(pixels.shape, (PIXELS, PIXELS))
        mid = PIXELS // 2
        rows = pixels[mid - 2:mid + 2].mean(axis=0)        # along x
        cols = pixels[:, mid - 2:mid + 2].mean(axis=1)     # along y
        return [world_x(crossing(rows)), world_x(crossing(rows, True)),
                world_x(crossing(cols)), world_x(crossing(cols, True))]

    def check_engine(self, engine):
        cube = helpers.cube(size=2.0)
        helpers.select_only(cube)
        self.assertEqual(self.voxelize(voxel_size=SIZE), {"FINISHED"})
        (obj,) = self.volumes()
        cube.hide_render = True
        setup_render(bpy.context.scene, obj, engine)
        edges = self.render_edges()
        print(engine, "50% crossings (world):", ["%.4f" % e for e in edges], "voxel", SIZE)
        errors = np.abs(np.abs(edges) - 1.0)
        self.assertLess(errors.max(), SIZE / 4, f"edges {edges}")
        # The other choice (correction toggled) must be visibly off, so the version rule
        # of core/alignment.py is measured both ways on the Blender running this.
        corrected = any(obj.location)
        obj.location = (0, 0, 0) if corrected else (-SIZE / 2,) * 3
        other = self.render_edges()
        print(engine, "corrected" if not corrected else "uncorrected", "crossings:",
              ["%.4f" % e for e in other])
        self.assertGreater(np.abs(np.abs(other) - 1.0).max(), SIZE / 4)

    def test_cycles(self):
        self.check_engine("CYCLES")

    def test_eevee(self):
        self.check_engine(eevee_engine())
