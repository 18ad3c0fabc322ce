# SPDX-License-Identifier: GPL-3.0-or-later
# The fuzz finding tests/fuzz/seeds/voxelize/sliver_beside_a_diagonal.bin decided by exact
# arithmetic (exact_sat.py). In voxel space the triangle is a sliver from (0, 2.5e-65, 0) to
# (30, 0, 29.99956) whose third corner stands 2.5e-76 above the far end in y: it passes
# 1.5e-5 voxel below the x = z diagonal at x = 1 (more than the 1e-5 touch band), so the
# voxels (1,0,0), (2,0,1), ... are its and (0,0,1), (1,0,2), ... are not. The cpu method set
# the latter before (its normal e0 x e1 had lost the sliver's width; native/src/core/
# triangle_normal.h). Every exact method must now set the exact voxels, up to touches.
import pathlib

import numpy as np
import pytest

import hyvox
from exact_sat import EPS, HALF, cross, exact_overlap, exact_voxels_near, sub, unexplained, voxel_space_corners

SEED = np.array(
    [
        [-2.50451951e33, 2.11894795e-33, -2.50448284e33],
        [8.85928915e-41, 0.0, -1.91017832e-37],
        [-9.40395481e-38, 2.1019477e-44, 8.0],
    ],
    np.float32,
)
TRIANGLES = np.array([[1, 0, 2]], np.uint32)


@pytest.fixture(scope="module")
def runs():
    return {
        method: hyvox.voxelize(SEED, TRIANGLES, resolution=30, method=method)
        for method in ("cpu", "reference", "triangle", "fragment", "hybrid")
    }


def test_the_seed_is_this_triangle():
    seed = pathlib.Path(__file__).parents[1] / "fuzz" / "seeds" / "voxelize" / "sliver_beside_a_diagonal.bin"
    # fuzz_voxelize.cpp: 3 header bytes, then the raw float32 vertices.
    assert np.array_equal(np.frombuffer(seed.read_bytes(), "<f4", 9, 3).view("<u4"), SEED.reshape(-1).view("<u4"))


def test_every_exact_method_sets_the_exact_slivers_voxels(runs):
    grid = runs["reference"]
    corners = voxel_space_corners(SEED[TRIANGLES[0]], grid)
    assert cross(sub(corners[1], corners[0]), sub(corners[2], corners[1])) != [0, 0, 0]  # a true triangle
    # The sides of the diagonal: the sliver meets every voxel (x, 0, x - 1) below it and no
    # voxel (x, 0, x + 1) above it, and from x = 1 on those are beyond the touch band too.
    # (Every voxel it meets is a touch in y: it lies on the grid's y = 0 face.)
    assert all(exact_overlap(corners, (x, 0, x - 1)) for x in range(1, 30))
    assert not any(exact_overlap(corners, (x, 0, x + 1)) for x in range(29))
    assert not any(exact_overlap(corners, (x, 0, x + 1), HALF + EPS) for x in range(1, 29))
    found = {method: set(map(tuple, run.coords().tolist())) for method, run in runs.items()}
    exact = exact_voxels_near(corners, found.values(), grid.dims)
    assert len(exact) >= 30  # one voxel per slab along x at least
    for method, voxels in found.items():
        assert not unexplained(corners, voxels, exact), (method, len(voxels), len(exact))
