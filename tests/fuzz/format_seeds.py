# SPDX-License-Identifier: GPL-3.0-or-later
"""Seeds for the fuzz targets of the STL, OFF and assimp-read formats: the meshes given (the
shared meshes' binary PLY, as their README lays them out) written in each format by
tests/python/mesh_writers.py.
    python3 format_seeds.py TARGET OUT_DIR MESH.ply...
TARGET: stl_reader, off_reader, gltf_reader, fbx_check or assimp_formats (whose inputs start with a byte
that picks the format: fuzz_assimp_formats.cpp)."""

import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import mesh_writers  # noqa: E402

# fuzz_assimp_formats.cpp's kFormats, in its order.
ASSIMP_FORMATS = ["fbx", "3mf"]
WRITERS = {
    "stl_reader": ["stl_binary", "stl_ascii"],
    "off_reader": ["off"],
    "gltf_reader": ["gltf", "glb"],
    "fbx_check": ["fbx"],
    "assimp_formats": ASSIMP_FORMATS,
}


def read_ply(path):
    data = open(path, "rb").read()
    body = data.index(b"end_header\n") + len(b"end_header\n")
    lines = data[:body].decode().splitlines()
    nv = int(next(line for line in lines if line.startswith("element vertex")).split()[2])
    nf = int(next(line for line in lines if line.startswith("element face")).split()[2])
    stride = 4 * sum(1 for line in lines if line.startswith("property float")) + sum(
        1 for line in lines if line.startswith("property uchar")
    )
    records = np.frombuffer(data, np.uint8, nv * stride, body).reshape(nv, stride)
    vertices = records[:, :12].copy().view("<f4").reshape(nv, 3)
    faces = np.frombuffer(data, np.dtype([("n", "u1"), ("i", "<i4", 3)]), nf, body + nv * stride)["i"]
    return vertices, faces.astype(np.uint32)


def main(target, out_dir, meshes):
    os.makedirs(out_dir, exist_ok=True)
    for mesh in meshes:
        vertices, triangles = read_ply(mesh)
        stem = os.path.splitext(os.path.basename(mesh))[0]
        for name in WRITERS[target]:
            data = mesh_writers.FORMATS[name][1](vertices, triangles)
            if target == "assimp_formats":
                data = bytes([ASSIMP_FORMATS.index(name)]) + data
            with open(os.path.join(out_dir, f"{stem}.{name}"), "wb") as f:
                f.write(data)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], sys.argv[3:])
