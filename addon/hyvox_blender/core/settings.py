# SPDX-License-Identifier: GPL-3.0-or-later
"""One settings object per run, gathered once from the scene, the operator's keyword
arguments and the add-on preferences (the glTF exporter's pattern), then validated."""
from dataclasses import dataclass, field
from typing import List, Optional

from .errors import SettingsError

METHODS = ("auto", "hybrid", "triangle", "fragment", "tessellation", "cpu", "reference")
MODES = ("conservative", "thin")

MIN_RESOLUTION = 1
MAX_RESOLUTION = 8192


@dataclass
class VoxelizeSettings:
    resolution: int = 256          # voxels along the longest side of each volume's bounds
    voxel_size: float = 0.0        # world units; > 0 overrides resolution
    method: str = "auto"           # "auto": hybrid when GL works here, else cpu
    mode: str = "conservative"
    tessellation_gamma: float = 1.0
    hybrid_cutoff: float = -1.0    # < 0: the module picks (auto)
    padding: int = 0               # empty voxels around the bounds
    separate: bool = False         # one volume per object instead of one for the selection
    frames: Optional[List[int]] = None  # None: the current frame only, no sequence
    threads: int = 0
    gl_device: str = ""            # "" auto, "software", or an EGL device index "0", "1"...
    memory_budget_mb: int = 4096
    extra: dict = field(default_factory=dict)  # passed through to hyvox.voxelize

    @property
    def is_sequence(self) -> bool:
        return self.frames is not None

    def validate(self) -> "VoxelizeSettings":
        if self.method not in METHODS:
            raise SettingsError(f"method must be one of {', '.join(METHODS)}, not {self.method!r}")
        if self.mode not in MODES:
            raise SettingsError(f"mode must be one of {', '.join(MODES)}, not {self.mode!r}")
        if self.voxel_size < 0 or self.voxel_size != self.voxel_size:
            raise SettingsError(f"voxel size must be positive, not {self.voxel_size}")
        if self.voxel_size == 0 and not MIN_RESOLUTION <= self.resolution <= MAX_RESOLUTION:
            raise SettingsError(
                f"resolution must be in {MIN_RESOLUTION}..{MAX_RESOLUTION}, not {self.resolution}")
        if self.tessellation_gamma <= 0:
            raise SettingsError("tessellation gamma must be positive")
        if self.padding < 0:
            raise SettingsError("padding cannot be negative")
        if self.memory_budget_mb <= 0:
            raise SettingsError("memory budget must be positive")
        if self.frames is not None:
            if not self.frames:
                raise SettingsError("the frame range is empty")
            if min(self.frames) < 0:
                # Blender reads a sequence's frame number from the file name's digits,
                # which cannot carry a sign.
                raise SettingsError("volume sequences cannot start before frame 0")
        return self


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
            start, end = int(text[:cut]), int(text[cut + 1:])
        else:
            start = end = int(text)
    except ValueError:
        raise SettingsError(f"frame range must look like 1-10 or 1-10:2, not {text!r}") from None
    if end < start:
        raise SettingsError(f"frame range ends before it starts: {start}-{end}")
    return list(range(start, end + 1, step))
