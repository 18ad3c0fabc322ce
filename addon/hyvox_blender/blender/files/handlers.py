# SPDX-License-Identifier: GPL-3.0-or-later
"""Results made before the first save live in this session's own temporary folder
(naming.unsaved_output_dir). When the file is saved, they move next to the .blend
(hyvox_cache/<blend name>/): the .vdb and .vox files of the volumes and Blocks, and those of
replaced results that undo can bring back (history.py points an undone volume at its
moved file); the volumes and results point there by relative paths, and the folder is
removed once empty. So the saved file does not depend on a temporary
folder that is gone after a reboot.

Blender 3.4 tells a save_pre handler neither the new path nor whether it saves a copy, so
the move happens in save_post, and the file is written once more with the new paths. A
"Save Copy" leaves the session unsaved: its files stay where they are (a message says so).

The session's folder also goes on quit when empty; with results of an unsaved file in it, it
stays for File > Recover (core/session_folder.py), and a later session removes it once its
owner has ended and it is stale."""

import atexit
import os
import shutil

import bpy
from bpy.app.handlers import persistent

from ...core import cleanup, naming, session_folder
from . import history as file_history

_saving_again = False


def _inside(path: str, folder: str) -> bool:
    path, folder = os.path.realpath(path), os.path.realpath(folder)
    return os.path.commonpath([path, folder]) == folder


def move_unsaved_results() -> int:
    """Move the voxel files of the unsaved folder that the open file uses or the undo history
    may reach (file_history.kept_keys) next to the saved .blend, point the volumes and results
    there (relative paths) and remove the folder if that emptied it (Live's cache keeps its
    other files there until it deletes them). Returns how many volumes and results now point
    elsewhere."""
    unsaved = naming.unsaved_output_dir(create=False)
    if not unsaved or not bpy.data.filepath or not os.path.isdir(unsaved):
        return 0
    target = naming.default_output_dir(bpy.data.filepath)
    kept = file_history.kept_keys()
    names = sorted(
        n for n in os.listdir(unsaved) if naming.is_voxel_file(n) and cleanup.file_key(os.path.join(unsaved, n)) in kept
    )
    if names:
        os.makedirs(target, exist_ok=True)
    for name in names:
        old, new = os.path.join(unsaved, name), os.path.join(target, name)
        shutil.move(old, new)
        file_history.record_move(old, new)
    changed = file_history.repoint_moved()
    if session_folder.remove_if_empty(unsaved):
        naming.forget_unsaved_output_dir()
    return changed


@persistent
def keep_results_with_the_blend(*_args):
    global _saving_again
    if _saving_again:
        return
    if not bpy.data.filepath:
        unsaved = naming.unsaved_output_dir(create=False)
        if unsaved and any(_inside(bpy.path.abspath(v.filepath), unsaved) for v in bpy.data.volumes if v.filepath):
            print(
                f"hyvox: saved a copy; the voxel files of this unsaved session stay in {unsaved} "
                "(save the file itself to keep them next to it)"
            )
        return
    if move_unsaved_results():
        _saving_again = True
        try:
            bpy.ops.wm.save_mainfile()
        finally:
            _saving_again = False


def _remove_own_folder_if_empty():
    """At quit: the session's folder, when nothing is left in it."""
    if session_folder.remove_if_empty(naming.unsaved_output_dir(create=False)):
        naming.forget_unsaved_output_dir()


_at_exit = []  # registered once per process, however often the add-on is enabled


def register():
    bpy.app.handlers.save_post.append(keep_results_with_the_blend)
    if not _at_exit:  # the bpy module's exit; Blender's own quit disables the add-on first
        atexit.register(_remove_own_folder_if_empty)
        _at_exit.append(True)
    session_folder.sweep(naming.is_voxel_file, own=naming.unsaved_output_dir(create=False))


def unregister():
    _remove_own_folder_if_empty()  # Blender disables every add-on when it quits
    if keep_results_with_the_blend in bpy.app.handlers.save_post:
        bpy.app.handlers.save_post.remove(keep_results_with_the_blend)
