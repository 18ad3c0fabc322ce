# SPDX-License-Identifier: GPL-3.0-or-later
"""Solid voxels three ways in one run, on the same grid: hyvox (mode="solid", inside rule
auto), OpenVDB's meshToVolume + sdfToFogVolume (Blender's Mesh to Volume with Fill Volume;
timed by build/bench/bench_solid, which also writes its fog voxels) and libigl's
fast_winding_number (PyPI libigl, pinned in bench/requirements-py311.txt; Barill et al. 2018,
order 2, beta 2) at every voxel centre of hyvox's grid, inside where w >= 0.5.

    /usr/bin/python3 -m venv --system-site-packages bench/.venv
    bench/.venv/bin/pip install -r bench/requirements-py311.txt
    PYTHONPATH=build/python bench/.venv/bin/python bench/bench_solid_three_way.py [--res 128,256] [--out DIR] [MESH...]

Where each is wrong: on the voxels outside hyvox's (conservative) surface, the voxels where
OpenVDB's fog or libigl's w >= 0.5 differ from hyvox, and for a random sample of each set
(and of all those voxels) the float64 brute-force winding number (the tests' oracle,
tests/python/test_solid.py): how often it sides with hyvox, with the other, or lies within
0.05 of 0.5 (ambiguous: no approximation is held to those). The two tables also go to
DIR/solid_three_way.{json,md} and DIR/solid_three_way_checks.{json,md} (default bench/results/)."""

import argparse
import json
import os
import pathlib
import subprocess
import sys
import tempfile
import time

import numpy as np

import hyvox
import igl
from bench_results import Column, Table, add_out_argument

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests" / "python"))
from test_solid import brute_force_winding  # noqa: E402  (the tests' oracle, one definition)

MESHES = ["sponza_crytek_262k_vcolor.ply.gz", "dragon_stanford_871k.ply.gz"]
POINTS_PER_CALL = 8_000_000  # libigl's memory for its output and temporaries stays modest


def openvdb_run(bench_solid, mesh_dir, name, res, fog_dir):
    """bench_solid's row (its hyvox and OpenVDB ms) and OpenVDB's fog voxels."""
    subprocess.run(
        [
            bench_solid,
            "--runs",
            "1",
            "--res",
            str(res),
            "--mesh-dir",
            str(mesh_dir),
            "--fog-dir",
            fog_dir,
            "--out",
            fog_dir,
            name,
        ],
        check=True,
        capture_output=True,
        text=True,
    )
    with open(os.path.join(fog_dir, "solid.json")) as f:
        row = json.load(f)["rows"][-1]
    hyvox_ms, openvdb_ms = row[3], row[5]
    fog = np.fromfile(os.path.join(fog_dir, f"{name}_{res}.fog.ijk"), dtype=np.int32).reshape(-1, 3)
    return hyvox_ms, openvdb_ms, fog


