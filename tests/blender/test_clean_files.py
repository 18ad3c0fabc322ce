# SPDX-License-Identifier: GPL-3.0-or-later
"""Clean Unused Files deletes only what nothing can use any more: it keeps the files of the
open file's volumes and results (a result's .vox export with its .vdb, a Blocks result's
.vox and .vdb) and those an undo or redo can bring back, so a redo after a Clean finds its file; once
the file is opened again (a new undo history) the replaced results' files go. (This test
opens a file: its own Blender process.)"""

import os

import bpy

import helpers
from helpers import AddonTestCase


def file_of(obj):
    return bpy.path.abspath(obj.data.filepath)


class CleanFilesTest(AddonTestCase):
    def voxelize_with_undo(self, **kw):
        """As the UI runs it: the operator pushes an undo step."""
        kw.setdefault("output_dir", self.out)
        kw.setdefault("method", "cpu")
        kw.setdefault("mode", "conservative")
        return bpy.ops.object.hyvox_voxelize("EXEC_DEFAULT", True, **kw)

    def listing(self):
        return sorted(os.listdir(self.out))

    def test_clean_keeps_exports_and_what_undo_reaches(self):
        cube, ball = helpers.cube("Cube"), helpers.cube("Ball", 1.0, (4, 0, 0))
        block = helpers.cube("Block", 1.0, (8, 0, 0))
        bpy.ops.ed.undo_push(message="scene")
        helpers.select_only(cube)
        self.voxelize_with_undo(resolution=8, export_vox=True)
        first = file_of(self.volumes()[0])
        self.voxelize_with_undo(resolution=16, export_vox=True)
        second = file_of(bpy.data.objects["Cube_voxels"])
        helpers.select_only(ball)
        self.voxelize_with_undo(resolution=8, frame_start=1, frame_end=2, export_vox=True)
        helpers.select_only(block)
        self.voxelize_with_undo(resolution=8, output="BLOCKS", export_vox=True)
        vox = sorted(f for f in self.listing() if f.endswith(".vox"))
        self.assertEqual(len(vox), 5)  # two of the cube, two frames, the blocks'
        strangers = ["notes.txt", "mine.vdb", "Cube_voxels.vdb.bak"]
        for name in strangers:
            open(os.path.join(self.out, name), "w").close()
        made = self.listing()

        # Undo the blocks, the ball and the cube's second run: the first volume is back.
        for _ in range(3):
            bpy.ops.ed.undo()
        self.assertEqual(file_of(bpy.data.objects["Cube_voxels"]), first)
        self.assertEqual(bpy.ops.wm.hyvox_clean_voxel_files(), {"FINISHED"})
        self.assertEqual(self.listing(), made)  # the redo steps' files, .vox exports included
        for _ in range(3):
            bpy.ops.ed.redo()
        volume = bpy.data.objects["Cube_voxels"]
        self.assertEqual(file_of(volume), second)
        self.assertTrue(volume.data.grids.load() and len(volume.data.grids), "the redone volume reads its file")
        self.assertEqual(bpy.ops.wm.hyvox_clean_voxel_files(), {"FINISHED"})
        self.assertEqual(self.listing(), made)  # the first run is an undo away

        # A new history: only what the opened file uses stays.
        blend = os.path.join(self.out, "shot.blend")
        bpy.ops.wm.save_as_mainfile(filepath=blend)
        bpy.ops.wm.open_mainfile(filepath=blend)
        self.assertEqual(bpy.ops.wm.hyvox_clean_voxel_files(), {"FINISHED"})
        gone = [os.path.basename(first), os.path.splitext(os.path.basename(first))[0] + ".vox"]
        self.assertEqual(self.listing(), sorted(set(made) - set(gone) | {"shot.blend"}))
        block_vox = bpy.path.abspath(bpy.data.objects["Block_blocks"]["hyvox_vox"])
        self.assertTrue(os.path.isfile(block_vox))
