# SPDX-License-Identifier: GPL-3.0-or-later
"""Which voxel files nothing uses any more ("Clean Unused Files"). Every run writes new files
(naming.new_run_tag) so that undo never meets an overwritten one; the files of replaced
results therefore stay until this clean-up removes them. A result's .vdb and .vox count as
used together."""

import os
import re
from typing import Iterable, List, Set

_FRAME = re.compile(r"(.*?)(\d+)(\.\w+)")


def file_key(path: str) -> str:
    """One spelling of a path to compare paths by: links resolved, case as the system compares it."""
    return os.path.normcase(os.path.realpath(path))


def sequence_files(first_file: str) -> List[str]:
    """The files of the sequence whose first file is given: the same name up to the last
    digits (the frame number), any frame. Blender reads a volume sequence the same way."""
    folder, name = os.path.split(first_file)
    match = _FRAME.fullmatch(name)
    if match is None or not os.path.isdir(folder):
        return [first_file]
    stem, ext = match.group(1), match.group(3)
    frame = re.compile(re.escape(stem) + r"\d+" + re.escape(ext))
    return [os.path.join(folder, n) for n in os.listdir(folder) if frame.fullmatch(n)]


RESULT_EXTENSIONS = (".vdb", ".vox")  # a result's files: one stem, the .vox beside the .vdb


def _with_exports(path: str) -> List[str]:
    """The file and the others of its result (the .vox of a .vdb, the .vdb of a .vox)."""
    stem = os.path.splitext(path)[0]
    return [path] + [stem + ext for ext in RESULT_EXTENSIONS]


def used_keys(used_files: Iterable[str], used_sequences: Iterable[str]) -> Set[str]:
    """The keys (file_key) of the files in use: used_files, the frames of the sequences
    starting at used_sequences, and the other file of each one's result (the .vox beside a
    used .vdb, the .vdb beside a used .vox)."""
    used: Set[str] = {file_key(e) for p in used_files for e in _with_exports(p)}
    for first in used_sequences:
        used.update(file_key(e) for p in sequence_files(first) for e in _with_exports(p))
    return used


def unused_files(
    folders: Iterable[str],
    used_files: Iterable[str],
    used_sequences: Iterable[str],
    is_voxel_file,
    keep: Iterable[str] = (),
) -> List[str]:
    """The files in `folders` (not below them) that is_voxel_file(name) accepts and nothing
    uses (used_keys) and that are not among `keep` (keys: what the undo history may reach).
    Sorted."""
    used = used_keys(used_files, used_sequences) | set(keep)
    unused = set()
    for folder in {file_key(f) for f in folders}:
        if not os.path.isdir(folder):
            continue
        for name in os.listdir(folder):
            path = os.path.join(folder, name)
            if is_voxel_file(name) and os.path.isfile(path) and file_key(path) not in used:
                unused.add(path)
    return sorted(unused)
