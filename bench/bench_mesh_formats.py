# SPDX-License-Identifier: GPL-3.0-or-later
"""What each way of reading costs: shared meshes written in every format hyvox reads
(tests/python/mesh_writers.py), each read by hyvox.readMesh (its strict reader, or for FBX and
3MF assimp in its own process) and by assimp in the process (the way hyvox read them before),
median of 5 reads each (bench_mesh_read). For FBX and 3MF the ratio is the price of the
process (starting it, the mesh through a pipe); for the other formats the price of the strict
reader against assimp's.

    PYTHONPATH=BUILD/python python3 bench/bench_mesh_formats.py --bench BUILD/bench/bench_mesh_read
        [--meshes ../shared/data/meshes] [--out bench/results]

Writes OUT/mesh_formats.json and OUT/mesh_formats.md."""

import argparse
import json
import os
import subprocess
import sys
import tempfile

import hyvox

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "python"))
import mesh_writers  # noqa: E402
from bench_results import Column, Table, add_out_argument  # noqa: E402

MESHES = [
    "teapot_utah.ply",
    "bunny_stanford_69k.ply",
    "dragon_stanford_res2_203k.ply.gz",
    "sponza_crytek_262k_vcolor.ply.gz",
    "dragon_stanford_871k.ply.gz",
]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bench", required=True)
    parser.add_argument("--meshes", default=os.path.join(HERE, "..", "..", "shared", "data", "meshes"))
    add_out_argument(parser)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for mesh in MESHES:
            vertices, triangles = hyvox.read_mesh(os.path.join(args.meshes, mesh))
            files = []
            for name, (suffix, writer) in mesh_writers.FORMATS.items():
                path = os.path.join(work, f"{mesh.split('.')[0]}.{name}{suffix}")
                with open(path, "wb") as f:
                    f.write(writer(vertices, triangles))
                files.append(path)
            out = os.path.join(work, "rows.json")
            subprocess.run([args.bench, "--repeat", str(args.repeat), "--json", out, "--out", work, *files], check=True)
            for row in json.load(open(out)):
                stem, name = row["file"].rsplit(".", 2)[0:2]
                rows.append(
                    {
                        "mesh": stem,
                        "format": name,
                        "triangles": row["triangles"],
                        "reader": "assimp process" if name in ("fbx", "3mf") else "strict",
                        "hyvox_ms": row["hyvox_ms"],
                        "assimp_in_process_ms": row["assimp_ms"],
                        "ratio": row["hyvox_ms"] / row["assimp_ms"],
                        "same_triangle_count": row["triangles"] == row["assimp_triangles"],
                    }
                )
    table = Table(
        "mesh_formats",
        "Reading the shared meshes in every format: hyvox.readMesh against assimp in the process",
        [
            Column("mesh"),
            Column("format"),
            Column("triangles"),
            Column("hyvox reader"),
            Column("hyvox ms", 1),
            Column("assimp in process ms", 1),
            Column("ratio", 2),
        ],
    )
    for r in rows:
        table.add(
            [r["mesh"], r["format"], r["triangles"], r["reader"], r["hyvox_ms"], r["assimp_in_process_ms"], r["ratio"]]
        )
        if not r["same_triangle_count"]:
            table.note(f"{r['mesh']}.{r['format']}: the two readers give different triangle counts")
    table.note(
        f"Medians of {args.repeat} reads. ratio < 1: hyvox faster. FBX and 3MF: assimp in its own process "
        "(the ratio is the process's price)."
    )
    table.write(args.out)


if __name__ == "__main__":
    main()
