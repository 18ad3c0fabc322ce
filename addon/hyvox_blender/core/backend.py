# SPDX-License-Identifier: GPL-3.0-or-later
"""The one place that talks to the compiled hyvox module: finding it, choosing the
method, calling voxelize with a cancel token, turning its errors into HyvoxError.

`settings` below is a run's core.settings.VoxelizeSettings; this module does not import
that one (settings imports this), so the add-on's imports have no cycle."""

import importlib
import importlib.util
import os
import threading
from typing import List, Optional

import numpy as np

from . import module_diagnosis
from .errors import CancelledError, HyvoxError, ModuleMissingError

AUTO_METHOD = "auto"  # the add-on's own method: hybrid when a GPU runs GL here, else cpu

_module = None
_gl_probe = {}  # gl_device -> bool, probed once per session: creating an EGL context is slow
_lock = threading.Lock()


def load_module():
    """The hyvox package the build copies into the add-on (hyvox_blender/hyvox/), else an
    installed one (the extension's wheel, pip, PYTHONPATH=B/python). When one is there but
    does not load, the error says why in plain words (module_diagnosis)."""
    global _module
    if _module is not None:
        return _module
    errors = []
    addon_dir = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parent = __package__.rpartition(".")[0]
    candidates = [(parent + ".hyvox", os.path.join(addon_dir, "hyvox"))] if parent else []
    candidates.append(("hyvox", None))
    for name, package_dir in candidates:
        if package_dir is None:
            spec = importlib.util.find_spec(name)  # locates without running it
            package_dir = os.path.dirname(spec.origin) if spec and spec.origin else None
        if package_dir is None or not os.path.isdir(package_dir):
            errors.append(f"{name}: not installed")
            continue
        try:
            module = importlib.import_module(name)
        except ImportError as exc:
            raise ModuleMissingError(module_diagnosis.explain(package_dir, exc)) from exc
        if hasattr(module, "voxelize"):
            _module = module
            return module
        errors.append(f"{name}: has no voxelize()")
    raise ModuleMissingError("the compiled hyvox module was not found (" + "; ".join(errors) + ")")


def gl_available(module, gl_device: str = "") -> bool:
    """Whether a hardware GL device can run the GL methods here. Mesa's llvmpipe runs them
    too, but on the CPU and much slower than the CPU method, so "auto" only picks a
    GL method for hardware (docs/why/addon-core.md)."""
    with _lock:
        if gl_device in _gl_probe:
            return _gl_probe[gl_device]
        ok = False
        if gl_device != "software":
            try:
                devices = module.gl_devices()
            except Exception:  # no EGL here at all
                devices = []
            if gl_device.isdigit():
                devices = [d for d in devices if d["index"] == int(gl_device)]
            ok = any(not d["software"] for d in devices)
        if ok:
            # The device exists; make sure a context and the shaders really work here.
            tri_v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=np.float32)
            tri_t = np.array([[0, 1, 2]], dtype=np.uint32)
            try:
                module.voxelize(tri_v, tri_t, resolution=4, method="hybrid", gl_device=gl_device)
            except Exception:
                ok = False
        _gl_probe[gl_device] = ok
        return ok


def resolve_method(module, method: str, gl_device: str = "") -> str:
    """The hyvox method a run of `method` uses: "auto" is hybrid where a hardware GL
    device runs it (gl_available), else cpu. module None (not loaded): no GL."""
    if method != AUTO_METHOD:
        return method
    return "hybrid" if module is not None and gl_available(module, gl_device) else "cpu"


def ignored_settings(module, settings, method: str) -> List[str]:
    """The options set away from the schema's default that `method` does not use, by the
    module's one rule (hyvox.ignored_options). The add-on passes every setting it has, so an
    option still at its default is no news and is not listed."""
    options = settings.options
    return [name for name in module.ignored_options(method, options) if options[name] != module.option(name).default]


def ignored_message(names: List[str], method: str) -> str:
    """The add-on's report for ignored_settings (the CLI's warning, in one line)."""
    return f"{', '.join(names)} {'does' if len(names) == 1 else 'do'} not apply to the {method} method: ignored"


def write_options(module, settings) -> dict:
    """The settings that are options of VoxelGrid.write_vdb (module.WRITE_OPTIONS: threads,
    the memory budget), by name."""
    names = {spec.name for spec in module.WRITE_OPTIONS}
    return {name: value for name, value in settings.options.items() if name in names}


def make_token(module):
    """A fresh cancel/progress token."""
    return module.CancelToken()


def token_progress(token) -> float:
    """0..1 progress of the running call (the token counts percent, -1 before start)."""
    if token is None:
        return 0.0
    return min(max(float(token.progress), 0.0) / 100.0, 1.0)


def voxelize(
    module,
    vertices: np.ndarray,
    triangles: np.ndarray,
    settings,
    method: str,
    voxel_size: Optional[float] = None,
    token=None,
    colour: Optional[dict] = None,
):
    """hyvox.voxelize with the run's settings. voxel_size: a sequence's first frame's, for
    every later frame (the module's rule lets it win over the resolution); with
    settings.fixed_lattice the module snaps the origin to whole multiples of it. colour: the
    colour source's keyword arguments (colour.combine); given, a `color` grid is made. With
    settings.sdf, an `sdf` level set too."""
    kwargs = dict(settings.options, method=method, snap_origin=settings.fixed_lattice)
    if voxel_size:
        kwargs["voxel_size"] = float(voxel_size)
    # Settings another method would use are dropped here (reported once per run by the
    # operator, see ignored_settings), so hyvox.voxelize has nothing to warn about.
    for name in module.ignored_options(method, list(kwargs)):
        del kwargs[name]
    attributes = (["color"] if colour else []) + (["sdf"] if settings.sdf else [])
    if colour:
        kwargs.update(colour)
    if attributes:
        kwargs["attributes"] = attributes
    if token is not None:
        kwargs["cancel"] = token
    try:
        return module.voxelize(vertices, triangles, **kwargs)
    except Exception as exc:  # every native failure becomes a report, never a crash
        if isinstance(exc, module.Cancelled):
            raise CancelledError("voxelization cancelled") from exc
        if isinstance(exc, MemoryError):
            raise HyvoxError("out of memory: lower the resolution or raise the memory budget") from exc
        if isinstance(exc, (ValueError, RuntimeError, TypeError, OSError)):
            raise HyvoxError(f"{method}: {exc}") from exc
        raise


def voxel_colors(grid) -> Optional[np.ndarray]:
    """The grid's per-voxel linear colours (K,3) in the order of grid.coords(), or None
    when it has no `color` grid; Blocks and .vox take their colours from here."""
    attributes = getattr(grid, "attributes", None)
    colors = attributes().get("color") if callable(attributes) else None
    return np.asarray(colors, dtype=np.float32) if colors is not None else None
