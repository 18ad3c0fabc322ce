# SPDX-License-Identifier: GPL-3.0-or-later
"""The results of Live runs, by key (core/live_key.py), so that a state seen before (a
frame scrubbed back to, an undo step) shows again without voxelizing.

An entry is the files one run wrote (.vdb, .vox) and what stays in memory with them (the
Blocks mesh). The cache is bounded twice: the bytes of its files on disk and the bytes it
holds in memory; past either bound the least recently used entries go, and their files are
deleted, except files still in use (shown by a volume, or referenced by a saved .blend),
which the caller names at each eviction. Files the cache did not write are never deleted."""

import os
import threading
from collections import OrderedDict
from dataclasses import dataclass, field
from typing import Callable, Iterable, List, Optional, Set

from .pipeline import GroupResult

DEFAULT_DISK_BYTES = 2 << 30
DEFAULT_MEMORY_BYTES = 512 << 20


def _norm(path: str) -> str:
    return os.path.normcase(os.path.realpath(path))


def _delete(path: str) -> bool:
    try:
        os.remove(path)
    except FileNotFoundError:
        return True
    except OSError:
        return False
    return True


@dataclass
class CacheEntry:
    key: str
    result: GroupResult  # files, voxel size, origin, counts, the Blocks mesh
    owner: str = ""  # the live volume that made it
    frame: Optional[int] = None  # the frame it was made at
    disk_bytes: int = 0
    memory_bytes: int = 0
    files: List[str] = field(default_factory=list)

    def __post_init__(self):
        if not self.files:
            self.files = list(self.result.files) + list(self.result.vox_files)
        if not self.disk_bytes:
            self.disk_bytes = sum(os.path.getsize(p) for p in self.files if os.path.exists(p))
        if not self.memory_bytes and self.result.blocks is not None:
            blocks = self.result.blocks
            self.memory_bytes = sum(
                a.nbytes for a in (blocks.vertices, blocks.faces, blocks.face_colors) if a is not None
            )


class LiveCache:
    def __init__(
        self,
        max_disk_bytes: int = DEFAULT_DISK_BYTES,
        max_memory_bytes: int = DEFAULT_MEMORY_BYTES,
        in_use: Callable[[], Iterable[str]] = lambda: (),
    ):
        """in_use(): the paths that must not be deleted now (asked on the caller's thread at
        each eviction: the main thread's view of what volumes show)."""
        self.max_disk_bytes = max_disk_bytes
        self.max_memory_bytes = max_memory_bytes
        self.in_use = in_use
        self._entries: "OrderedDict[str, CacheEntry]" = OrderedDict()  # least recently used first
        self._written: Set[str] = set()  # every file the cache took in (and may delete)
        self._lock = threading.Lock()

    # -- lookups ----------------------------------------------------------------------
    def get(self, key: str) -> Optional[CacheEntry]:
        """The entry for key when all its files are still there (a save may have moved them,
        someone may have deleted them), marked as just used."""
        with self._lock:
            entry = self._entries.get(key)
            if entry is None:
                return None
            if not all(os.path.exists(p) for p in entry.files):
                del self._entries[key]
                return None
            self._entries.move_to_end(key)
            return entry

    def __contains__(self, key: str) -> bool:
        with self._lock:
            return key in self._entries

    def __len__(self) -> int:
        with self._lock:
            return len(self._entries)

    @property
    def disk_bytes(self) -> int:
        with self._lock:
            return sum(e.disk_bytes for e in self._entries.values())

    @property
    def memory_bytes(self) -> int:
        with self._lock:
            return sum(e.memory_bytes for e in self._entries.values())

    def files(self) -> Set[str]:
        with self._lock:
            return {p for e in self._entries.values() for p in e.files}

    # -- changes ----------------------------------------------------------------------
    def put(self, entry: CacheEntry, keep: Iterable[str] = ()) -> List[str]:
        """Add (or refresh) an entry, then evict past the bounds; keep: paths the caller is
        about to show (not deleted whatever in_use says). Returns the deleted files."""
        with self._lock:
            old = self._entries.pop(entry.key, None)
            self._entries[entry.key] = entry
            self._written.update(_norm(p) for p in entry.files)
            replaced = [p for p in (old.files if old else []) if _norm(p) not in {_norm(f) for f in entry.files}]
        protected = {_norm(p) for p in list(self.in_use()) + list(keep) + entry.files}
        deleted = [p for p in replaced if _norm(p) not in protected and _delete(p)]
        return deleted + self.evict(protected)

    def evict(self, protected: Optional[Set[str]] = None) -> List[str]:
        """Drop least recently used entries until both bounds hold; their files are deleted
        unless protected (normalised paths; default: in_use())."""
        if protected is None:
            protected = {_norm(p) for p in self.in_use()}
        deleted = []
        with self._lock:
            keys = list(self._entries)
            for key in keys:
                disk = sum(e.disk_bytes for e in self._entries.values())
                memory = sum(e.memory_bytes for e in self._entries.values())
                if disk <= self.max_disk_bytes and memory <= self.max_memory_bytes:
                    break
                entry = self._entries[key]
                if any(_norm(p) in protected for p in entry.files):
                    continue  # shown now: it stays, and so do its files
                del self._entries[key]
                deleted += [p for p in entry.files if _delete(p)]
        return deleted

    def remove(self, key: str, protected: Iterable[str] = ()) -> List[str]:
        """Forget one entry and delete its files unless protected."""
        with self._lock:
            entry = self._entries.pop(key, None)
        if entry is None:
            return []
        keep = {_norm(p) for p in protected}
        return [p for p in entry.files if _norm(p) not in keep and _delete(p)]

    def drop_owner(self, owner: str, protected: Iterable[str] = ()) -> List[str]:
        """Forget every entry of one volume (Live switched off, the volume deleted) and
        delete their files unless protected (the one the volume goes on showing)."""
        with self._lock:
            keys = [k for k, e in self._entries.items() if e.owner == owner]
        return [p for key in keys for p in self.remove(key, protected)]

    def clear(self, protected: Iterable[str] = ()) -> List[str]:
        """Forget every entry and delete the files the cache wrote, except the protected ones
        (a saved .blend's, the shown ones when the session goes on), which are the cache's no
        more: from now on they are files like any run's."""
        keep = {_norm(p) for p in protected}
        with self._lock:
            self._entries.clear()
            written, self._written = self._written, set()
        return [p for p in sorted(written) if p not in keep and os.path.exists(p) and _delete(p)]
