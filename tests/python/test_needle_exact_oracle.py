# SPDX-License-Identifier: GPL-3.0-or-later
# The fuzz finding of tests/fuzz/findings/README.md (a needle: one corner at -2.5e33, two
# 1e-37 apart near the origin) decided by exact arithmetic: the true triangle (not zero
# area: its near corners differ) in voxel space as rationals, from the float32 corners and
# the grid's own double origin and voxel size, against each voxel's closed box by the 13-axis
# separating-axis test in Fractions. Every exact method must set exactly those voxels, except
# voxels the triangle merely touches (it meets the box grown by 1e-5 and not the box shrunk
# by 1e-5; DESIGN.md, "Correctness"). The methods dropped the needle before (0 voxels).
from fractions import Fraction
from itertools import product

import numpy as np
import pytest

import hyvox

NEEDLE = np.array([[-1.41794e-37, -1.917669e-37, -1.917669e-37], [-1.924353e-37, 1.1985432e-38, 0.0],
                   [-2.5045195e+33] * 3], np.float32)
TRIANGLES = np.array([[0, 1, 2]], np.uint32)
EPS = Fraction(1, 100000)


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def exact_overlap(corners, voxel, half):
    """The triangle meets the box of `voxel` with half-size `half` around its centre (SAT)."""
    centre = [v + Fraction(1, 2) for v in voxel]
    points = [sub(c, centre) for c in corners]
    edges = [sub(corners[1], corners[0]), sub(corners[2], corners[1]), sub(corners[0], corners[2])]
    units = ([1, 0, 0], [0, 1, 0], [0, 0, 1])
    axes = [cross(edges[0], edges[1]), *units] + [cross(u, e) for u in units for e in edges]
    for axis in axes:
        projected = [sum(a * p for a, p in zip(axis, point)) for point in points]
        reach = half * sum(abs(a) for a in axis)
        if min(projected) > reach or max(projected) < -reach:
            return False
    return True


@pytest.fixture(scope="module")
def runs():
    return {method: hyvox.voxelize(NEEDLE, TRIANGLES, resolution=35, padding=1, method=method)
            for method in ("cpu", "reference", "triangle", "fragment", "hybrid")}


def test_every_exact_method_sets_the_exact_needles_voxels(runs):
    grid = runs["reference"]
    origin, size = [Fraction(o) for o in grid.origin], Fraction(grid.voxel_size)
    corners = [[(Fraction(float(x)) - o) / size for x, o in zip(vertex, origin)] for vertex in NEEDLE]
    assert cross(sub(corners[1], corners[0]), sub(corners[2], corners[1])) != [0, 0, 0]  # a true triangle
    # The exact voxels lie next to the ones any method found (the true triangle is within
    # 1e-60 voxel of the segment the methods see): those and their 26 neighbours decide.
    found = {method: set(map(tuple, run.coords().tolist())) for method, run in runs.items()}
    candidates = {tuple(v + d for v, d in zip(voxel, step))
                  for voxel in set().union(*found.values()) for step in product((-1, 0, 1), repeat=3)}
    candidates = {c for c in candidates if all(0 <= v < n for v, n in zip(c, grid.dims))}
    exact = {c for c in candidates if exact_overlap(corners, c, Fraction(1, 2))}
    assert len(exact) >= 35  # along the grid's diagonal, at least one voxel per slab
    for method, voxels in found.items():
        differ = voxels ^ exact
        touches = {c for c in differ
                   if exact_overlap(corners, c, Fraction(1, 2) + EPS) and not exact_overlap(corners, c, Fraction(1, 2) - EPS)}
        assert differ == touches, (method, len(voxels), len(exact), sorted(differ - touches)[:5])
