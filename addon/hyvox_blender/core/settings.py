# SPDX-License-Identifier: GPL-3.0-or-later
"""One settings object per run, gathered once from the scene, the operator's keyword
arguments and the add-on preferences (the glTF exporter's pattern), then validated by the
native options schema."""

from typing import Any, Dict, List, Optional

from . import backend
from .backend import AUTO_METHOD
from .errors import SettingsError


class VoxelizeSettings:
    """method (a hyvox method or "auto"), separate, frames, and the hyvox.voxelize options
    by their schema names (hyvox.OPTIONS), passed to it as they are (the module decides the
    grid: voxel_size, when given, wins over resolution); an option left out takes the native
    default."""

    def __init__(
        self,
        method: str = AUTO_METHOD,
        separate: bool = False,
        frames: Optional[List[int]] = None,
        blocks: bool = False,
        export_vox: bool = False,
        color: bool = False,
        sdf: bool = False,
        fixed_lattice: bool = False,
        live: bool = False,
        **options: Any,
    ):
        self.method = method
        self.separate = separate  # one volume per object instead of one for the selection
        self.frames = frames  # None: the current frame only, no sequence
        self.blocks = blocks  # also build the blocks mesh (core/blocks.py)
        self.export_vox = export_vox  # also write a MagicaVoxel .vox beside each .vdb
        self.color = color  # also a `color` grid, from what the materials show
        # The run makes live volumes (the operator's live=True): one frame, and each group's
        # exported geometry is digested (GroupResult.geometry_digest) for Live's cache.
        self.live = live
        # The grid on a lattice fixed in world space (the module's snap_origin): always for
        # sequences; for Live, whose every run must land on the voxels of the one before.
        self.fixed_lattice = fixed_lattice or live or frames is not None
        self.sdf = sdf  # also an `sdf` level set, for Blender 5's SDF nodes
        self.options: Dict[str, Any] = options

    @property
    def is_sequence(self) -> bool:
        return self.frames is not None

    def validate(self) -> "VoxelizeSettings":
        """Refuses with the schema's own message (the one the CLI and hyvox.voxelize give)."""
        module = backend.load_module()
        if self.method != AUTO_METHOD:
            self._check(module, "method", self.method)
        for name, value in self.options.items():
            self._check(module, name, value)
        if self.frames is not None:
            if self.live:
                raise SettingsError("Live volumes follow the animation by themselves: turn off the frame range")
            if not self.frames:
                raise SettingsError("the frame range is empty")
            if self.blocks:
                raise SettingsError("Blocks output makes one mesh of one frame: turn off the frame range")
            if min(self.frames) < 0:
                # Blender reads a sequence's frame number from the file name's digits,
                # which cannot carry a sign.
                raise SettingsError("volume sequences cannot start before frame 0")
        return self

    @staticmethod
    def _check(module, name: str, value: Any) -> None:
        try:
            module.check_option(name, value)
        except (ValueError, TypeError) as exc:
            raise SettingsError(str(exc)) from None


def parse_frame_range(text: str) -> List[int]:
    """'7' -> [7]; '1-10' -> [1..10]; '1-10:2' -> every second frame."""
    text = text.strip()
    step = 1
    if ":" in text:
        text, step_text = text.split(":", 1)
        step = int(step_text)
        if step < 1:
            raise SettingsError("frame step must be at least 1")
    try:
        if "-" in text[1:]:
            cut = text.index("-", 1)
            start, end = int(text[:cut]), int(text[cut + 1 :])
        else:
            start = end = int(text)
    except ValueError:
        raise SettingsError(f"frame range must look like 1-10 or 1-10:2, not {text!r}") from None
    if end < start:
        raise SettingsError(f"frame range ends before it starts: {start}-{end}")
    return list(range(start, end + 1, step))
