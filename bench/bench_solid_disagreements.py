# SPDX-License-Identifier: GPL-3.0-or-later
"""Where hyvox's solid and OpenVDB's fog (meshToVolume + sdfToFogVolume, written by
build/bench/bench_solid --fog-dir) disagree, at resolutions where the dense arrays of
bench_solid_three_way.py do not fit: the voxel sets as sorted coordinate keys, and a random
sample of each disagreement against the tests' float64 brute-force winding number.

    PYTHONPATH=build/python /usr/bin/python3 bench/bench_solid_disagreements.py --res 1024 sponza_crytek_262k_vcolor.ply.gz

The table also goes to DIR/solid_disagreements.{json,md} (--out DIR, default bench/results/).
"""

import argparse
import os
import pathlib
import subprocess
import sys
import tempfile

import numpy as np

import hyvox
from bench_results import Column, Table, add_out_argument

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests" / "python"))
from test_solid import brute_force_winding  # noqa: E402  (the tests' oracle, one definition)


def keys(ijk):
    """Sorted unique int64 keys of voxel coordinates (21 bits each)."""
    ijk = np.asarray(ijk).astype(np.int64)
    return np.unique((ijk[:, 0] << 42) | (ijk[:, 1] << 21) | ijk[:, 2])


def coordinates(key):
    mask = (1 << 21) - 1
    return np.stack([key >> 42, (key >> 21) & mask, key & mask], axis=1)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--res", type=int, default=1024)
    parser.add_argument("--samples", type=int, default=100)
    parser.add_argument(
        "--mesh-dir", default=os.environ.get("HYVOX_MESH_DIR", str(ROOT.parent / "shared" / "data" / "meshes"))
    )
    parser.add_argument("--bench-solid", default=str(ROOT / "build" / "bench" / "bench_solid"))
    parser.add_argument("mesh")
    add_out_argument(parser)
    args = parser.parse_args()
    table = Table(
        "solid_disagreements",
        "Solid: where hyvox and OpenVDB's fog disagree, by the brute-force winding number",
        [
            Column("mesh"),
            Column("res"),
            Column("voxels"),
            Column("count"),
            Column("sampled"),
            Column("w >= 0.55"),
            Column("w <= 0.45"),
            Column("within 0.05 of 0.5"),
        ],
    )
    print(f"load average at start: {os.getloadavg()}", flush=True)
    with tempfile.TemporaryDirectory() as fog_dir:
        row = subprocess.run(
            [
                args.bench_solid,
                "--runs",
                "1",
                "--res",
                str(args.res),
                "--mesh-dir",
                args.mesh_dir,
                "--fog-dir",
                fog_dir,
                "--out",
                fog_dir,
                args.mesh,
            ],
            check=True,
            capture_output=True,
            text=True,
        ).stdout
        print(row, flush=True)
        fog = keys(np.fromfile(os.path.join(fog_dir, f"{args.mesh}_{args.res}.fog.ijk"), dtype=np.int32).reshape(-1, 3))
    vertices, triangles = hyvox.read_mesh(os.path.join(args.mesh_dir, args.mesh))
    solid = hyvox.voxelize(vertices, triangles, resolution=args.res, mode="solid")
    origin, size = np.array(solid.origin), solid.voxel_size
    ours = keys(solid.coords())
    del solid
    surface = keys(hyvox.voxelize(vertices, triangles, resolution=args.res).coords())
    inside = np.setdiff1d(ours, surface, assume_unique=True)
    sets = {
        "hyvox inside (off its surface), OpenVDB outside": np.setdiff1d(inside, fog, assume_unique=True),
        "OpenVDB inside, hyvox outside": np.setdiff1d(fog, ours, assume_unique=True),
    }
    print(f"hyvox {len(ours):,} voxels ({len(surface):,} surface), fog {len(fog):,}", flush=True)
    rng = np.random.default_rng(1)
    for label, found in sets.items():
        pick = found[rng.choice(len(found), min(args.samples, len(found)), replace=False)]
        w = brute_force_winding(vertices, triangles, origin + (coordinates(pick) + 0.5) * size)
        clear = np.abs(w - 0.5) >= 0.05
        print(
            f"{label}: {len(found):,}; sampled {len(pick)}: w >= 0.55 {int((clear & (w >= 0.5)).sum())}, "
            f"w <= 0.45 {int((clear & (w < 0.5)).sum())}, within 0.05 of 0.5 {int((~clear).sum())}",
            flush=True,
        )
        table.add(
            [
                args.mesh,
                args.res,
                label,
                len(found),
                len(pick),
                int((clear & (w >= 0.5)).sum()),
                int((clear & (w < 0.5)).sum()),
                int((~clear).sum()),
            ]
        )
    print(f"load average at end: {os.getloadavg()}")
    table.write(args.out)


if __name__ == "__main__":
    main()
