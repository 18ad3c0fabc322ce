# SPDX-License-Identifier: GPL-3.0-or-later
"""Watertightness of the tessellation method on closed shapes nobody tuned for.

    /usr/bin/python3 bench/tessellation_seal_sweep.py [--shapes 16] [--seed 99] [--gammas 1,1.25,1.5,2] [--out DIR]

Makes random closed meshes (tetrahedra, boxes of random aspect, thin prisms with long
skinny side triangles, squashed icosahedra), each randomly rotated, at a random resolution
between 100 and 300, and runs `build/hyvox gamma-sweep` on each. Prints, per shape and γ,
the points, the bias against the exact conservative and thin sets, and the voxels the thin
set encloses that a 6-connected flood from outside reaches through the result (0 = sealed).
This is how the default γ was chosen (docs/why/tessellation-gamma.md). Run after building. The
per-γ summary also goes to DIR/tessellation_seal_sweep.{json,md} (default bench/results/).
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

from bench_results import Column, Table, add_out_argument

CLI = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build", "hyvox")


def rotation(rng):
    a, b, c = rng.uniform(0, 3, 3)
    rx = np.array([[1, 0, 0], [0, np.cos(a), -np.sin(a)], [0, np.sin(a), np.cos(a)]])
    ry = np.array([[np.cos(b), 0, np.sin(b)], [0, 1, 0], [-np.sin(b), 0, np.cos(b)]])
    rz = np.array([[np.cos(c), -np.sin(c), 0], [np.sin(c), np.cos(c), 0], [0, 0, 1]])
    return rz @ ry @ rx


def tetrahedron(rng):
    v = rng.random((4, 3))
    return v, [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]]  # the flood needs no orientation


def box(rng):
    v = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float) * rng.uniform(0.1, 1, 3)
    t = [
        [0, 1, 3],
        [0, 3, 2],
        [4, 6, 7],
        [4, 7, 5],
        [0, 4, 5],
        [0, 5, 1],
        [2, 3, 7],
        [2, 7, 6],
        [0, 2, 6],
        [0, 6, 4],
        [1, 5, 7],
        [1, 7, 3],
    ]
    return v, t


def prism(rng):
    n, r = int(rng.integers(5, 20)), rng.uniform(0.01, 0.2)
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    ring = np.stack([r * np.cos(a), r * np.sin(a)], 1)
    v = [[x, y, 0] for x, y in ring] + [[x, y, 1] for x, y in ring] + [[0, 0, 0], [0, 0, 1]]
    t = []
    for i in range(n):
        j = (i + 1) % n
        t += [[i, j, n + j], [i, n + j, n + i], [2 * n, j, i], [2 * n + 1, n + i, n + j]]
    return np.array(v, float), t


def icosahedron(rng):
    p = (1 + 5**0.5) / 2
    v = np.array(
        [
            [-1, p, 0],
            [1, p, 0],
            [-1, -p, 0],
            [1, -p, 0],
            [0, -1, p],
            [0, 1, p],
            [0, -1, -p],
            [0, 1, -p],
            [p, 0, -1],
            [p, 0, 1],
            [-p, 0, -1],
            [-p, 0, 1],
        ],
        float,
    ) * rng.uniform(0.3, 1, 3)
    t = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ]
    return v, t


def write_ply(path, vertices, triangles):
    with open(path, "wb") as f:
        f.write(
            f"ply\nformat binary_little_endian 1.0\nelement vertex {len(vertices)}\n"
            "property float x\nproperty float y\nproperty float z\n"
            f"element face {len(triangles)}\nproperty list uchar int vertex_indices\nend_header\n".encode()
        )
        f.write(np.asarray(vertices, "<f4").tobytes())
        for tri in triangles:
            f.write(b"\x03" + np.asarray(tri, "<i4").tobytes())


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--shapes", type=int, default=16)
    parser.add_argument("--seed", type=int, default=99)
    parser.add_argument("--gammas", default="1,1.25,1.5,2")
    add_out_argument(parser)
    args = parser.parse_args()
    rng = np.random.default_rng(args.seed)
    makers = [tetrahedron, box, prism, icosahedron]
    print(f"{'shape':14} {'res':>4} {'gamma':>6} {'points':>10} {'bias':>8} {'bias_thin':>9} {'leaked':>10}")
    leaks = {}
    with tempfile.TemporaryDirectory() as tmp:
        for n in range(args.shapes):
            make = makers[n % len(makers)]
            vertices, triangles = make(rng)
            vertices = vertices @ rotation(rng).T
            resolution = int(rng.integers(100, 300))
            mesh, stats = os.path.join(tmp, "shape.ply"), os.path.join(tmp, "sweep.json")
            write_ply(mesh, vertices, triangles)
            subprocess.run(
                [
                    CLI,
                    "gamma-sweep",
                    mesh,
                    "--resolution",
                    str(resolution),
                    "--gammas",
                    args.gammas,
                    "--quiet",
                    "--stats-json",
                    stats,
                ],
                check=True,
            )
            for row in json.load(open(stats))["rows"]:
                print(
                    f"{make.__name__ + str(n):14} {resolution:4} {row['gamma']:6g} {row['points']:10.0f} "
                    f"{row['bias']:8.4f} {row['bias_thin']:9.5f} {row['leaked_voxels']:10d}"
                )
                leaks.setdefault(row["gamma"], []).append(row["leaked_voxels"])
    table = Table(
        "tessellation_seal_sweep",
        "Watertightness of the tessellation on random closed shapes",
        [Column("γ"), Column("shapes"), Column("shapes that leak")],
    )
    table.note(
        f"{args.shapes} shapes (seed {args.seed}): tetrahedra, boxes, thin prisms, squashed icosahedra, "
        "randomly rotated, at resolutions 100-300; a shape leaks when a 6-connected flood from outside "
        "reaches a voxel its exact thin voxels enclose."
    )
    for gamma, leaked in sorted(leaks.items()):
        print(f"gamma {gamma:g}: {sum(1 for x in leaked if x)} of {len(leaked)} shapes leak")
        table.add([gamma, len(leaked), sum(1 for x in leaked if x)])
    table.write(args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
