# SPDX-License-Identifier: GPL-3.0-or-later
# VoxelGrid.write_vdb read back with pyopenvdb: the same voxels, at the same world
# positions; writes are atomic.
import numpy as np
import pytest

import pyopenvdb as vdb  # the test interpreter has it (tests/python/CMakeLists.txt): no skip

import hyvox


def dense_from_vdb(grid, dims):
    array = np.zeros(dims, dtype=np.float32)
    grid.copyToArray(array, ijk=(0, 0, 0))
    return array


@pytest.mark.parametrize("mode", ["conservative", "thin"])
def test_write_vdb_round_trip(bunny, tmp_path, mode):
    vertices, triangles = bunny
    grid = hyvox.voxelize(vertices, triangles, resolution=100, mode=mode, padding=2)
    path = tmp_path / "bunny.vdb"
    grid.write_vdb(path)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bunny.vdb"]

    density = vdb.read(str(path), "density")
    assert density.gridClass == vdb.GridClass.FOG_VOLUME
    assert density.activeVoxelCount() == grid.voxel_count
    assert density.background == 0.0
    meta = density.metadata
    assert meta["hyvox_mode"] == mode and meta["hyvox_method"] == "cpu"
    assert tuple(meta["hyvox_dims"]) == grid.dims
    assert meta["hyvox_voxel_size"] == grid.voxel_size

    # Same voxels: the file's dense occupancy equals the module's.
    assert np.array_equal(dense_from_vdb(density, grid.dims) == 1.0, grid.to_dense())
    lo, hi = density.evalActiveVoxelBoundingBox()
    coords = grid.coords()
    assert tuple(lo) == tuple(coords.min(axis=0)) and tuple(hi) == tuple(coords.max(axis=0))

    # Same places: index (i, j, k) maps to voxel (i, j, k)'s world-space centre.
    centres = grid.world_centres()
    for n in np.linspace(0, len(coords) - 1, 50).astype(int):
        world = density.transform.indexToWorld(tuple(int(c) for c in coords[n]))
        np.testing.assert_allclose(world, centres[n], rtol=0, atol=1e-12)
    corner = density.transform.indexToWorld((-0.5, -0.5, -0.5))
    np.testing.assert_allclose(corner, grid.origin, rtol=0, atol=1e-12)


def test_write_vdb_threads_give_the_same_file_contents(bunny, tmp_path):
    vertices, triangles = bunny
    grid = hyvox.voxelize(vertices, triangles, resolution=64)
    one, every = tmp_path / "one.vdb", tmp_path / "every.vdb"
    grid.write_vdb(one, threads=1)
    grid.write_vdb(every)
    a, b = vdb.read(str(one), "density"), vdb.read(str(every), "density")
    assert a.activeVoxelCount() == b.activeVoxelCount() == grid.voxel_count
    assert np.array_equal(dense_from_vdb(a, grid.dims), dense_from_vdb(b, grid.dims))
    with pytest.raises(ValueError, match="threads"):
        grid.write_vdb(tmp_path / "bad.vdb", threads=-1)
    assert not (tmp_path / "bad.vdb").exists()


def test_write_vdb_budget_is_its_own_and_the_voxelizations_when_unset(bunny, tmp_path):
    # voxelize() refuses before any work a run whose estimate (every pass, the .vdb write
    # included) exceeds its budget; write_vdb() checks the grids it builds against its own
    # budget, the voxelization's when none is given.
    vertices, triangles = bunny
    path = tmp_path / "b.vdb"
    estimate = hyvox.voxelize(vertices, triangles, resolution=512).stats["memory_estimate"]
    need_mib = -(-estimate["vdb_write"] // (1 << 20))
    assert need_mib >= 2, estimate
    with pytest.raises(hyvox.ResourceError, match="more than the memory budget of 1 MiB"):
        hyvox.voxelize(vertices, triangles, resolution=512, memory_budget_mib=1)
    grid = hyvox.voxelize(vertices, triangles, resolution=512, memory_budget_mib=need_mib + 1)
    leaves = grid.stats["leaves"]
    with pytest.raises(
        hyvox.ResourceError, match=rf"{leaves} leaves needs about \d+ MiB, more than the memory budget of 1 MiB"
    ):
        grid.write_vdb(path, memory_budget_mib=1)
    assert not path.exists()
    grid.write_vdb(path)  # unset: the voxelization's budget, which its estimate of the write fits
    assert vdb.read(str(path), "density").activeVoxelCount() == grid.voxel_count


def test_write_vdb_is_atomic(tetrahedron, tmp_path):
    vertices, triangles = tetrahedron
    grid = hyvox.voxelize(vertices, triangles, resolution=8)
    with pytest.raises(ValueError, match="missing"):
        grid.write_vdb(tmp_path / "missing" / "out.vdb")
    with pytest.raises(ValueError):
        grid.write_vdb("/proc/hyvox-test.vdb")  # unwritable even for root
    existing = tmp_path / "keep.vdb"
    existing.write_bytes(b"previous")
    with pytest.raises(ValueError):
        grid.write_vdb(tmp_path)  # a folder
    assert existing.read_bytes() == b"previous"
    grid.write_vdb(str(existing))
    assert vdb.read(str(existing), "density").activeVoxelCount() == grid.voxel_count
    assert sorted(p.name for p in tmp_path.iterdir()) == ["keep.vdb"]


def test_multi_valued_counts_grid(bunny, tmp_path):
    vertices, triangles = bunny
    # Mesa's llvmpipe is always there on the test machines, as for the native GL tests,
    # which never skip: a BackendError here is a failure.
    grid = hyvox.voxelize(vertices, triangles, resolution=48, method="tessellation")
    ijk, counts = grid.counts()
    assert ijk.dtype == np.int32 and counts.dtype == np.uint32 and len(ijk) == len(counts) > 0
    path = tmp_path / "tess.vdb"
    grid.write_vdb(path)
    names = sorted(meta["name"] for meta in vdb.readAllGridMetadata(str(path)))
    assert names == ["count", "density"]
    count = vdb.read(str(path), "count")
    assert count.activeVoxelCount() == len(counts)
    dense = np.zeros(grid.dims, np.float32)
    count.copyToArray(dense, ijk=(0, 0, 0))
    assert np.array_equal(dense[tuple(ijk.T)], counts.astype(np.float32))


def test_write_to_a_name_of_254_characters(tetrahedron, tmp_path):
    grid = hyvox.voxelize(*tetrahedron, resolution=8)
    path = tmp_path / ("n" * 250 + ".vdb")  # the longest names need a shorter temporary
    grid.write_vdb(path)
    assert path.exists() and sorted(p.name for p in tmp_path.iterdir()) == [path.name]
