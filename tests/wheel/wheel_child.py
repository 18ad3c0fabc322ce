# SPDX-License-Identifier: GPL-3.0-or-later
"""Runs inside the clean venv the wheel is installed into (check_installed_wheel.py
starts it with an empty environment): imports hyvox, voxelizes with the CPU method, then
a GL method, then reads a COLLADA file (through the assimp reader process), and records which
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


def triangle_dae():
    """One triangle as COLLADA (a format read through the assimp reader process)."""
    return """<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <library_geometries><geometry id="m"><mesh>
    <source id="p"><float_array id="pa" count="9">0 0 0 1 0 0 0 1 0</float_array>
      <technique_common><accessor source="#pa" count="3" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
    <triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s"><node><instance_geometry url="#m"/></node></visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
"""


def main(mesh, out_dir):
    before = mapped_libraries()   # the interpreter and numpy
    import hyvox
    vertices, triangles = hyvox.read_mesh(mesh)
    grid = hyvox.voxelize(vertices, triangles, resolution=128, method="cpu")
    after_cpu = mapped_libraries()
    gl = hyvox.voxelize(vertices, triangles, resolution=128, method="hybrid")
    after_gl = mapped_libraries()
    dae = os.path.join(out_dir, "triangle.dae")
    with open(dae, "w") as f:
        f.write(triangle_dae())
    dae_triangles = len(hyvox.read_mesh(dae)[1])
    after_dae = mapped_libraries()
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
            "dae_triangles": dae_triangles,
            "loaded_by_dae": sorted(after_dae - after_gl),
        }, f, indent=1)


if __name__ == "__main__":
    main(*sys.argv[1:3])
