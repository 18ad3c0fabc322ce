# SPDX-License-Identifier: GPL-3.0-or-later
"""WM_OT_hyvox_clean_voxel_files: delete the voxel files nothing uses (runs write new files
each time, so replaced results leave theirs behind). It looks in the folders hyvox writes to
(the cache next to the .blend, this session's unsaved folder, the scene's output folder, the
folders of hyvox volumes) and only at files named as hyvox names them. It keeps the files of
the open file's volumes and results (a result's .vox with its .vdb) and those an undo or redo
could bring back (history.py); those go once the file is opened again."""

import os

import bpy

from ...core import cleanup, naming
from . import history as file_history
from ..volume import importer


def candidate_folders(context):
    # The .blend's cache folder, and this session's unsaved-file folder if one was made
    # (default_output_dir would make one for an unsaved file just to look into it).
    folders = {naming.default_output_dir(bpy.data.filepath)} if bpy.data.filepath else set()
    unsaved = naming.unsaved_output_dir(create=False)
    if unsaved:
        folders.add(unsaved)
    for scene in bpy.data.scenes:
        if scene.hyvox.output_dir:
            folders.add(bpy.path.abspath(scene.hyvox.output_dir))
    for obj in bpy.data.objects:
        if obj.type == "VOLUME" and importer.KEY in obj and obj.data is not None and obj.data.filepath:
            folders.add(os.path.dirname(bpy.path.abspath(obj.data.filepath)))
    return folders


def unused_voxel_files(context, keep_undo_reachable=True):
    keep = file_history.kept_keys() if keep_undo_reachable else cleanup.used_keys(*file_history.used_files())
    return cleanup.unused_files(candidate_folders(context), (), (), naming.is_voxel_file, keep)


class WM_OT_hyvox_clean_voxel_files(bpy.types.Operator):
    """Delete the voxel files (.vdb, .vox) nothing uses any more: those of replaced or deleted
    results that undo cannot bring back either"""

    bl_idname = "wm.hyvox_clean_voxel_files"
    bl_label = "Clean Unused Voxel Files"

    def execute(self, context):
        removed, size, failed = 0, 0, []
        for path in unused_voxel_files(context):
            try:
                file_size = os.path.getsize(path)
                os.remove(path)
            except OSError as exc:
                failed.append(f"{os.path.basename(path)} ({exc.strerror})")
                continue
            removed += 1
            size += file_size
        if failed:
            self.report({"WARNING"}, "Could not delete " + ", ".join(failed[:3]))
        kept = len(unused_voxel_files(context, keep_undo_reachable=False))
        more = f"; kept {kept} that undo could bring back (they go once the file is opened again)" if kept else ""
        self.report(
            {"INFO"}, f"Deleted {removed} unused voxel file{'s' * (removed != 1)} ({size / 2**20:.1f} MiB){more}"
        )
        return {"FINISHED"}


CLASSES = (WM_OT_hyvox_clean_voxel_files,)