def libigl_inside(V, F, grid):
    """w >= 0.5 at every voxel centre of `grid` (dense), libigl's w, and the ms it took."""
    nx, ny, nz = grid.dims
    origin, h = np.array(grid.origin), grid.voxel_size
    jj, kk = np.meshgrid(np.arange(ny), np.arange(nz), indexing="ij")
    slab = np.stack([np.zeros(jj.size), jj.ravel(), kk.ravel()], axis=1)
    w = np.empty(nx * ny * nz)
    per_call = max(1, POINTS_PER_CALL // (ny * nz))
    ms = 0.0
    for x0 in range(0, nx, per_call):
        xs = range(x0, min(nx, x0 + per_call))
        query = origin + (np.concatenate([slab + [x, 0, 0] for x in xs]) + 0.5) * h
        start = time.perf_counter()
        w[x0 * ny * nz : (xs[-1] + 1) * ny * nz] = igl.fast_winding_number(V, F, query)
        ms += 1e3 * (time.perf_counter() - start)
    w = w.reshape(nx, ny, nz)
    return w >= 0.5, w, ms


def judge(V, F, grid, ijk, ours, rng, samples):
    """For a random sample of voxels ijk: how many the brute-force winding number puts on
    hyvox's side, on the other side, or within 0.05 of 0.5."""
    if len(ijk) == 0:
        return 0, 0, 0, 0
    pick = ijk[rng.choice(len(ijk), min(samples, len(ijk)), replace=False)]
    w = brute_force_winding(V, F, np.array(grid.origin) + (pick + 0.5) * grid.voxel_size)
    hyvox_side = ours[tuple(pick.T)]
    clear = np.abs(w - 0.5) >= 0.05
    with_hyvox = int((clear & ((w >= 0.5) == hyvox_side)).sum())
    return len(pick), with_hyvox, int((clear & ((w >= 0.5) != hyvox_side)).sum()), int((~clear).sum())


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--res", default="128,256")
    parser.add_argument(
        "--mesh-dir", default=os.environ.get("HYVOX_MESH_DIR", str(ROOT.parent / "shared" / "data" / "meshes"))
    )
    parser.add_argument("--bench-solid", default=str(ROOT / "build" / "bench" / "bench_solid"))
    parser.add_argument("--samples", type=int, default=100, help="brute-force checks per voxel set")
    parser.add_argument("meshes", nargs="*", default=MESHES)
    add_out_argument(parser)
    args = parser.parse_args()
    times = Table(
        "solid_three_way",
        "Solid three ways: hyvox, OpenVDB, libigl's fast winding numbers",
        [
            Column("mesh"),
            Column("res"),
            Column("hyvox rule (auto)"),
            Column("hyvox ms", 0),
            Column("hyvox ms (bench_solid)", 0),
            Column("OpenVDB ms", 0),
            Column("libigl ms", 0),
            Column("OpenVDB / hyvox", 1),
            Column("libigl / hyvox", 1),
            Column("voxels off hyvox's surface"),
        ],
    )
    times.note(
        "One run each. hyvox in this process (mode solid, inside rule auto); OpenVDB: meshToVolume + "
        "sdfToFogVolume through bench_solid; libigl: fast_winding_number at every voxel centre, its tree "
        "built inside the timed call."
    )
    judged = Table(
        "solid_three_way_checks",
        "Solid three ways: where each is wrong, by the brute-force winding number",
        [
            Column("mesh"),
            Column("res"),
            Column("voxels (off hyvox's surface)"),
            Column("count"),
            Column("sampled"),
            Column("brute force with hyvox"),
            Column("with the other"),
            Column("within 0.05 of 0.5"),
        ],
    )
    judged.note(
        f"Up to {args.samples} random voxels of each set against the float64 brute-force winding number "
        "(tests/python/test_solid.py); with hyvox / with the other: |w - 0.5| >= 0.05 on that side."
    )
    rng = np.random.default_rng(1)
    print(f"load average at start: {os.getloadavg()}", flush=True)
    timing = []
    checks = []
    with tempfile.TemporaryDirectory() as fog_dir:
        for name in args.meshes:
            vertices, triangles = hyvox.read_mesh(os.path.join(args.mesh_dir, name))
            V, F = vertices.astype(np.float64), triangles.astype(np.int64)
            for res in [int(r) for r in args.res.split(",")]:
                start = time.perf_counter()
                solid = hyvox.voxelize(vertices, triangles, resolution=res, mode="solid")
                hyvox_ms = 1e3 * (time.perf_counter() - start)
                stats = solid.stats["solid"]
                surface = hyvox.voxelize(vertices, triangles, resolution=res).to_dense()
                ours = solid.to_dense()
                bench_hyvox_ms, openvdb_ms, fog_ijk = openvdb_run(args.bench_solid, args.mesh_dir, name, res, fog_dir)
                fog = np.zeros(solid.dims, bool)
                fog[tuple(fog_ijk.T)] = True
                igl_in, _, igl_ms = libigl_inside(V, F, solid)
                free = ~surface
                timing.append(
                    (
                        name,
                        res,
                        f"{stats['inside_rule']} by {stats['evaluation']}",
                        hyvox_ms,
                        bench_hyvox_ms,
                        openvdb_ms,
                        igl_ms,
                        int(free.sum()),
                    )
                )
                print("timing", timing[-1], f"load {os.getloadavg()[0]:.1f}", flush=True)
                sets = {
                    "all outside hyvox's surface": np.argwhere(free),
                    "OpenVDB inside, hyvox outside": np.argwhere(free & fog & ~ours),
                    "hyvox inside, OpenVDB outside": np.argwhere(free & ~fog & ours),
                    "libigl inside, hyvox outside": np.argwhere(free & igl_in & ~ours),
                    "hyvox inside, libigl outside": np.argwhere(free & ~igl_in & ours),
                }
                for label, ijk in sets.items():
                    checks.append((name, res, label, len(ijk)) + judge(V, F, solid, ijk, ours, rng, args.samples))
                    print("check", checks[-1], flush=True)
    print(f"\nload average at end: {os.getloadavg()}\n")
    print(
        "| mesh | res | hyvox rule (auto) | hyvox ms | hyvox ms (bench_solid) | OpenVDB ms | libigl ms | "
        "OpenVDB / hyvox | libigl / hyvox | voxels outside hyvox's surface |"
    )
    print("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|")
    for name, res, rule, ms, bench_ms, vdb_ms, igl_ms, free in timing:
        print(
            f"| {name} | {res} | {rule} | {ms:,.0f} | {bench_ms:,.0f} | {vdb_ms:,.0f} | {igl_ms:,.0f} | "
            f"{vdb_ms / ms:.1f} | {igl_ms / ms:.1f} | {free:,} |"
        )
        times.add([name, res, rule, ms, bench_ms, vdb_ms, igl_ms, vdb_ms / ms, igl_ms / ms, free])
    print(
        "\n| mesh | res | voxels (outside hyvox's surface) | count | sampled | brute force with hyvox | "
        "with the other | within 0.05 of 0.5 |"
    )
    print("|---|---:|---|---:|---:|---:|---:|---:|")
    for name, res, label, count, sampled, with_hyvox, against, ambiguous in checks:
        print(f"| {name} | {res} | {label} | {count:,} | {sampled} | {with_hyvox} | {against} | {ambiguous} |")
        judged.add([name, res, label, count, sampled, with_hyvox, against, ambiguous])
    times.write(args.out)
    judged.write(args.out)


if __name__ == "__main__":
    main()
