# SPDX-License-Identifier: GPL-3.0-or-later
"""Frame lists as render farms write them: "1-250", "1-9:2", "1,3,7-20:2", "12" (Open Job
Description range expressions and Flamenco's chunks)."""

from typing import List

from .errors import SettingsError
from .settings import parse_frame_range


def parse_frames(text: str) -> List[int]:
    """The frames of a comma list of ranges, ascending, each once."""
    parts = [part for part in text.split(",") if part.strip()]
    if not parts:
        raise SettingsError(f"no frames in {text!r}")
    return sorted({frame for part in parts for frame in parse_frame_range(part)})
