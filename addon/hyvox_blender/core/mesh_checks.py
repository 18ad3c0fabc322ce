# SPDX-License-Identifier: GPL-3.0-or-later
"""Checks of an object's exported vertices that name the object, numpy only.

- A coordinate that is not a finite number refuses the run, naming the object and its own
  vertex index (the native check names the merged mesh's index). Blender stores an infinite
  coordinate as the largest float (3.4e38), so a magnitude of NOT_A_COORDINATE or more counts
  too, as the native check counts it.
- A few vertices far from the rest make the grid span mostly empty space (one stray vertex
  500 units away turns a 128 grid into 128x1x1): a warning names the object and how many."""

from typing import Optional

import numpy as np

NOT_A_COORDINATE = 3.4e38  # |x| at or above: Inf as Blender stores it (float max, 3.4028235e38)
FEW_FRACTION = 0.001  # "a few" vertices: at most this share of the object's ...
FEW_AT_LEAST = 3  # ... or this many
MOSTLY_EMPTY_RATIO = 4.0  # the object spans at least this many times what the rest spans
MARGIN = 0.25  # of the rest's longest side: vertices this close to it are not far


def box(vertices: np.ndarray):
    """(low, high) float64 (3,) of (N,3) vertices, N > 0. Column by column: numpy's min and
    max along axis 0 of an (N,3) array run far slower than over its three strided columns
    (docs/why/addon-core.md)."""
    vertices = np.asarray(vertices).reshape(-1, 3)
    low = np.array([vertices[:, axis].min() for axis in range(3)], np.float64)
    high = np.array([vertices[:, axis].max() for axis in range(3)], np.float64)
    return low, high


def first_bad_vertex(vertices: np.ndarray) -> Optional[int]:
    """Index of the first vertex with a NaN, infinite or float-max coordinate, or None."""
    vertices = np.asarray(vertices).reshape(-1, 3)
    if len(vertices) == 0:
        return None
    # Two reductions answer for a good mesh (Live runs this on every edit); min and max carry
    # a NaN through, and a NaN compares False, so only a bad mesh is searched vertex by vertex.
    if float(vertices.min()) > -NOT_A_COORDINATE and float(vertices.max()) < NOT_A_COORDINATE:
        return None
    good = np.abs(vertices) < NOT_A_COORDINATE  # NaN compares False
    bad = np.flatnonzero(~good.all(axis=1))
    return int(bad[0]) if len(bad) else None


def bad_vertex_message(name: str, index: int, coordinate) -> str:
    values = ", ".join(f"{float(c):.6g}" for c in coordinate)
    why = "infinite (Blender stores Inf as 3.4e+38)" if np.all(np.isfinite(coordinate)) else "not a number or infinite"
    return f"{name}: vertex {index} is at ({values}) in world space, {why}; move or delete that vertex"


def used_vertices(vertices: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """The vertices some triangle uses (loose ones do not change the grid)."""
    used = np.zeros(len(vertices), bool)
    used[np.asarray(triangles).reshape(-1)] = True
    return np.asarray(vertices) if used.all() else np.asarray(vertices)[used]


def _core_interval(values: np.ndarray, drop: int):
    """The shortest interval holding all but `drop` of the values (sorted ends only)."""
    n = len(values)
    low = np.sort(np.partition(values, drop)[: drop + 1]) if drop + 1 < n else np.sort(values)
    high = np.sort(np.partition(values, n - drop - 1)[n - drop - 1 :]) if drop + 1 < n else np.sort(values)
    # Dropping i from below and drop - i from above: the interval [low[i], high[i]] (high is
    # the drop + 1 largest, ascending, so high[i] leaves drop - i above it).
    widths = high[: drop + 1] - low[: drop + 1]
    best = int(np.argmin(widths))
    return low[best], high[best]


def _few(vertex_count: int) -> int:
    return max(FEW_AT_LEAST, int(np.ceil(FEW_FRACTION * vertex_count)))


def far_vertices_warning(name: str, vertices: np.ndarray) -> str:
    """A warning when a few of the object's vertices (those triangles use, world space) lie so
    far from the rest that the grid is mostly empty; "" otherwise."""
    vertices = np.asarray(vertices, np.float64).reshape(-1, 3)
    n = len(vertices)
    few = _few(n)
    if n <= 2 * few + 1:
        return ""
    low, high = box(vertices)
    span = high - low
    core = np.array([_core_interval(vertices[:, axis], few) for axis in range(3)])  # (3, 2)
    core_side = float((core[:, 1] - core[:, 0]).max())
    if not float(span.max()) >= MOSTLY_EMPTY_RATIO * max(core_side, 1e-30):
        return ""
    margin = MARGIN * core_side
    far = np.any((vertices < core[:, 0] - margin) | (vertices > core[:, 1] + margin), axis=1)
    count = int(far.sum())
    if not 0 < count <= few:
        return ""
    return (
        f"{name}: {count} vertex{'es' if count != 1 else ''} far from the rest (the object spans "
        f"{float(span.max()):.4g} units, the rest of it {core_side:.4g}): the grid is mostly empty "
        f"space. Move or delete {'them' if count != 1 else 'it'} to voxelize the object finely"
    )


SAMPLED_TRIANGLES = 1024  # about this many triangles' corners sampled per part for the bound


def _core_side_lower_bound(parts, few: int) -> float:
    """At most the longest side of the used vertices' core (per axis the shortest interval
    holding all of them but `few`, as far_vertices_warning takes it), from a sample of distinct
    used vertices: the whole core interval leaves out at most `few` of the sample, so it is at
    least as long as the sample's own; and dropping more (`few` of the object's vertex count, not
    of its used vertices) only shortens it."""
    samples = []
    for vertices, triangles in parts:
        triangles = np.asarray(triangles).reshape(-1, 3)
        step = max(1, len(triangles) // SAMPLED_TRIANGLES)
        samples.append(np.asarray(vertices).reshape(-1, 3)[np.unique(triangles[::step])])
    sample = np.concatenate(samples).astype(np.float64)
    if len(sample) <= 2 * few + 1:
        return 0.0
    return max(float(high - low) for low, high in (_core_interval(sample[:, axis], few) for axis in range(3)))


def object_far_vertices_warning(name: str, parts) -> str:
    """far_vertices_warning of the vertices the object's parts' triangles use, parts being
    (vertices, triangles) pairs. Live runs this on every edit: a bound from every vertex's box
    and a sample answers for a mesh without strays in a fraction of a millisecond, and only a
    mesh the bound cannot clear gets the whole check."""
    parts = [(np.asarray(v).reshape(-1, 3), t) for v, t in parts if len(v) and len(t)]
    if not parts:
        return ""
    few = _few(sum(len(v) for v, _ in parts))
    boxes = [box(v) for v, _ in parts]
    low, high = np.min([b[0] for b in boxes], axis=0), np.max([b[1] for b in boxes], axis=0)
    span = float((high - low).max())  # at least the used vertices' span
    if span < MOSTLY_EMPTY_RATIO * max(_core_side_lower_bound(parts, few), 1e-30):
        return ""  # what far_vertices_warning would answer, without its sort of every vertex
    return far_vertices_warning(name, np.concatenate([used_vertices(v, t) for v, t in parts]))
