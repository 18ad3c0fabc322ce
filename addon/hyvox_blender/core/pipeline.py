# SPDX-License-Identifier: GPL-3.0-or-later
"""A run: for each frame, export (callback into the bpy layer, main thread), then
voxelize and write every group (main thread in background mode, a worker thread in the
UI). Files go to staging paths and are renamed into place only when the whole run
succeeds, so a cancelled or failed run leaves the previous results untouched."""

import os
import threading
import time
from dataclasses import dataclass, field
from typing import Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np

from . import backend, live_key, naming, vox
from .blocks import BlocksMesh, blocks_mesh
from .errors import CancelledError, HyvoxError
from .settings import VoxelizeSettings


@dataclass
class Group:
    """What becomes one Volume object: one source object, or the whole selection."""

    name: str
    sources: List[str]
    lead: str = ""  # the source the volume is parented to (default: the first)

    def __post_init__(self):
        self.lead = self.lead or self.sources[0]

    @property
    def key(self) -> str:
        return naming.group_key(self.sources)


@dataclass
class GroupMesh:
    group: Group
    vertices: np.ndarray  # (N,3) float32, world space
    triangles: np.ndarray  # (M,3) uint32 (what the module uses natively)
    colour: Dict[str, np.ndarray] = field(default_factory=dict)  # colour.combine's keyword arguments


@dataclass
class GroupResult:
    group: Group
    files: List[str] = field(default_factory=list)  # final paths, one per frame
    frames: Optional[List[int]] = None
    voxel_size: float = 0.0
    origin: Tuple[float, float, float] = (0.0, 0.0, 0.0)
    dims: Tuple[int, int, int] = (0, 0, 0)
    voxel_counts: List[int] = field(default_factory=list)
    triangles: int = 0
    method: str = ""
    stats: dict = field(default_factory=dict)  # of the last frame
    blocks: Optional[BlocksMesh] = None  # settings.blocks: the blocks of the (one) frame
    vox_files: List[str] = field(default_factory=list)  # settings.export_vox: one per frame
    has_color: bool = False  # the .vdb has a `color` grid (the volume's material shows it)
    geometry_digest: str = ""  # settings.live: the exported geometry's (live_key), for Live's cache


@dataclass
class Timings:
    """Milliseconds per stage, summed over frames and groups."""

    export_ms: float = 0.0
    voxelize_ms: float = 0.0
    write_ms: float = 0.0
    import_ms: float = 0.0

    @property
    def total_ms(self) -> float:
        return self.export_ms + self.voxelize_ms + self.write_ms + self.import_ms


def merge_meshes(parts: Sequence[Tuple[np.ndarray, np.ndarray]]) -> Tuple[np.ndarray, np.ndarray]:
    """Concatenate (vertices, triangles) pairs into one mesh, offsetting indices."""
    if len(parts) == 1:
        return parts[0]
    offsets = np.cumsum([0] + [len(v) for v, _ in parts[:-1]])
    vertices = np.concatenate([v for v, _ in parts]).astype(np.float32, copy=False)
    triangles = np.concatenate([t.astype(np.uint32, copy=False) + np.uint32(o) for (_, t), o in zip(parts, offsets)])
    return vertices, triangles


ExportFrame = Callable[[Optional[int]], List[GroupMesh]]


