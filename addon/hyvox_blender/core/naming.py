# SPDX-License-Identifier: GPL-3.0-or-later
"""Names of output files and Blender objects, in one place so that re-running finds
and replaces its previous result instead of piling up copies."""

import os
import re
import secrets
import zlib
from typing import Optional, Sequence

from . import session_folder

CACHE_FOLDER = "hyvox_cache"
VOXELS_SUFFIX = "_voxels"
FRAME_DIGITS = 4  # name_0001.vdb: Blender reads the frame from the trailing digits


def _clean(name: str) -> str:
    return re.sub(r"[^A-Za-z0-9._-]+", "_", name).strip("._") or "volume"


def volume_file_name(source_name: str, frame: Optional[int] = None, run_tag: Optional[str] = None) -> str:
    """Name_voxels[_TAG][_0001].vdb. The run tag (new_run_tag) makes every run's files new
    ones, so an undo step that brings back an earlier volume finds its own file intact."""
    stem = _clean(source_name) + VOXELS_SUFFIX
    if run_tag:
        stem += "_" + run_tag  # ends in a letter: no stray frame number
    if frame is None:
        return stem + ".vdb"
    return f"{stem}_{frame:0{FRAME_DIGITS}d}.vdb"


def new_run_tag() -> str:
    """A short tag unique to one run: 'r' + 6 random hex digits + 'x' (ends in a letter:
    Blender takes a sequence's frame number from the last digits of the name)."""
    return f"r{secrets.token_hex(3)}x"


# Files a run writes (with or without a run tag, single or a frame of a sequence); the
# only files "Clean unused voxel files" may delete.
VOXEL_FILE = re.compile(r".+" + VOXELS_SUFFIX + r"(_r[0-9a-f]{6}x)?(_\d+)?\.(vdb|vox)")


def is_voxel_file(name: str) -> bool:
    return VOXEL_FILE.fullmatch(name) is not None


def result_stem(group_name: str, key: str, sources: int, fixed_names: bool = False) -> str:
    """The stem of a result's files: the result's name, as a file can hold it. A run with new
    file names (a run tag) makes at most one group, so its group's name is unique in the run
    and the tag makes it unique across runs. A hash of the sources is added where that is not
    enough: to a name a file cannot hold as it is ("a/b" and "a_b" both clean to "a_b", and
    two objects can be voxelized apart in one run), and to a group's name under fixed names
    (another selection led by the same object makes the same "A_and_1_more")."""
    if _clean(group_name) == group_name and (sources == 1 or not fixed_names):
        return group_name
    return f"{group_name}_{zlib.crc32(key.encode()):08x}"


def staging_path(final_path: str) -> str:
    """Where a run writes before it commits: a hidden sibling, renamed into place only when
    the whole run succeeded, so a cancelled run leaves the previous files intact."""
    folder, name = os.path.split(final_path)
    return os.path.join(folder, f".{name}.{os.getpid()}.partial")


def object_name(source_name: str) -> str:
    return source_name + VOXELS_SUFFIX


def group_name(source_names: Sequence[str], active_name: Optional[str]) -> str:
    """One volume for several objects is named after the active object (or the first)."""
    if len(source_names) == 1:
        return source_names[0]
    lead = active_name if active_name in source_names else sorted(source_names)[0]
    return f"{lead}_and_{len(source_names) - 1}_more"


def group_key(source_names: Sequence[str]) -> str:
    """Identity of a result: the sorted source names. Stored on the volume object so a
    re-run of the same selection replaces it."""
    return "\n".join(sorted(source_names))


_unsaved_dir: Optional[str] = None


def unsaved_output_dir(create: bool = True) -> Optional[str]:
    """This session's own folder for the results of a file not saved yet, made with mkdtemp
    when first needed (session_folder.py): two Blender sessions never write into each other's
    folder. On a save the add-on moves its files next to the .blend and removes the folder
    (forget_unsaved_output_dir). None if not made yet and create is False."""
    global _unsaved_dir
    if (_unsaved_dir is None or not os.path.isdir(_unsaved_dir)) and create:
        _unsaved_dir = session_folder.make()
    return _unsaved_dir


def forget_unsaved_output_dir() -> None:
    """The folder is gone (removed after a save): the next unsaved result makes a new one."""
    global _unsaved_dir
    _unsaved_dir = None


def default_output_dir(blend_path: str) -> str:
    """A cache folder next to the .blend (hyvox_cache/<blend name>/), or this session's own
    temporary folder for an unsaved file."""
    if blend_path:
        folder, name = os.path.split(os.path.abspath(blend_path))
        return os.path.join(folder, CACHE_FOLDER, os.path.splitext(name)[0])
    return unsaved_output_dir()
