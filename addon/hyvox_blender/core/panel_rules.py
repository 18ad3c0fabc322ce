# SPDX-License-Identifier: GPL-3.0-or-later
"""What the sidebar panel shows, decided without bpy: how the GL methods are marked with the
device they would run on, and the result summary in short lines that fit the sidebar. (Which
options apply to a method is the schema's rule: OptionSpec.applies_to.)"""

import os
from typing import Dict, List, Optional, Sequence

GL_METHODS = ("hybrid", "triangle", "fragment", "tessellation")


def gl_device_summary(devices: Sequence[Dict]) -> Optional[Dict]:
    """The device the GL methods would use by default (a hardware GPU if any, else the
    software one) as {'name', 'software'}, or None when there is no EGL device at all."""
    hardware = [d for d in devices if not d.get("software")]
    chosen = (hardware or list(devices) or [None])[0]
    if chosen is None:
        return None
    return {"name": str(chosen.get("name", "?")), "software": bool(chosen.get("software"))}


def method_note(method: str, resolved: str, device: Optional[Dict]) -> Optional[str]:
    """One short line under Method: where it runs, and a warning for software GL."""
    if method == "auto":
        return f"Auto: {'GPU' if resolved in GL_METHODS else 'CPU'} here"
    if method not in GL_METHODS:
        return None
    if device is None:
        return "No OpenGL 4.5 device here"
    if device["software"]:
        return "GL runs in software here (slow)"
    return f"GPU: {device['name']}"


def _count(n: int) -> str:
    return f"{n:,}"


def summary_lines(record: dict) -> List[str]:
    """The panel's summary of a run (summary.as_dict's record): a few short lines per result
    instead of one long one the sidebar would cut."""
    lines = []
    for volume in record.get("volumes", []):
        lines.append(volume["name"])
        voxels = sum(volume["voxel_counts"])
        lines.append(f"  {_count(voxels)} voxels")
        dims = volume["dims"]
        lines.append(f"  grid {dims[0]} x {dims[1]} x {dims[2]}")
        lines.append(f"  voxel size {volume['voxel_size']:.4g}")
        lines.append(f"  {_count(volume['triangles'])} triangles, {volume['method']}")
        if volume.get("blocks_faces") is not None:
            lines.append(f"  blocks: {_count(volume['blocks_faces'])} faces")
        if volume.get("frames"):
            lines.append(f"  frames {volume['frames'][0]}-{volume['frames'][-1]}")
        if volume.get("vox_files"):
            lines.append(f"  {os.path.basename(volume['vox_files'][0])}")
    timings = record.get("timings_ms")
    if timings:
        lines.append(f"Took {timings['total'] / 1000.0:.2f} s")
    return lines
