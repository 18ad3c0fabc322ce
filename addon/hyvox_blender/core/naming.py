# SPDX-License-Identifier: GPL-3.0-or-later
"""Names of output files and Blender objects, in one place so that re-running finds
and replaces its previous result instead of piling up copies."""
import os
import re
import tempfile
import zlib
from typing import Optional, Sequence

CACHE_FOLDER = "hyvox_cache"
VOXELS_SUFFIX = "_voxels"
FRAME_DIGITS = 4  # name_0001.vdb: Blender reads the frame from the trailing digits


def _clean(name: str) -> str:
    return re.sub(r"[^A-Za-z0-9._-]+", "_", name).strip("._") or "volume"


def volume_file_name(source_name: str, frame: Optional[int] = None) -> str:
    stem = _clean(source_name) + VOXELS_SUFFIX  # ends in a letter: no stray frame number
    if frame is None:
        return stem + ".vdb"
    return f"{stem}_{frame:0{FRAME_DIGITS}d}.vdb"


def result_stem(group_name: str, key: str, sources: int) -> str:
    """The stem of a result's files. One object's name is unique in Blender and kept as it
    is; a group of several objects ("A_and_1_more") or a name a file cannot hold ("a/b" and
    "a_b" both clean to "a_b") gets a hash of its sources, so no two results share a file,
    in one run or across runs."""
    if sources == 1 and _clean(group_name) == group_name:
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


def default_output_dir(blend_path: str) -> str:
    """A cache folder next to the .blend (hyvox_cache/<blend name>/), or in the temp folder
    for unsaved files."""
    if blend_path:
        folder, name = os.path.split(os.path.abspath(blend_path))
        return os.path.join(folder, CACHE_FOLDER, os.path.splitext(name)[0])
    return os.path.join(tempfile.gettempdir(), CACHE_FOLDER, "unsaved")
