# SPDX-License-Identifier: GPL-3.0-or-later
# Stubs of the compiled module hyvox._core (private: use the hyvox package).
import os
from typing import Dict, Callable, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str
METHODS: Tuple[str, ...]
MODES: Tuple[str, ...]

class Cancelled(Exception): ...
class ResourceError(RuntimeError): ...
class BackendError(RuntimeError): ...

class CancelToken:
    def __init__(self) -> None: ...
    def cancel(self) -> None: ...
    def reset(self) -> None: ...
    @property
    def cancelled(self) -> bool: ...
    @property
    def progress(self) -> int: ...
    @property
    def running(self) -> bool: ...

class VoxelGrid:
    def coords(self) -> npt.NDArray[np.int32]: ...
    def world_centres(self) -> npt.NDArray[np.float64]: ...
    def counts(self) -> Tuple[npt.NDArray[np.int32], npt.NDArray[np.uint32]]: ...
    def to_dense(self) -> npt.NDArray[np.bool_]: ...
    def write_vdb(self, path: Union[str, os.PathLike[str]], threads: int = 0) -> None: ...
    @property
    def origin(self) -> Tuple[float, float, float]: ...
    @property
    def voxel_size(self) -> float: ...
    @property
    def dims(self) -> Tuple[int, int, int]: ...
    @property
    def voxel_count(self) -> int: ...
    @property
    def method(self) -> str: ...
    @property
    def mode(self) -> str: ...
    @property
    def stats(self) -> dict: ...
    def __len__(self) -> int: ...

def voxelize(
    vertices: npt.NDArray[np.float32],
    triangles: npt.NDArray[np.uint32],
    *,
    uvs: Optional[npt.NDArray[np.float32]] = ...,
    normals: Optional[npt.NDArray[np.float32]] = ...,
    resolution: int = ...,
    voxel_size: Optional[float] = ...,
    mode: str = ...,
    method: str = ...,
    padding: int = ...,
    threads: int = ...,
    origin: Optional[Tuple[float, float, float]] = ...,
    bounds: Optional[Tuple[Sequence[float], Sequence[float]]] = ...,
    memory_budget: Optional[int] = ...,
    gl_device: str = ...,
    shader_dir: str = ...,
    hybrid_cutoff: float = ...,
    tess_gamma: float = ...,
    pn_triangles: bool = ...,
    displacement_image: str = ...,
    displacement_strength: float = ...,
    displacement_midlevel: float = ...,
    displacement_pixels: Optional[npt.NDArray[np.float32]] = ...,
    tess_counts: bool = ...,
    tess_measure_accuracy: bool = ...,
    cancel: Optional[CancelToken] = ...,
    progress: Optional[Callable[[int], object]] = ...,
) -> VoxelGrid: ...
def read_mesh(
    path: Union[str, os.PathLike[str]],
) -> Tuple[
    npt.NDArray[np.float32],
    npt.NDArray[np.uint32],
    Optional[npt.NDArray[np.float32]],
    Optional[npt.NDArray[np.float32]],
]: ...
def gl_devices() -> list[Dict[str, Union[int, str, bool]]]: ...
