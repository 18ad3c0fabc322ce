# SPDX-License-Identifier: GPL-3.0-or-later
"""Which voxel files no volume uses any more ("Clean unused voxel files"). Every run writes
new files (naming.new_run_tag) so that undo never meets an overwritten one; the files of
replaced results therefore stay until this clean-up removes them."""
import os
import re
from typing import Iterable, List, Set

_FRAME = re.compile(r"(.*?)(\d+)(\.\w+)")


def _key(path: str) -> str:
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


def unused_files(folders: Iterable[str], used_files: Iterable[str], used_sequences: Iterable[str],
                 is_voxel_file) -> List[str]:
    """The files in `folders` (not below them) that is_voxel_file(name) accepts and no volume
    uses: neither one of used_files nor a frame of a sequence starting at one of
    used_sequences. Sorted."""
    used: Set[str] = {_key(p) for p in used_files}
    for first in used_sequences:
        used.update(_key(p) for p in sequence_files(first))
    unused = set()
    for folder in {_key(f) for f in folders}:
        if not os.path.isdir(folder):
            continue
        for name in os.listdir(folder):
            path = os.path.join(folder, name)
            if is_voxel_file(name) and os.path.isfile(path) and _key(path) not in used:
                unused.add(path)
    return sorted(unused)
