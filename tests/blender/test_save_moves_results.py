# SPDX-License-Identifier: GPL-3.0-or-later
"""Results made before the first save move next to the .blend when it is saved, and the
saved file points at them by relative paths (this test saves: its own Blender process)."""
import os
import subprocess

import bpy

import helpers
from helpers import AddonTestCase


class SaveMovesResultsTest(AddonTestCase):
    def test_first_save_moves_unsaved_results_next_to_the_blend(self):
        from hyvox_blender.core import naming
        self.assertEqual(bpy.data.filepath, "")
        cube, ball = helpers.cube("Cube"), helpers.cube("Ball", 1.0, (4, 0, 0))
        helpers.select_only(cube)
        self.voxelize(resolution=8, output_dir="")
        helpers.select_only(ball)
        self.voxelize(resolution=8, output_dir="", frame_start=1, frame_end=2)
        unsaved = naming.unsaved_output_dir(create=False)
        made = sorted(os.listdir(unsaved))
        self.assertEqual(len(made), 3)

        # A copy leaves the session unsaved: nothing moves.
        bpy.ops.wm.save_as_mainfile(filepath=os.path.join(self.out, "copy.blend"), copy=True)
        self.assertEqual(sorted(os.listdir(unsaved)), made)

        blend = os.path.join(self.out, "shot.blend")
        bpy.ops.wm.save_as_mainfile(filepath=blend)
        cache = os.path.join(self.out, "hyvox_cache", "shot")
        self.assertEqual(sorted(os.listdir(cache)), made)
        self.assertEqual(os.listdir(unsaved), [])
        for obj in self.volumes():
            self.assertTrue(obj.data.filepath.startswith("//hyvox_cache/shot/"), obj.data.filepath)

        # The saved file itself, opened by another Blender: relative paths, grids that load.
        check = ("import bpy, os\n"
                 "for v in sorted(bpy.data.volumes, key=lambda v: v.name):\n"
                 "    print('VOLUME', v.filepath, os.path.exists(bpy.path.abspath(v.filepath)), v.grids.load())\n")
        done = subprocess.run([bpy.app.binary_path, "-b", "--factory-startup", "-noaudio", blend,
                               "--python-expr", check], capture_output=True, text=True, timeout=120)
        lines = [line.split() for line in done.stdout.splitlines() if line.startswith("VOLUME ")]
        self.assertEqual(len(lines), 2, done.stdout[-2000:])
        for _, path, exists, loaded in lines:
            self.assertTrue(path.startswith("//hyvox_cache/shot/"), path)
            self.assertEqual((exists, loaded), ("True", "True"), path)
