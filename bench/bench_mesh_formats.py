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
import platform
import subprocess
import sys
import tempfile

import hyvox

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "python"))
import mesh_writers  # noqa: E402

MESHES = ["teapot_utah.ply", "bunny_stanford_69k.ply", "dragon_stanford_res2_203k.ply.gz",
          "sponza_crytek_262k_vcolor.ply.gz", "dragon_stanford_871k.ply.gz"]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bench", required=True)
    parser.add_argument("--meshes", default=os.path.join(HERE, "..", "..", "shared", "data", "meshes"))
    parser.add_argument("--out", default=os.path.join(HERE, "results"))
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
            subprocess.run([args.bench, "--repeat", str(args.repeat), "--json", out, *files], check=True)
            for row in json.load(open(out)):
                stem, name = row["file"].rsplit(".", 2)[0:2]
                rows.append({"mesh": stem, "format": name, "triangles": row["triangles"],
                             "reader": "assimp process" if name in ("fbx", "3mf") else "strict",
                             "hyvox_ms": row["hyvox_ms"], "assimp_in_process_ms": row["assimp_ms"],
                             "ratio": row["hyvox_ms"] / row["assimp_ms"],
                             "same_triangle_count": row["triangles"] == row["assimp_triangles"]})
    header = (f"Reading the shared meshes in every format: hyvox.readMesh against assimp in the process, "
              f"median of {args.repeat} (`bench/bench_mesh_formats.py`), {platform.node()}, {os.cpu_count()} cores. "
              "ratio < 1: hyvox faster. FBX and 3MF: assimp in its own process (the ratio is the process's price).")
    lines = ["| mesh | format | triangles | hyvox reader | hyvox ms | assimp in process ms | ratio |",
             "|---|---|---:|---|---:|---:|---:|"]
    for r in rows:
        lines.append(f"| {r['mesh']} | {r['format']} | {r['triangles']} | {r['reader']} | {r['hyvox_ms']:.1f} | "
                     f"{r['assimp_in_process_ms']:.1f} | {r['ratio']:.2f}{'' if r['same_triangle_count'] else ' (counts differ)'} |")
    text = header + "\n\n" + "\n".join(lines) + "\n"
    print(text)
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "mesh_formats.md"), "w") as f:
        f.write(text)
    with open(os.path.join(args.out, "mesh_formats.json"), "w") as f:
        json.dump({"command": " ".join(sys.argv), "rows": rows}, f, indent=1)


if __name__ == "__main__":
    main()
