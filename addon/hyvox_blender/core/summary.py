# SPDX-License-Identifier: GPL-3.0-or-later
"""Human-readable summaries of a run for the operator's report, the console and the demo."""

from typing import Dict, List

from .pipeline import GroupResult, Timings


def describe_result(result: GroupResult) -> str:
    dims = "x".join(str(d) for d in result.dims)
    voxels = sum(result.voxel_counts)
    frames = ""
    if result.frames:
        frames = f", frames {result.frames[0]}-{result.frames[-1]} ({len(result.frames)} files)"
    blocks = f", blocks of {len(result.blocks.faces):,} faces" if result.blocks is not None else ""
    return (
        f"{result.group.name}: {voxels:,} voxels, grid {dims}, voxel size "
        f"{result.voxel_size:.6g}, {result.triangles:,} triangles, {result.method}{frames}{blocks}"
    )


def describe_timings(timings: Timings) -> str:
    return (
        f"export {timings.export_ms:.0f} ms, voxelize {timings.voxelize_ms:.0f} ms, "
        f"write {timings.write_ms:.0f} ms, import {timings.import_ms:.0f} ms, "
        f"total {timings.total_ms:.0f} ms"
    )


def short_report(results: Dict[str, GroupResult], timings: Timings) -> str:
    """One line for the status bar / Info editor."""
    made = []
    for r in results.values():
        kind = "blocks" if r.blocks is not None else ("volume sequence" if r.frames else "volume")
        made.append(f"{r.group.name} {kind} of {sum(r.voxel_counts):,} voxels")
    return f"Made {', '.join(made)} in {timings.total_ms / 1000.0:.2f} s"


def long_report(results: Dict[str, GroupResult], timings: Timings) -> List[str]:
    lines = [describe_result(r) for r in results.values()]
    for r in results.values():
        for files in (r.files, r.vox_files):
            for path in files[:1]:
                more = f" (+{len(files) - 1} more)" if len(files) > 1 else ""
                lines.append(f"  {path}{more}")
    lines.append(describe_timings(timings))
    return lines


def as_dict(results: Dict[str, GroupResult], timings: Timings) -> dict:
    """JSON-friendly record (the headless script's --stats-json)."""
    return {
        "volumes": [
            {
                "name": r.group.name,
                "sources": r.group.sources,
                "files": r.files,
                "frames": r.frames,
                "voxel_size": r.voxel_size,
                "origin": list(r.origin),
                "dims": list(r.dims),
                "voxel_counts": r.voxel_counts,
                "triangles": r.triangles,
                "method": r.method,
                "vox_files": r.vox_files,
                "blocks_faces": len(r.blocks.faces) if r.blocks is not None else None,
                "stats": {k: v for k, v in r.stats.items() if isinstance(v, (int, float, str, list, dict))},
            }
            for r in results.values()
        ],
        "timings_ms": {
            "export": timings.export_ms,
            "voxelize": timings.voxelize_ms,
            "write": timings.write_ms,
            "import": timings.import_ms,
            "total": timings.total_ms,
        },
    }
