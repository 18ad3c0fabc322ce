# SPDX-License-Identifier: GPL-3.0-or-later
# An exact oracle for conservative voxelization of single triangles that double precision
# cannot hold (fuzz findings: needles and slivers 1e-60 wide): the float32 corners in voxel
# space as rationals, from the grid's own double origin and voxel size, against each voxel's
# closed box by the 13-axis separating-axis test in Fractions. A voxel the triangle merely
# touches (it meets the box grown by 1e-5 and not the box shrunk by 1e-5; docs/design.md,
# "Correctness") may go either way.
from fractions import Fraction
from itertools import product

EPS = Fraction(1, 100000)
HALF = Fraction(1, 2)  # a voxel box's half-size


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def voxel_space_corners(vertices, grid):
    """The corners (float32 rows) in voxel space, exactly."""
    origin, size = [Fraction(o) for o in grid.origin], Fraction(grid.voxel_size)
    return [[(Fraction(float(x)) - o) / size for x, o in zip(vertex, origin)] for vertex in vertices]


def exact_overlap(corners, voxel, half=HALF):
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


def is_touch(corners, voxel):
    return exact_overlap(corners, voxel, HALF + EPS) and not exact_overlap(corners, voxel, HALF - EPS)


def exact_voxels_near(corners, found, dims):
    """The exact voxels among those any method found and their 26 neighbours (enough when
    the triangle lies within a fraction of a voxel of what the methods see)."""
    candidates = {
        tuple(v + d for v, d in zip(voxel, step))
        for voxel in set().union(*found)
        for step in product((-1, 0, 1), repeat=3)
    }
    return {c for c in candidates if all(0 <= v < n for v, n in zip(c, dims)) and exact_overlap(corners, c)}


def unexplained(corners, voxels, exact):
    """The voxels where `voxels` and `exact` differ by more than a touch."""
    return sorted(c for c in voxels ^ exact if not is_touch(corners, c))
