# SPDX-License-Identifier: GPL-3.0-or-later
"""Runs inside the clean venv the wheel is installed into (check_installed_wheel.py
starts it with an empty environment): imports hyvox, voxelizes with the CPU method, then
a GL method, then reads a glTF file (through the assimp reader process), and records which
shared libraries the process had mapped after each step, as the kernel reports them
(/proc/self/maps).
    python wheel_child.py MESH OUT_DIR"""
import base64
import json
import os
import struct
import sys

import numpy as np


def mapped_libraries():
    paths = set()
    with open("/proc/self/maps") as maps:
        for line in maps:
            fields = line.split()
            if len(fields) >= 6 and fields[5].startswith("/") and ".so" in fields[5]:
                paths.add(fields[5])
    return paths


def triangle_gltf():
    """One triangle as glTF 2.0, its buffer inline (a format read through assimp)."""
    data = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<3I", 0, 1, 2)
    return {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
            "buffers": [{"byteLength": len(data),
                         "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
            "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                            {"buffer": 0, "byteOffset": 36, "byteLength": 12}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                           "min": [0, 0, 0], "max": [1, 1, 0]},
                          {"bufferView": 1, "componentType": 5125, "count": 3, "type": "SCALAR"}]}


def main(mesh, out_dir):
    before = mapped_libraries()   # the interpreter and numpy
    import hyvox
    vertices, triangles = hyvox.read_mesh(mesh)
    grid = hyvox.voxelize(vertices, triangles, resolution=128, method="cpu")
    after_cpu = mapped_libraries()
    gl = hyvox.voxelize(vertices, triangles, resolution=128, method="hybrid")
    after_gl = mapped_libraries()
    gltf = os.path.join(out_dir, "triangle.gltf")
    with open(gltf, "w") as f:
        json.dump(triangle_gltf(), f)
    gltf_triangles = len(hyvox.read_mesh(gltf)[1])
    after_gltf = mapped_libraries()
    np.save(os.path.join(out_dir, "cpu_coords.npy"), grid.coords())
    with open(os.path.join(out_dir, "child.json"), "w") as f:
        json.dump({
            "core_file": hyvox._core.__file__,
            "origin": list(grid.origin), "voxel_size": grid.voxel_size,
            "gl_voxels": int(len(gl.coords())),
            # The exact methods agree: the GL method through the system's driver sets the
            # cpu method's voxels.
            "gl_equals_cpu": bool(np.array_equal(gl.coords(), grid.coords())),
            "loaded_by_import_and_cpu": sorted(after_cpu - before),
            "loaded_by_gl": sorted(after_gl - after_cpu),
            "gltf_triangles": gltf_triangles,
            "loaded_by_gltf": sorted(after_gltf - after_gl),
        }, f, indent=1)


if __name__ == "__main__":
    main(*sys.argv[1:3])
