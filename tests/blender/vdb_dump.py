# SPDX-License-Identifier: GPL-3.0-or-later
"""A .vdb's active voxels, read with pyopenvdb: in process (helpers.read_vdb), or for a
test process that has no pyopenvdb (the bpy module's venv) by Debian's Python:
    python3 vdb_dump.py FILE.vdb GRID OUT.npz
which writes coords, size and zero as read() returns them."""

import sys

import numpy as np


def read(path, grid_name="density"):
    """(ijk (K,3) int64, voxel size (3,), world position of index (0,0,0), grid) of the
    grid's active voxels; tiles (count > 1) are expanded."""
    import pyopenvdb as vdb

    grid = vdb.read(path, grid_name)
    coords = []
    for item in grid.citerOnValues():
        lo, hi = item.min, item.max
        if item.count == 1:
            coords.append(lo)
        else:
            r = [np.arange(lo[a], hi[a] + 1) for a in range(3)]
            coords.extend(np.stack(np.meshgrid(*r, indexing="ij"), -1).reshape(-1, 3).tolist())
    coords = np.array(coords, dtype=np.int64).reshape(-1, 3)
    size = np.array(grid.transform.voxelSize(), dtype=np.float64)
    zero = np.array(grid.transform.indexToWorld((0, 0, 0)), dtype=np.float64)
    return coords, size, zero, grid


if __name__ == "__main__":
    coords, size, zero, _ = read(sys.argv[1], sys.argv[2])
    np.savez(sys.argv[3], coords=coords, size=size, zero=zero)