class Pipeline:
    def __init__(
        self,
        settings: VoxelizeSettings,
        output_dir: str,
        export_frame: ExportFrame,
        module=None,
        run_tag: Optional[str] = None,
    ):
        """run_tag (naming.new_run_tag): this run's files get new names, never an earlier
        run's; None: fixed names, rewritten by each run (farm chunks that assemble)."""
        self.settings = settings.validate()
        self.output_dir = output_dir
        self.run_tag = run_tag
        self.export_frame = export_frame
        self.module = module if module is not None else backend.load_module()
        self.method = backend.resolve_method(self.module, settings.method, settings.options.get("gl_device", ""))
        # Settings changed for another method: the operator reports them (INFO).
        self.ignored_options: List[str] = backend.ignored_settings(self.module, settings, self.method)
        self.frames: List[Optional[int]] = list(settings.frames) if settings.is_sequence else [None]
        self.results: Dict[str, GroupResult] = {}
        self.timings = Timings()
        self._staged: List[Tuple[str, str]] = []  # (staging, final)
        self._frame_index = 0
        self._groups_in_frame = 1
        self._group_index = 0
        self._token = None
        self._stage = 0  # 0 voxelize, 1 write (for progress)
        self._cancelled = False
        self._thread: Optional[threading.Thread] = None
        self._error: Optional[BaseException] = None
        # abandon(): the caller has stopped waiting; the worker deletes what it staged.
        self._lock = threading.Lock()
        self._abandoned = False
        self._worker_running = False

    # -- driving the run --------------------------------------------------------------
    def run(self) -> Dict[str, GroupResult]:
        """Synchronously (background mode, scripts, redo)."""
        try:
            for _ in self.frames:
                self._work(self._export_next())
            self.commit()
        except BaseException:
            self.discard()
            raise
        return self.results

    def start_next_frame(self) -> bool:
        """Export the next frame (caller's thread: bpy is not thread-safe) and voxelize it
        on a worker thread. False when every frame is done."""
        if self._frame_index >= len(self.frames):
            return False
        meshes = self._export_next()
        self._error = None
        self._thread = threading.Thread(target=self._work_guarded, args=(meshes,), name="hyvox-voxelize", daemon=True)
        self._worker_running = True
        self._thread.start()
        return True

    def worker_busy(self) -> bool:
        return self._thread is not None and self._thread.is_alive()

    def finish_frame(self) -> None:
        """After the worker ended: re-raise its error in the caller's thread."""
        if self._thread is not None:
            self._thread.join()
            self._thread = None
        if self._error is not None:
            error, self._error = self._error, None
            raise error

    def cancel(self) -> None:
        self._cancelled = True
        token = self._token
        if token is not None:
            token.cancel()

    def abandon(self) -> None:
        """Cancel without waiting (Esc): whatever stage the worker is in, the caller goes
        on at once; the files it staged are deleted when it ends (now, if none runs)."""
        self.cancel()
        with self._lock:
            self._abandoned = True
            running = self._worker_running
        if not running:
            self.discard()

    def wait(self) -> None:
        if self._thread is not None:
            self._thread.join()

    @property
    def progress(self) -> float:
        """0..1 over all frames and groups."""
        frames = max(len(self.frames), 1)
        groups = max(self._groups_in_frame, 1)
        done_frames = max(self._frame_index - 1, 0) if self.worker_busy() else self._frame_index
        # Each group: voxelizing is the first 80% of its share, writing the last 20%.
        stage_share = (
            0.8 * backend.token_progress(self._token)
            if self._stage == 0
            else 0.8 + 0.2 * backend.token_progress(self._token)
        )
        within = (self._group_index + stage_share) / groups
        if not self.worker_busy():
            within = 0.0
        return min((done_frames + within) / frames, 1.0)

    @property
    def current_frame(self) -> Optional[int]:
        """The frame being voxelized (None outside sequences)."""
        return self.frames[max(self._frame_index - 1, 0)]

    # -- staging ----------------------------------------------------------------------
    def commit(self) -> None:
        """Rename every staged file into place; a failure leaves the rest staged for
        discard() and becomes a HyvoxError."""
        while self._staged:
            staging, final = self._staged[0]
            try:
                os.replace(staging, final)
            except OSError as exc:
                raise HyvoxError(f"cannot write {final}: {exc}") from exc
            self._staged.pop(0)

    def discard(self) -> None:
        for staging, _ in self._staged:
            try:
                os.remove(staging)
            except OSError:
                pass
        self._staged.clear()

    # -- work -------------------------------------------------------------------------
    def _export_next(self) -> List[GroupMesh]:
        frame = self.frames[self._frame_index]
        self._frame_index += 1
        start = time.perf_counter()
        meshes = self.export_frame(frame)
        self.timings.export_ms += (time.perf_counter() - start) * 1000.0
        if not meshes:
            raise HyvoxError("nothing to voxelize")
        self._groups_in_frame = len(meshes)
        self._group_index = 0
        return meshes

    def _final_path(self, group: Group, frame: Optional[int]) -> str:
        stem = naming.result_stem(group.name, group.key, len(group.sources), fixed_names=self.run_tag is None)
        return os.path.join(self.output_dir, naming.volume_file_name(stem, frame, self.run_tag))

    def _work_guarded(self, meshes: List[GroupMesh]) -> None:
        try:
            self._work(meshes)
        except BaseException as exc:  # handed to the main thread by finish_frame()
            self._error = exc
        finally:
            with self._lock:
                self._worker_running = False
                if self._abandoned:
                    self.discard()

    def _work(self, meshes: List[GroupMesh]) -> None:
        frame = self.frames[self._frame_index - 1]
        try:
            os.makedirs(self.output_dir, exist_ok=True)
        except OSError as exc:
            raise HyvoxError(f"cannot create the output folder {self.output_dir}: {exc}") from exc
        for index, mesh in enumerate(meshes):
            self._group_index = index
            if self._cancelled:
                raise CancelledError("voxelization cancelled")
            result = self.results.get(mesh.group.key)
            if result is None:
                result = GroupResult(mesh.group, frames=[] if frame is not None else None, method=self.method)
                self.results[mesh.group.key] = result
            # Every frame of a sequence uses the first frame's voxel size: the Volume
            # object's half-voxel correction and the look must not change per frame.
            first_size = result.voxel_size if result.voxel_size else None
            self._token = backend.make_token(self.module)
            start = time.perf_counter()
            # Solid runs too: the inside voxels take their colour from the surface inward
            # (the module's solid-mode attributes).
            colour = mesh.colour if self.settings.color else None
            grid = backend.voxelize(
                self.module,
                mesh.vertices,
                mesh.triangles,
                self.settings,
                self.method,
                voxel_size=first_size,
                token=self._token,
                colour=colour,
            )
            self.timings.voxelize_ms += (time.perf_counter() - start) * 1000.0
            if self._cancelled:
                raise CancelledError("voxelization cancelled")

            final = self._final_path(mesh.group, frame)
            staging = naming.staging_path(final)
            start = time.perf_counter()
            # A token of its own: the write (grid build, then the bytes) stops on Esc too,
            # and its progress restarts from 0 for the progress bar's second half.
            self._token = backend.make_token(self.module)
            self._stage = 1
            if self._cancelled:
                raise CancelledError("voxelization cancelled")
            try:
                grid.write_vdb(staging, cancel=self._token, **backend.write_options(self.module, self.settings))
            except self.module.Cancelled as exc:
                raise CancelledError("voxelization cancelled") from exc
            except (OSError, RuntimeError, ValueError) as exc:
                raise HyvoxError(f"cannot write {final}: {exc}") from exc
            finally:
                self._stage = 0
            self._staged.append((staging, final))
            if self.settings.blocks or self.settings.export_vox:
                if self._cancelled:
                    raise CancelledError("voxelization cancelled")
                self._blocks_and_vox(grid, result, final)
            self.timings.write_ms += (time.perf_counter() - start) * 1000.0

            result.files.append(final)
            if frame is not None:
                result.frames.append(frame)
            result.voxel_size = float(grid.voxel_size)
            result.origin = tuple(float(x) for x in grid.origin)
            result.dims = tuple(int(x) for x in grid.dims)
            result.stats = dict(grid.stats)
            result.voxel_counts.append(int(grid.voxel_count))
            result.triangles = int(len(mesh.triangles))
            result.has_color = bool(colour)
            if self.settings.live:
                result.geometry_digest = live_key.geometry_digest([mesh])
        self._group_index = len(meshes)

    def _blocks_and_vox(self, grid, result: GroupResult, final_vdb: str) -> None:
        """The other outputs of the same voxels: the blocks mesh (imported on the main
        thread) and the .vox file (staged like the .vdb)."""
        ijk = grid.coords()
        colors = backend.voxel_colors(grid)
        if self.settings.blocks:
            result.blocks = blocks_mesh(ijk, float(grid.voxel_size), tuple(grid.origin), colors)
        if self.settings.export_vox:
            final = os.path.splitext(final_vdb)[0] + ".vox"
            staging = naming.staging_path(final)
            try:
                vox.write_vox(staging, ijk, colors)
            except (OSError, ValueError) as exc:
                raise HyvoxError(f"cannot write {final}: {exc}") from exc
            self._staged.append((staging, final))
            result.vox_files.append(final)
