# SPDX-License-Identifier: GPL-3.0-or-later
"""The voxel files this session's undo history may still point at, so that Clean Unused
Files keeps them (an undo or redo after a Clean must find its volume's file), and the
volumes of undo steps pointed at their files after a save moved them.

Blender's Python API does not list the undo steps, so this keeps a superset, in the module
(undo does not touch it): every file a result of this session was made with (importer), and
every file a volume used when the file was opened or after an undo or redo. Opening a file
starts a new history: then only what that file uses is reachable. A save that moves results
next to the .blend records where each file went; an undo or redo that brings back a volume
pointing at the old place is pointed at the new one."""

import os
from typing import Dict, Iterable, Set

import bpy
from bpy.app.handlers import persistent

from ...core import cleanup

RESULT_VOX_PROPERTY = "hyvox_vox"  # on a result object: its (first) .vox file

_reachable: Set[str] = set()
_moved: Dict[str, str] = {}


def remember(paths: Iterable[str]) -> None:
    _reachable.update(cleanup.file_key(p) for p in paths if p)


def remember_results(results) -> None:
    """The files of a run's results (pipeline.GroupResult): every frame's .vdb and .vox."""
    for result in results:
        remember(list(result.files) + list(result.vox_files))


def used_files():
    """(single files, first files of sequences) the open file's volumes and results use,
    absolute: the .vdb of every volume and the .vox every result object names."""
    singles, sequences = [], []
    for volume in bpy.data.volumes:
        if volume.filepath:
            (sequences if volume.is_sequence else singles).append(bpy.path.abspath(volume.filepath))
    for obj in bpy.data.objects:
        vox = obj.get(RESULT_VOX_PROPERTY)
        if vox:
            singles.append(bpy.path.abspath(str(vox)))
    return singles, sequences


def kept_keys():
    """The keys (cleanup.file_key) of the files the open file uses (cleanup.used_keys) or the
    undo history may reach: what Clean Unused Files keeps and a save moves."""
    return cleanup.used_keys(*used_files()) | _reachable


def _remember_used() -> None:
    singles, sequences = used_files()
    remember(singles)
    for first in sequences:
        remember(cleanup.sequence_files(first))


def record_move(old: str, new: str) -> None:
    _moved[cleanup.file_key(old)] = new
    remember([new])


def blend_relative(path: str) -> str:
    """Relative to the .blend when it is saved (the project folder can move)."""
    if bpy.data.filepath:
        try:
            return bpy.path.relpath(path)
        except ValueError:  # another drive on Windows
            pass
    return path


def repoint_moved() -> int:
    """Point volumes (and results' .vox names) whose file a save moved at the new place;
    returns how many it changed."""
    changed = 0
    for volume in bpy.data.volumes:
        new = _moved.get(cleanup.file_key(bpy.path.abspath(volume.filepath))) if volume.filepath else None
        if new is not None and os.path.exists(new):
            volume.filepath = blend_relative(new)
            changed += 1
    for obj in bpy.data.objects:
        vox = obj.get(RESULT_VOX_PROPERTY)
        new = _moved.get(cleanup.file_key(bpy.path.abspath(str(vox)))) if vox else None
        if new is not None and os.path.exists(new):
            obj[RESULT_VOX_PROPERTY] = blend_relative(new)
            changed += 1
    return changed


@persistent
def _after_undo_or_redo(*_args):
    repoint_moved()
    _remember_used()


@persistent
def _after_load(*_args):
    _reachable.clear()
    _moved.clear()
    _remember_used()


_HANDLERS = (("undo_post", _after_undo_or_redo), ("redo_post", _after_undo_or_redo), ("load_post", _after_load))


def register():
    for name, handler in _HANDLERS:
        getattr(bpy.app.handlers, name).append(handler)
    try:
        _remember_used()  # enabled in a session with a file open
    except AttributeError:  # at start-up bpy.data is not readable yet: load_post does it
        pass


def unregister():
    for name, handler in _HANDLERS:
        handlers = getattr(bpy.app.handlers, name)
        if handler in handlers:
            handlers.remove(handler)
