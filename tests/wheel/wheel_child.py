# SPDX-License-Identifier: GPL-3.0-or-later
"""Runs inside the clean venv the wheel is installed into (check_installed_wheel.py
starts it with an empty environment): imports hyvox, voxelizes with the CPU method, then
a GL method, then reads a 3MF file (through the assimp reader process), and records which
shared libraries the process had mapped after each step, as the kernel reports them
(/proc/self/maps).
    python wheel_child.py MESH OUT_DIR"""

import json
import os
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


def main(mesh, out_dir):
    before = mapped_libraries()  # the interpreter and numpy
    import hyvox

    vertices, triangles = hyvox.read_mesh(mesh)
    grid = hyvox.voxelize(vertices, triangles, resolution=128, method="cpu")
    after_cpu = mapped_libraries()
    gl = hyvox.voxelize(vertices, triangles, resolution=128, method="hybrid")
    after_gl = mapped_libraries()
    model = os.path.join(out_dir, "triangle.3mf")
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
    import mesh_writers  # numpy and the standard library only

    with open(model, "wb") as f:
        f.write(mesh_writers.three_mf(np.eye(3, dtype=np.float32), np.array([[0, 1, 2]], np.uint32)))
    model_triangles = len(hyvox.read_mesh(model)[1])
    after_model = mapped_libraries()
    np.save(os.path.join(out_dir, "cpu_coords.npy"), grid.coords())
    with open(os.path.join(out_dir, "child.json"), "w") as f:
        json.dump(
            {
                "core_file": hyvox._core.__file__,
                "origin": list(grid.origin),
                "voxel_size": grid.voxel_size,
                "gl_voxels": int(len(gl.coords())),
                # The exact methods agree: the GL method through the system's driver sets the
                # cpu method's voxels.
                "gl_equals_cpu": bool(np.array_equal(gl.coords(), grid.coords())),
                "loaded_by_import_and_cpu": sorted(after_cpu - before),
                "loaded_by_gl": sorted(after_gl - after_cpu),
                "model_triangles": model_triangles,
                "loaded_by_3mf": sorted(after_model - after_gl),
            },
            f,
            indent=1,
        )


if __name__ == "__main__":
    main(*sys.argv[1:3])
