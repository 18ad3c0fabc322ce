# SPDX-License-Identifier: GPL-3.0-or-later
"""hyvox solid (inside rule auto) against libigl's fast winding number (PyPI libigl, the
Barill et al. 2018 code, expansion order 2, beta 2) evaluated at the same voxel centres.

    python3 -m venv --system-site-packages bench/.venv && bench/.venv/bin/pip install libigl==2.6.3
    PYTHONPATH=build/python bench/.venv/bin/python bench/bench_solid_winding.py [--res 256,512,1024] \\
        [--out DIR] [MESH...]

libigl answers for points, not voxels, so it gets every voxel centre of the grid hyvox laid
out. Where that is too many for this machine's memory and time, it gets the centres of every
s-th x-slab (s printed; its time scaled by s), one call per slab group, its tree built once per
call (the build time, measured on its own, is counted once). Agreement: on the evaluated
voxels outside hyvox's surface, how many libigl's w >= 0.5 puts on the other side than hyvox,
and how many of those lie within 0.05 of the threshold (ambiguous for any approximation). The
table also goes to DIR/solid_winding.{json,md} (default bench/results/)."""

import argparse
import os
import time

import numpy as np

import hyvox
import igl
from bench_results import Column, Table, add_out_argument

MESHES = ["happy_buddha_100k.ply", "dragon_stanford_871k.ply.gz", "sponza_crytek_262k_vcolor.ply.gz"]
POINTS_PER_CALL = 8_000_000


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--res", default="256,512,1024")
    parser.add_argument("--mesh-dir", default=os.environ.get("HYVOX_MESH_DIR", "../shared/data/meshes"))
    parser.add_argument("--max-points", type=float, default=3e7, help="centres libigl gets at most per case")
    parser.add_argument("meshes", nargs="*", default=MESHES)
    add_out_argument(parser)
    args = parser.parse_args()
    table = Table(
        "solid_winding",
        "Solid: hyvox against libigl's fast winding numbers at the voxel centres",
        [
            Column("mesh"),
            Column("res"),
            Column("hyvox ms", 1),
            Column("libigl ms", 1),
            Column("slab step"),
            Column("libigl / hyvox", 1),
            Column("checked"),
            Column("differ"),
            Column("within 0.05 of 0.5"),
        ],
    )
    table.note(
        "libigl gets every s-th x-slab's voxel centres (s = slab step; its time scaled by s, its tree build "
        "counted once); differ: voxels off hyvox's surface where w >= 0.5 disagrees with hyvox."
    )
    print(
        f"{'mesh':34} {'res':>5} {'hyvox ms':>9} {'igl ms':>10} {'slab step':>9} {'igl/hyvox':>9} "
        f"{'checked':>11} {'differ':>8} {'ambiguous':>9}"
    )
    for name in args.meshes:
        vertices, triangles = hyvox.read_mesh(os.path.join(args.mesh_dir, name))
        V = vertices.astype(np.float64)
        F = triangles.astype(np.int64)
        start = time.perf_counter()
        igl.fast_winding_number(V, F, np.zeros((1, 3)))
        build_ms = 1e3 * (time.perf_counter() - start)
        for res in [int(r) for r in args.res.split(",")]:
            start = time.perf_counter()
            solid = hyvox.voxelize(vertices, triangles, resolution=res, mode="solid")
            hyvox_ms = 1e3 * (time.perf_counter() - start)
            surface = hyvox.voxelize(vertices, triangles, resolution=res)
            nx, ny, nz = solid.dims
            step = max(1, int(np.ceil(nx * ny * nz / args.max_points)))
            slabs = np.arange(0, nx, step)
            origin, h = np.array(solid.origin), solid.voxel_size
            jj, kk = np.meshgrid(np.arange(ny), np.arange(nz), indexing="ij")
            per_slab = np.stack([np.zeros(jj.size), jj.ravel(), kk.ravel()], axis=1)
            group = max(1, POINTS_PER_CALL // (ny * nz))
            igl_ms, checked, differ, ambiguous = 0.0, 0, 0, 0
            ours_ijk, shell_ijk = by_slab(solid, slabs), by_slab(surface, slabs)
            for g0 in range(0, len(slabs), group):
                xs = slabs[g0 : g0 + group]
                ijk = np.concatenate([per_slab + [x, 0, 0] for x in xs]).astype(np.int64)
                query = origin + (ijk + 0.5) * h
                start = time.perf_counter()
                w = igl.fast_winding_number(V, F, query)
                igl_ms += 1e3 * (time.perf_counter() - start) - build_ms
                ours = slab_bits(ours_ijk, xs, ny, nz)
                shell = slab_bits(shell_ijk, xs, ny, nz)
                free = ~shell
                other = free & ((w >= 0.5) != ours)
                checked += int(free.sum())
                differ += int(other.sum())
                ambiguous += int((other & (np.abs(w - 0.5) < 0.05)).sum())
            igl_ms = igl_ms * step + build_ms
            print(
                f"{name:34} {res:5d} {hyvox_ms:9.1f} {igl_ms:10.1f} {step:9d} {igl_ms / hyvox_ms:9.1f} "
                f"{checked:11d} {differ:8d} {ambiguous:9d}",
                flush=True,
            )
            table.add([name, res, hyvox_ms, igl_ms, step, igl_ms / hyvox_ms, checked, differ, ambiguous])
    table.write(args.out)


def by_slab(grid, slabs):
    """The grid's voxels on the sampled x-slabs, sorted by x."""
    ijk = grid.coords()
    ijk = ijk[np.isin(ijk[:, 0], slabs)]
    return ijk[np.argsort(ijk[:, 0], kind="stable")]


def slab_bits(ijk, xs, ny, nz):
    """The voxels of ijk (sorted by x) on x-slabs xs, flattened in the order of the queries."""
    lo, hi = np.searchsorted(ijk[:, 0], [xs[0], xs[-1] + 1])
    sel = ijk[lo:hi]
    sel = sel[np.isin(sel[:, 0], xs)]
    out = np.zeros((len(xs), ny, nz), bool)
    out[np.searchsorted(xs, sel[:, 0]), sel[:, 1], sel[:, 2]] = True
    return out.ravel()


if __name__ == "__main__":
    main()
