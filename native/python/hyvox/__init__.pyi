# SPDX-License-Identifier: GPL-3.0-or-later
# Stubs of the hyvox package (see __init__.py for the documentation).
import os
from typing import Callable, Dict, Literal, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

from ._core import BackendError as BackendError
from ._core import Cancelled as Cancelled
from ._core import CancelToken as CancelToken
from ._core import ResourceError as ResourceError
from ._core import VoxelGrid as VoxelGrid
from ._core import gl_devices as gl_devices

__version__: str
METHODS: Tuple[str, ...]
MODES: Tuple[str, ...]
__all__: list[str]

def voxelize(
    vertices: npt.ArrayLike,
    triangles: npt.ArrayLike,
    resolution: int = 256,
    voxel_size: Optional[float] = None,
    mode: str = "conservative",
    method: str = "cpu",
    padding: int = 0,
    threads: int = 0,
    origin: Optional[Sequence[float]] = None,
    progress: Optional[Callable[[int], object]] = None,
    cancel: Optional[CancelToken] = None,
    *,
    uvs: Optional[npt.ArrayLike] = None,
    normals: Optional[npt.ArrayLike] = None,
    bounds: Optional[Tuple[Sequence[float], Sequence[float]]] = None,
    memory_budget: Optional[int] = None,
    gl_device: Optional[str] = None,
    shader_dir: Optional[str] = None,
    hybrid_cutoff: Optional[float] = None,
    tess_gamma: Optional[float] = None,
    pn_triangles: Optional[bool] = None,
    displacement_image: Optional[str] = None,
    displacement_strength: Optional[float] = None,
    displacement_midlevel: Optional[float] = None,
    displacement_pixels: Optional[npt.ArrayLike] = None,
    tess_counts: Optional[bool] = None,
    tess_measure_accuracy: Optional[bool] = None,
) -> VoxelGrid: ...
@overload
def read_mesh(
    path: Union[str, os.PathLike[str]], attributes: Literal[False] = False
) -> Tuple[npt.NDArray[np.float32], npt.NDArray[np.uint32]]: ...
@overload
def read_mesh(
    path: Union[str, os.PathLike[str]], attributes: Literal[True]
) -> Tuple[npt.NDArray[np.float32], npt.NDArray[np.uint32], Dict[str, npt.NDArray[np.float32]]]: ...
