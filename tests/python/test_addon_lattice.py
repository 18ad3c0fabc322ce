# SPDX-License-Identifier: GPL-3.0-or-later
"""The lattice fixed in world space (the module's snap_origin, which the add-on asks for):
sequence frames (and Live runs) put their voxels on one lattice, so a static part keeps its
voxels while another part moves."""

import math
import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "addon"))

from hyvox_blender.core.pipeline import Group, GroupMesh, Pipeline, merge_meshes  # noqa: E402
from hyvox_blender.core.settings import VoxelizeSettings  # noqa: E402
from lattice_oracle import snapped_origin  # noqa: E402
from shapes import icosphere  # noqa: E402


@pytest.fixture(scope="module")
def hyvox():
    import hyvox as module

    return module


def test_snap_origin_is_the_oracles_lattice(hyvox):
    v, t = icosphere(2)
    rng = np.random.default_rng(7)
    for size in (0.15, 0.1, 1e-3 * 40, 3.0):
        for shift in rng.uniform(-50, 50, (20, 3)):
            moved = (v + shift).astype(np.float32)
            plan = hyvox.plan_grid(moved, t, voxel_size=size, snap_origin=True)
            assert tuple(plan["origin"]) == snapped_origin(moved, t, size)


def test_snap_origin_with_a_resolution_keeps_the_modules_voxel_size(hyvox):
    v, t = icosphere(2)
    v = v * np.float32([1.0, 2.0, 0.5]) + np.float32([3.0, -1.0, 0.2])
    snapped = hyvox.voxelize(v, t, resolution=40, method="cpu", snap_origin=True)
    free = hyvox.voxelize(v, t, resolution=40, method="cpu")
    assert snapped.voxel_size == free.voxel_size
    assert tuple(snapped.origin) == snapped_origin(v, t, free.voxel_size)


def test_unused_vertices_do_not_widen_the_bounds(hyvox):
    v, t = icosphere(1)
    far = np.vstack([v, [[-100.0, -100.0, -100.0]]]).astype(np.float32)
    plan = hyvox.plan_grid(far, t, voxel_size=0.1, snap_origin=True)
    assert min(plan["origin"]) >= -1.1


def _cube_and_sphere(sphere_x):
    """A static cube grouped with a sphere moving along x on its left: the bounds' min
    follows the sphere."""
    cube_v = np.array([(x, y, z) for x in (0.3, 1.1) for y in (-0.4, 0.4) for z in (-0.4, 0.4)], np.float32)
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    cube_t = np.array([tri for a, b, c, d in quads for tri in ((a, b, c), (a, c, d))], np.uint32)
    sphere_v, sphere_t = icosphere(2)
    sphere_v = sphere_v * np.float32(0.4) + np.float32([sphere_x, 0.0, 0.0])
    return merge_meshes([(cube_v, cube_t), (sphere_v, sphere_t)])


def _file_world_indices(path):
    """The .vdb's voxels (read back with pyopenvdb) as world lattice indices."""
    import pyopenvdb as vdb

    grid = vdb.read(path, "density")
    size = grid.transform.voxelSize()[0]
    points = []
    for item in grid.citerOnValues():
        assert item.count == 1
        centre = grid.transform.indexToWorld(item.min)
        points.append(tuple(int(round(c / size - 0.5)) for c in centre))
    return set(points)


def _grid_world_indices(grid):
    offset = np.array([round(o / grid.voxel_size) for o in grid.origin])
    return {tuple(p) for p in grid.coords().astype(np.int64) + offset}


def _world_indices(grid, box_min_x):
    """The grid's voxels right of box_min_x as world lattice indices (origin / size + ijk)."""
    size = grid.voxel_size
    offset = np.array([round(o / size) for o in grid.origin])
    ijk = grid.coords().astype(np.int64) + offset
    right = ijk[:, 0] * size >= box_min_x
    return {tuple(p) for p in ijk[right]}


@pytest.mark.parametrize("mode", ["conservative", "solid"])
def test_a_static_part_keeps_its_voxels_across_a_sequence(hyvox, tmp_path, mode):
    xs = {1: -0.6, 2: -0.6 + 0.0331, 3: -0.6 - 0.0467}  # the sphere moves by fractions of a voxel
    group = Group("Pair", ["Cube", "Sphere"])

    def export(frame):
        return [GroupMesh(group, *_cube_and_sphere(xs[frame]))]

    settings = VoxelizeSettings(voxel_size=0.15, method="cpu", mode=mode, frames=[1, 2, 3])
    pipeline = Pipeline(settings, str(tmp_path), export, module=hyvox)
    (result,) = pipeline.run().values()
    assert len(result.files) == 3
    # The grids the pipeline wrote sit on one lattice (whole multiples of the voxel size)...
    grids = []
    for frame in (1, 2, 3):
        v, t = _cube_and_sphere(xs[frame])
        origin = snapped_origin(v, t, 0.15)
        for o in origin:
            assert math.isclose(o / 0.15, round(o / 0.15), abs_tol=1e-9)
        grids.append(hyvox.voxelize(v, t, voxel_size=0.15, origin=origin, method="cpu", mode=mode))
    for grid, path in zip(grids, result.files):
        assert _file_world_indices(path) == _grid_world_indices(grid)
    # ... so the cube (x from 0.3; the sphere ends before 0) has the same voxels every frame.
    cube = [_world_indices(grid, 0.0) for grid in grids]
    assert cube[0] and cube[0] == cube[1] == cube[2]
    # Left to the module, the origin follows each frame's bounds and the cube's voxels change.
    free = [hyvox.voxelize(*_cube_and_sphere(xs[f]), voxel_size=0.15, method="cpu", mode=mode) for f in (1, 2, 3)]
    assert len({grid.origin[0] for grid in free}) == 3
    corners = [
        {
            tuple(np.round(np.array(g.origin) + ijk * g.voxel_size, 6))
            for ijk in g.coords()
            if g.origin[0] + ijk[0] * g.voxel_size >= 0.0
        }
        for g in free
    ]
    assert not corners[0] == corners[1] == corners[2]


def test_a_non_finite_vertex_is_refused_in_plain_words(hyvox):
    v, t = icosphere(1)
    v[5, 1] = np.nan
    with pytest.raises(ValueError, match="non-finite|NaN"):
        hyvox.voxelize(v, t, resolution=16, method="cpu", snap_origin=True)
