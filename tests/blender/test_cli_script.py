# SPDX-License-Identifier: GPL-3.0-or-later
"""The headless pipeline entry point (hyvox_blender/cli_blender.py) in a child Blender:
frame chunks, stats JSON, saving, and exit code 1 on failure."""

import json
import os

import bpy
import numpy as np

import helpers
from helpers import AddonTestCase


class CliScriptTest(AddonTestCase):
    def save_scene(self):
        cube = helpers.cube(size=1.0)
        cube.keyframe_insert("location", frame=1)
        cube.location = (2, 0, 0)
        cube.keyframe_insert("location", frame=4)
        blend = os.path.join(self.out, "scene.blend")
        bpy.ops.wm.save_as_mainfile(filepath=blend, copy=True)
        return blend

    def test_frame_chunk_stats_and_save(self):
        blend = self.save_scene()
        vdb_dir = os.path.join(self.out, "vdb")
        stats = os.path.join(self.out, "stats.json")
        saved = os.path.join(self.out, "voxelized.blend")
        done = helpers.run_cli_script(
            blend,
            "--frames",
            "3-4",
            "--output",
            vdb_dir,
            "--resolution",
            "16",
            "--method",
            "cpu",
            "--objects",
            "Cube",
            "--stats-json",
            stats,
            "--save",
            saved,
        )
        self.assertEqual(done.returncode, 0, done.stdout[-2000:] + done.stderr[-2000:])
        self.assertEqual(sorted(os.listdir(vdb_dir)), ["Cube_voxels_0003.vdb", "Cube_voxels_0004.vdb"])
        with open(stats) as f:
            record = json.load(f)
        (volume,) = record["volumes"]
        self.assertEqual(volume["frames"], [3, 4])
        self.assertEqual(len(volume["voxel_counts"]), 2)
        self.assertIn("voxelize", record["timings_ms"])
        with bpy.data.libraries.load(saved) as (data_from, _):
            self.assertIn("Cube_voxels", data_from.objects)

    def test_colour_grid_unless_no_color(self):
        import pyopenvdb as vdb

        cube = helpers.cube(size=1.0)
        material = bpy.data.materials.new("Blue")
        material.diffuse_color = (0.1, 0.2, 0.9, 1.0)  # no nodes: the viewport colour counts
        cube.data.materials.append(material)
        blend = os.path.join(self.out, "coloured.blend")
        bpy.ops.wm.save_as_mainfile(filepath=blend, copy=True)
        for extra, grids in (((), ["color", "density"]), (("--no-color",), ["density"])):
            vdb_dir = os.path.join(self.out, "vdb" + "".join(extra))
            # A surface run, so the grids' voxels are the cube's shell.
            done = helpers.run_cli_script(
                blend, "--output", vdb_dir, "--resolution", "8", "--objects", "Cube", "--mode", "conservative", *extra
            )
            self.assertEqual(done.returncode, 0, done.stdout[-2000:] + done.stderr[-2000:])
            (name,) = os.listdir(vdb_dir)
            path = os.path.join(vdb_dir, name)
            self.assertEqual(sorted(g["name"] for g in vdb.readAllGridMetadata(path)), grids)
            if "color" in grids:
                values = np.array([item.value for item in vdb.read(path, "color").citerOnValues()])
                np.testing.assert_allclose(values, np.tile([0.1, 0.2, 0.9], (len(values), 1)), atol=1e-6)

    def test_failure_exits_1(self):
        blend = self.save_scene()
        done = helpers.run_cli_script(blend, "--objects", "NoSuchObject", "--output", self.out)
        self.assertEqual(done.returncode, 1)
        self.assertIn("NoSuchObject", done.stderr)
        # A value out of the schema's limits is refused with its message, and nothing is written.
        done = helpers.run_cli_script(blend, "--objects", "Cube", "--resolution", "0", "--output", self.out)
        self.assertEqual(done.returncode, 1)
        self.assertIn("resolution must be a whole number between 1 and 16384, got 0", done.stderr)
        self.assertEqual([f for f in os.listdir(self.out) if f != "scene.blend"], [])

    def test_live_renders_every_frame_with_its_own_voxels(self):
        """`blender -b scene.blend --python cli_blender.py -a -- --live`: the animation renders
        as voxels, each frame its own, with no frame range and nothing baked."""
        from test_live import read_frames, render_setup

        scene = bpy.context.scene
        cube = helpers.cube(size=1.0)
        for frame, x in ((1, -1.0), (2, 0.0), (3, 1.2)):
            cube.location.x = x
            cube.keyframe_insert("location", frame=frame)
        cube.hide_render = True  # only the voxels render
        scene.frame_start, scene.frame_end = 1, 3
        scene.frame_set(1)
        render_dir = os.path.join(self.out, "renders")
        render_setup(scene, render_dir)
        blend = os.path.join(self.out, "animated.blend")
        bpy.ops.wm.save_as_mainfile(filepath=blend, copy=True)
        vdb_dir = os.path.join(self.out, "vdb")
        done = helpers.run_cli_script(
            blend,
            "--live",
            "--output",
            vdb_dir,
            "--resolution",
            "12",
            "--objects",
            "Cube",
            blender_args=["-a"],
            timeout=300,
        )
        self.assertEqual(done.returncode, 0, done.stdout[-2000:] + done.stderr[-2000:])
        images = read_frames(render_dir, (1, 2, 3))
        # The cube's voxels darken the white background where the cube is in each frame.
        columns = [np.argmin(image[..., 0].mean(axis=0)) for image in images]
        self.assertLess(min(image[..., 0].min() for image in images), 0.5)
        self.assertTrue(columns[0] < columns[1] < columns[2], columns)
        # The session's Live files went with it: nothing was saved that refers to them.
        self.assertEqual(os.listdir(vdb_dir), [])
