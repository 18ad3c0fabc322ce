# SPDX-License-Identifier: GPL-3.0-or-later
# The fuzz finding tests/fuzz/seeds/voxelize/needle_near_1e-37.bin (a needle: one corner at
# -2.5e33, two 1e-37 apart near the origin) decided by exact arithmetic (exact_sat.py): the
# true triangle (not zero area: its near corners differ) against each voxel's closed box in
# Fractions. Every exact method must set exactly those voxels, except voxels the triangle
# merely touches. The methods dropped the needle before (0 voxels).
import numpy as np
import pytest

import hyvox
from exact_sat import cross, exact_voxels_near, sub, unexplained, voxel_space_corners

NEEDLE = np.array(
    [[-1.41794e-37, -1.917669e-37, -1.917669e-37], [-1.924353e-37, 1.1985432e-38, 0.0], [-2.5045195e33] * 3], np.float32
)
TRIANGLES = np.array([[0, 1, 2]], np.uint32)


@pytest.fixture(scope="module")
def runs():
    return {
        method: hyvox.voxelize(NEEDLE, TRIANGLES, resolution=35, padding=1, method=method)
        for method in ("cpu", "reference", "triangle", "fragment", "hybrid")
    }


def test_every_exact_method_sets_the_exact_needles_voxels(runs):
    grid = runs["reference"]
    corners = voxel_space_corners(NEEDLE, grid)
    assert cross(sub(corners[1], corners[0]), sub(corners[2], corners[1])) != [0, 0, 0]  # a true triangle
    # The true triangle is within 1e-60 voxel of the segment the methods see.
    found = {method: set(map(tuple, run.coords().tolist())) for method, run in runs.items()}
    exact = exact_voxels_near(corners, found.values(), grid.dims)
    assert len(exact) >= 35  # along the grid's diagonal, at least one voxel per slab
    for method, voxels in found.items():
        assert not unexplained(corners, voxels, exact), (method, len(voxels), len(exact))
