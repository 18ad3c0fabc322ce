# SPDX-License-Identifier: GPL-3.0-or-later
"""Results made before the first save live in this session's own temporary folder
(naming.unsaved_output_dir). When the file is saved, they move next to the .blend
(hyvox_cache/<blend name>/) and the volumes point there by relative paths, so the saved
file does not depend on a temporary folder that is gone after a reboot.

Blender 3.4 tells a save_pre handler neither the new path nor whether it saves a copy, so
the move happens in save_post, and the file is written once more with the new paths. A
"Save Copy" leaves the session unsaved: its files stay where they are (a message says so)."""
import os
import shutil

import bpy
from bpy.app.handlers import persistent

from ..core import cleanup, naming

_saving_again = False


def _inside(path: str, folder: str) -> bool:
    path, folder = os.path.realpath(path), os.path.realpath(folder)
    return os.path.commonpath([path, folder]) == folder


def move_unsaved_results() -> int:
    """Move the files of every volume in the unsaved folder next to the saved .blend and
    point the volume there (relative path). Returns how many volumes moved."""
    unsaved = naming.unsaved_output_dir(create=False)
    if not unsaved or not bpy.data.filepath:
        return 0
    target = naming.default_output_dir(bpy.data.filepath)
    moved = 0
    for volume in bpy.data.volumes:
        path = bpy.path.abspath(volume.filepath)
        if not volume.filepath or not _inside(path, unsaved):
            continue
        files = cleanup.sequence_files(path) if volume.is_sequence else [path]
        os.makedirs(target, exist_ok=True)
        for file in files:
            if os.path.exists(file):
                shutil.move(file, os.path.join(target, os.path.basename(file)))
        volume.filepath = bpy.path.relpath(os.path.join(target, os.path.basename(path)))
        moved += 1
    return moved


@persistent
def keep_results_with_the_blend(*_args):
    global _saving_again
    if _saving_again:
        return
    if not bpy.data.filepath:
        unsaved = naming.unsaved_output_dir(create=False)
        if unsaved and any(_inside(bpy.path.abspath(v.filepath), unsaved) for v in bpy.data.volumes if v.filepath):
            print(f"hyvox: saved a copy; the voxel files of this unsaved session stay in {unsaved} "
                  "(save the file itself to keep them next to it)")
        return
    if move_unsaved_results():
        _saving_again = True
        try:
            bpy.ops.wm.save_mainfile()
        finally:
            _saving_again = False


def register():
    bpy.app.handlers.save_post.append(keep_results_with_the_blend)


def unregister():
    if keep_results_with_the_blend in bpy.app.handlers.save_post:
        bpy.app.handlers.save_post.remove(keep_results_with_the_blend)
