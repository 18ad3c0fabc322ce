# SPDX-License-Identifier: GPL-3.0-or-later
"""Sparse results from Python: a thin triangle in a 16384 x 16384 grid runs within a small
memory budget, its voxels (coords, the .vdb) are exact against the plane's inequality
computed in numpy, and to_dense() refuses the 256 MiB box instead of allocating it."""

import numpy as np
import pytest

import hyvox

LENGTH, WIDTH = 16384, 64
# The plane z = 0.5 of unit voxels; voxel (i, j, 0)'s closed box meets the triangle
# {x, y >= 0, x / LENGTH + y / WIDTH <= 1} exactly when i / LENGTH + j / WIDTH <= 1.
VERTICES = np.array([[0, 0, 0.5], [LENGTH, 0, 0.5], [0, WIDTH, 0.5]], np.float32)
TRIANGLES = np.array([[0, 1, 2]], np.uint32)
OPTIONS = dict(voxel_size=1.0, origin=(0, 0, 0), bounds=((0, 0, 0), (LENGTH, LENGTH, 1)), memory_budget_mib=128)


def expected_mask(ijk):
    i, j = ijk[:, 0].astype(np.int64), ijk[:, 1].astype(np.int64)
    return i * WIDTH + j * LENGTH <= LENGTH * WIDTH


@pytest.fixture(scope="module")
def strip():
    return hyvox.voxelize(VERTICES, TRIANGLES, **OPTIONS)


def test_huge_grid_small_surface_is_exact(strip):
    assert strip.dims == (LENGTH, LENGTH, 1)
    assert strip.stats["tiles"] > 1 and strip.stats["leaves"] > 0
    ijk = strip.coords()
    assert len(ijk) == strip.voxel_count
    assert expected_mask(ijk).all() and (ijk[:, 2] == 0).all()
    # Every voxel the inequality admits is there: count them row by row.
    i = np.arange(LENGTH, dtype=np.int64)
    per_row = np.minimum(LENGTH, (LENGTH * WIDTH - i * WIDTH) // LENGTH + 1)
    assert strip.voxel_count == int(per_row.sum())


def test_to_dense_refuses_a_box_over_the_budget(strip):
    with pytest.raises(hyvox.ResourceError, match="to_dense.*memory budget of 128 MiB"):
        strip.to_dense()


def test_the_vdb_holds_the_sparse_voxels(strip, tmp_path):
    import pyopenvdb as vdb

    path = tmp_path / "strip.vdb"
    strip.write_vdb(path)
    grid = vdb.read(str(path), "density")
    assert grid.activeVoxelCount() == strip.voxel_count
    assert grid.evalActiveVoxelBoundingBox() == ((0, 0, 0), (LENGTH - 1, WIDTH, 0))


def test_tile_size_changes_nothing_but_the_tiles(bunny):
    vertices, triangles = bunny
    whole = hyvox.voxelize(vertices, triangles, resolution=64)
    tiled = hyvox.voxelize(vertices, triangles, resolution=64, tile_size=20)  # rounded up to 24
    assert whole.stats["tiles"] == 1 and tiled.stats["tiles"] > 1
    assert tiled.stats["options"]["tile_size"] == 20
    assert np.array_equal(np.sort(whole.coords(), axis=0), np.sort(tiled.coords(), axis=0))
    assert np.array_equal(whole.to_dense(), tiled.to_dense())


def test_write_reports_progress_and_can_be_cancelled(strip, tmp_path):
    seen = []
    report = strip.write_vdb(tmp_path / "a.vdb", progress=seen.append)
    assert seen and seen == sorted(seen) and seen[-1] == 100
    assert report["grid_bytes"] > 0 and report["build_ms"] >= 0
    token = hyvox.CancelToken()
    token.cancel()
    with pytest.raises(hyvox.Cancelled):
        strip.write_vdb(tmp_path / "b.vdb", cancel=token)
    assert not (tmp_path / "b.vdb").exists() and sorted(p.name for p in tmp_path.iterdir()) == ["a.vdb"]
