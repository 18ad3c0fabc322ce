# SPDX-License-Identifier: GPL-3.0-or-later
"""Bias of the tessellation method against three references, to show what its points miss.

    /usr/bin/python3 bench/tessellation_bias_references.py [--out DIR] MESH RESOLUTION [GAMMA ...]

References: the exact conservative voxels (cpu), the exact thin 6-separating voxels (cpu),
and the "centre-line" voxels computed here: a voxel is in it when the surface crosses one of
its three axis-parallel centre lines (rays through voxel centres along x, y and z, every hit
marked). For a plane it is the 6-separating set; near triangle edges it is thinner. It needs
nothing from hyvox but the grid placement, so it is an independent check of which voxels
the points cover. Run after building (it imports build/python). The table also goes to
DIR/tessellation_bias_references.{json,md} (default bench/results/).
"""

import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build", "python"))
import hyvox  # noqa: E402
from bench_results import DEFAULT_OUT, Column, Table  # noqa: E402


def centre_line_keys(points, triangles, dims):
    """Linear keys of the voxels whose centre lines the triangles cross (voxel units)."""
    keys = []
    a0, a1, a2 = points[triangles[:, 0]], points[triangles[:, 1]], points[triangles[:, 2]]
    for axis in range(3):
        b, c = [x for x in range(3) if x != axis]
        # Column centres (j + 0.5, k + 0.5) inside each triangle's projected bounding box.
        lo_b = np.ceil(np.minimum(np.minimum(a0[:, b], a1[:, b]), a2[:, b]) - 0.5).astype(np.int64)
        hi_b = np.floor(np.maximum(np.maximum(a0[:, b], a1[:, b]), a2[:, b]) - 0.5).astype(np.int64)
        lo_c = np.ceil(np.minimum(np.minimum(a0[:, c], a1[:, c]), a2[:, c]) - 0.5).astype(np.int64)
        hi_c = np.floor(np.maximum(np.maximum(a0[:, c], a1[:, c]), a2[:, c]) - 0.5).astype(np.int64)
        nb, nc = np.maximum(hi_b - lo_b + 1, 0), np.maximum(hi_c - lo_c + 1, 0)
        per_triangle = nb * nc
        tri = np.repeat(np.arange(len(triangles)), per_triangle)
        local = np.arange(per_triangle.sum()) - np.repeat(np.cumsum(per_triangle) - per_triangle, per_triangle)
        jb, jc = lo_b[tri] + local // nc[tri], lo_c[tri] + local % nc[tri]
        qb, qc = jb + 0.5, jc + 0.5
        p0, p1, p2 = a0[tri], a1[tri], a2[tri]

        def edge(p, q):  # twice the signed area of (p, q, column centre) in the (b, c) plane
            return (q[:, b] - p[:, b]) * (qc - p[:, c]) - (q[:, c] - p[:, c]) * (qb - p[:, b])

        w0, w1, w2 = edge(p1, p2), edge(p2, p0), edge(p0, p1)
        total = w0 + w1 + w2
        inside = (((w0 >= 0) & (w1 >= 0) & (w2 >= 0)) | ((w0 <= 0) & (w1 <= 0) & (w2 <= 0))) & (total != 0)
        depth = (w0 * p0[:, axis] + w1 * p1[:, axis] + w2 * p2[:, axis])[inside] / total[inside]
        voxel = np.empty((len(depth), 3), np.int64)
        voxel[:, axis], voxel[:, b], voxel[:, c] = np.floor(depth), jb[inside], jc[inside]
        voxel = voxel[np.all((voxel >= 0) & (voxel < np.array(dims)), axis=1)]
        keys.append((voxel[:, 0] * dims[1] + voxel[:, 1]) * dims[2] + voxel[:, 2])
    return np.unique(np.concatenate(keys))


def grid_keys(grid):
    c = grid.coords().astype(np.int64)
    d = grid.dims
    return np.unique((c[:, 0] * d[1] + c[:, 1]) * d[2] + c[:, 2])


def main():
    argv = sys.argv[1:]
    out = DEFAULT_OUT
    if argv[:1] == ["--out"] and len(argv) > 1:
        out, argv = argv[1], argv[2:]
    if len(argv) < 2:
        sys.exit(__doc__)
    path, resolution = argv[0], int(argv[1])
    gammas = [float(g) for g in argv[2:]] or [1.0, 2.0, 4.0]
    vertices, triangles = hyvox.read_mesh(path)
    vertices, triangles = np.asarray(vertices, np.float64), np.asarray(triangles, np.int64)
    conservative = hyvox.voxelize(vertices, triangles, resolution=resolution, method="cpu")
    thin = hyvox.voxelize(vertices, triangles, resolution=resolution, method="cpu", mode="thin")
    dims = tuple(conservative.dims)
    in_voxels = (vertices - np.array(conservative.origin)) / conservative.voxel_size
    references = {
        "conservative": grid_keys(conservative),
        "centre-line": centre_line_keys(in_voxels, triangles, dims),
        "thin": grid_keys(thin),
    }
    print(
        f"{os.path.basename(path)} at {resolution}: "
        + ", ".join(f"{name} {len(keys)} voxels" for name, keys in references.items())
    )
    print("gamma  " + "  ".join(f"bias vs {name:>12}" for name in references))
    table = Table(
        "tessellation_bias_references",
        "What the tessellation's points miss, against three references",
        [Column("mesh"), Column("res"), Column("γ")] + [Column(f"bias vs {name} %", 2) for name in references],
    )
    table.note(
        ", ".join(f"{name}: {len(keys):,} voxels" for name, keys in references.items())
        + "; centre-line: voxels whose axis-parallel centre lines the surface crosses."
    )
    for gamma in gammas:
        points = grid_keys(
            hyvox.voxelize(vertices, triangles, resolution=resolution, method="tessellation", tess_gamma=gamma)
        )
        print(
            f"{gamma:5.2f}  " + "  ".join(f"{1 - np.isin(keys, points).mean():20.4%}" for keys in references.values())
        )
        table.add(
            [os.path.basename(path), resolution, gamma]
            + [100 * float(1 - np.isin(keys, points).mean()) for keys in references.values()]
        )
    table.write(out)


if __name__ == "__main__":
    main()
