# SPDX-License-Identifier: GPL-3.0-or-later
"""hyvox.plan_grid lays out the grid voxelize() lays out, without voxelizing (a farm job's
chunks take the voxel size of the job's first frame by it)."""

import numpy as np
import pytest

import hyvox


def box_mesh(low, high):
    """The 12 triangles of an axis-aligned box."""
    corners = np.array([[(high if (c >> a) & 1 else low)[a] for a in range(3)] for c in range(8)], dtype=np.float32)
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    return corners, np.array([t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))], dtype=np.uint32)


@pytest.mark.parametrize(
    "options",
    [dict(resolution=37), dict(resolution=64, padding=3), dict(voxel_size=0.07), dict(resolution=20, mode="solid")],
)
def test_plan_is_the_grid_voxelize_lays_out(options):
    vertices, triangles = box_mesh((0.1, -0.2, 0.3), (1.3, 0.4, 2.0))
    plan = hyvox.plan_grid(vertices, triangles, **options)
    grid = hyvox.voxelize(vertices, triangles, method="cpu", **options)
    assert plan == {"origin": tuple(grid.origin), "voxel_size": grid.voxel_size, "dims": tuple(grid.dims)}


def test_degenerate_triangles_do_not_count_towards_the_bounds():
    vertices, triangles = box_mesh((0, 0, 0), (1, 1, 1))
    far = len(vertices)
    vertices = np.vstack([vertices, [[50, 50, 50], [60, 60, 60]]]).astype(np.float32)
    triangles = np.vstack([triangles, [[far, far + 1, far + 1]]]).astype(np.uint32)  # a repeated index
    plan = hyvox.plan_grid(vertices, triangles, resolution=10)
    assert plan["voxel_size"] == pytest.approx(0.1)
    assert plan == {
        "origin": (0.0, 0.0, 0.0),
        "voxel_size": hyvox.voxelize(vertices, triangles, resolution=10).voxel_size,
        "dims": (10, 10, 10),
    }


def test_bad_input_is_refused():
    vertices, triangles = box_mesh((0, 0, 0), (1, 1, 1))
    with pytest.raises(ValueError, match="resolution"):
        hyvox.plan_grid(vertices, triangles, resolution=0)
    with pytest.raises(ValueError):
        hyvox.plan_grid(vertices[:0], triangles[:0], resolution=8)
    with pytest.raises(TypeError):
        hyvox.plan_grid(vertices, triangles, no_such_option=1)
