# SPDX-License-Identifier: GPL-3.0-or-later
"""One Live run, the part that needs no Blender: from the exported meshes to the files of
their voxels. It runs on a worker thread in the UI (on the caller's in background mode and
while rendering) and never touches Blender data: the key of the input (core/live_key.py),
the cache (core/live_cache.py) when the key was seen, else the run pipeline (voxelize,
write to staging files, rename into place: a cancelled or failed run leaves no file)."""

import time
from dataclasses import dataclass, field
from typing import Dict, List, Optional

from . import live_key, naming
from .errors import CancelledError, HyvoxError
from .live_cache import CacheEntry, LiveCache
from .pipeline import GroupMesh, GroupResult, Pipeline
from .settings import VoxelizeSettings


@dataclass
class LiveInput:
    """What the main thread exported for one run of one live volume."""

    meshes: List[GroupMesh]  # one group: the volume's sources, world space
    settings: VoxelizeSettings  # the volume's own: its voxel size, a fixed lattice, no frames
    folder: str  # where the files go
    fingerprint: str  # the options as text (live_key.options_fingerprint)
    owner: str = ""  # the volume (cache entries are dropped with it)
    frame: Optional[int] = None
    export_ms: float = 0.0


@dataclass
class LiveOutput:
    key: str
    result: GroupResult
    cached: bool  # shown from the cache: nothing voxelized
    timings_ms: Dict[str, float] = field(default_factory=dict)  # export, key, voxelize, write

    @property
    def files(self) -> List[str]:
        return list(self.result.files) + list(self.result.vox_files)


class LiveRun:
    def __init__(self, job: LiveInput, cache: LiveCache, module=None):
        self.job = job
        self.cache = cache
        self.key: Optional[str] = None
        # Made here, on the caller's thread: it validates the settings and resolves Auto.
        self.pipeline = Pipeline(job.settings, job.folder, self._export, module=module, run_tag=naming.new_run_tag())
        self._cancelled = False

    def _export(self, frame):
        return self.job.meshes  # exported already, on the main thread

    def cancel(self) -> None:
        """From any thread: the voxelizer and the write stop at their next check; whatever
        was staged is deleted."""
        self._cancelled = True
        self.pipeline.abandon()

    @property
    def cancelled(self) -> bool:
        return self._cancelled

    @property
    def method(self) -> str:
        return self.pipeline.method

    def __call__(self) -> LiveOutput:
        timings = {"export": self.job.export_ms}
        start = time.perf_counter()
        self.key = live_key.run_key(live_key.geometry_digest(self.job.meshes), self.job.fingerprint)
        timings["key"] = (time.perf_counter() - start) * 1000.0
        hit = self.cache.get(self.key)
        if hit is not None:
            return LiveOutput(self.key, hit.result, True, timings)
        if self._cancelled:
            raise CancelledError("live update cancelled")
        results = self.pipeline.run()  # the staged files are renamed into place, or deleted
        if len(results) != 1:
            raise HyvoxError(f"a live volume is one group, not {len(results)}")
        (result,) = results.values()
        timings["voxelize"] = self.pipeline.timings.voxelize_ms
        timings["write"] = self.pipeline.timings.write_ms
        output = LiveOutput(self.key, result, False, timings)
        self.cache.put(CacheEntry(self.key, result, owner=self.job.owner, frame=self.job.frame), keep=output.files)
        return output
