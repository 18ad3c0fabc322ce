# SPDX-License-Identifier: GPL-3.0-or-later
"""Results made before the first save move next to the .blend when it is saved (.vdb and
.vox files, those of replaced results an undo can bring back too), the saved file points at
them by relative paths, an undo after the save finds its file where the save put it, and the
session's temporary folder goes once it is empty; on quit it goes if empty and stays with an
unsaved file's results in it, and a stale folder of an ended session goes when Blender starts
(this test saves and starts Blender: its own Blender processes)."""

import json
import os
import tempfile
import time

import bpy

import helpers
from helpers import AddonTestCase

HERE = os.path.dirname(os.path.abspath(__file__))


class SaveMovesResultsTest(AddonTestCase):
    def test_first_save_moves_unsaved_results_next_to_the_blend(self):
        from hyvox_blender.blender import operators
        from hyvox_blender.core import naming, session_folder

        self.assertEqual(bpy.data.filepath, "")
        cube, ball = helpers.cube("Cube"), helpers.cube("Ball", 1.0, (4, 0, 0))
        block = helpers.cube("Block", 1.0, (8, 0, 0))
        bpy.ops.ed.undo_push(message="scene")
        helpers.select_only(cube)
        run = dict(output_dir="", method="cpu", mode="conservative")
        bpy.ops.object.hyvox_voxelize("EXEC_DEFAULT", True, resolution=8, export_vox=True, **run)
        unsaved = naming.unsaved_output_dir(create=False)
        first_vox = os.path.join(unsaved, next(f for f in os.listdir(unsaved) if f.endswith(".vox")))
        self.assertIn("  " + first_vox, operators.last_summary)  # the run summary shows the .vox
        bpy.ops.object.hyvox_voxelize("EXEC_DEFAULT", True, resolution=12, **run)  # replaces the first
        helpers.select_only(ball)
        bpy.ops.object.hyvox_voxelize("EXEC_DEFAULT", True, resolution=8, frame_start=1, frame_end=2, **run)
        helpers.select_only(block)
        bpy.ops.object.hyvox_voxelize("EXEC_DEFAULT", True, resolution=8, output="BLOCKS", export_vox=True, **run)
        made = sorted(n for n in os.listdir(unsaved) if n != session_folder.OWNER_FILE)
        self.assertEqual(len(made), 7)  # 2 + 1 of the cube, 2 frames, the blocks' .vdb and .vox

        # A copy leaves the session unsaved: nothing moves.
        bpy.ops.wm.save_as_mainfile(filepath=os.path.join(self.out, "copy.blend"), copy=True)
        self.assertEqual(sorted(n for n in os.listdir(unsaved) if n != session_folder.OWNER_FILE), made)

        blend = os.path.join(self.out, "shot.blend")
        bpy.ops.wm.save_as_mainfile(filepath=blend)
        cache = os.path.join(self.out, "hyvox_cache", "shot")
        self.assertEqual(sorted(os.listdir(cache)), made)
        self.assertFalse(os.path.exists(unsaved), "the emptied session folder is removed")
        for obj in self.volumes():
            self.assertTrue(obj.data.filepath.startswith("//hyvox_cache/shot/"), obj.data.filepath)
        block_vox = bpy.data.objects["Block_blocks"]["hyvox_vox"]
        self.assertTrue(block_vox.startswith("//hyvox_cache/shot/") and block_vox.endswith(".vox"), block_vox)

        # Undo back to the cube's first volume: it pointed into the temporary folder, and now
        # reads its file where the save moved it.
        for _ in range(3):
            bpy.ops.ed.undo()
        volume = bpy.data.objects["Cube_voxels"]
        self.assertEqual(
            bpy.path.abspath(volume.data.filepath), os.path.join(cache, os.path.basename(first_vox)[:-4] + ".vdb")
        )
        self.assertTrue(volume.data.grids.load() and len(volume.data.grids))
        for _ in range(3):
            bpy.ops.ed.redo()

        # The saved file itself, opened by another Blender: relative paths, grids that load.
        check = (
            "import bpy, os\n"
            "for v in sorted(bpy.data.volumes, key=lambda v: v.name):\n"
            "    print('VOLUME', v.filepath, os.path.exists(bpy.path.abspath(v.filepath)), v.grids.load())\n"
        )
        done = helpers.run_blender(blend, "--python-expr", check)
        lines = [line.split() for line in done.stdout.splitlines() if line.startswith("VOLUME ")]
        self.assertEqual(len(lines), 2, done.stdout[-2000:])
        for _, path, exists, loaded in lines:
            self.assertTrue(path.startswith("//hyvox_cache/shot/"), path)
            self.assertEqual((exists, loaded), ("True", "True"), path)

    def test_session_folders_go_when_no_session_needs_them(self):
        from hyvox_blender.core import session_folder

        with tempfile.TemporaryDirectory(prefix="hyvox-tmp-") as tmp:
            env = dict(os.environ, TMPDIR=tmp)
            # A session that ended longer than STALE_AFTER_S ago, and one that runs (this
            # one), each with results in its folder.
            ended = session_folder.make(tmp)
            with open(os.path.join(ended, session_folder.OWNER_FILE), "w") as f:
                json.dump({"pid": 2**22 + 7, "identity": None}, f)  # beyond Linux's largest pid
            running = session_folder.make(tmp)
            for folder in (ended, running):
                open(os.path.join(folder, "Cube_voxels_r000001x.vdb"), "wb").close()
            then = time.time() - session_folder.STALE_AFTER_S - 60
            for folder in (ended, running):
                for path in [folder] + [os.path.join(folder, n) for n in os.listdir(folder)]:
                    os.utime(path, (then, then))
            script = os.path.join(HERE, "session_quit.py")
            unsaved = helpers.run_blender(
                "--python", script, "--", os.path.dirname(helpers.ADDON_DIR), "unsaved", env=env
            )
            saved = helpers.run_blender(
                "--python", script, "--", os.path.dirname(helpers.ADDON_DIR), os.path.join(tmp, "saved.blend"), env=env
            )
            failed = helpers.run_blender(
                "--python", script, "--", os.path.dirname(helpers.ADDON_DIR), "failed", env=env
            )
            folders = {}
            for done in (unsaved, saved, failed):
                line = next((text for text in done.stdout.splitlines() if text.startswith("SESSION ")), None)
                self.assertIsNotNone(line, done.stdout[-2000:] + done.stderr[-2000:])
                folders[line.split()[1]] = line.split()[2]
            self.assertFalse(os.path.exists(ended), "the ended session's stale folder is swept at start")
            self.assertTrue(os.path.isdir(running), "a running session's folder stays, however old")
            self.assertTrue(os.path.isdir(folders["unsaved"]), "an unsaved file's results stay for File > Recover")
            self.assertFalse(os.path.exists(folders["saved"]), "a saved session leaves no folder")
            self.assertFalse(os.path.exists(folders["failed"]), "an empty folder goes on quit")
