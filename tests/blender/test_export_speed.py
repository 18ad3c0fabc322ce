# SPDX-License-Identifier: GPL-3.0-or-later
"""Exporting a 1M-triangle evaluated mesh into numpy takes well under a second
(foreach_get raw copies, no per-triangle Python)."""
import time

import bpy
import numpy as np

import helpers
from helpers import AddonTestCase


class ExportSpeedTest(AddonTestCase):
    def test_million_triangles(self):
        from hyvox_blender.blender.export import object_triangles
        bpy.ops.mesh.primitive_monkey_add()
        monkey = bpy.context.active_object
        monkey.modifiers.new("Subdivision", "SUBSURF").levels = 5
        monkey.location = (1.0, 2.0, 3.0)
        depsgraph = bpy.context.evaluated_depsgraph_get()  # subdivision evaluated, untimed
        start = time.perf_counter()
        vertices, triangles = object_triangles(monkey, depsgraph)
        seconds = time.perf_counter() - start
        print(f"exported {len(triangles):,} triangles in {seconds * 1000:.0f} ms")
        self.assertGreater(len(triangles), 1_000_000)
        self.assertLess(seconds, 1.0)
        self.assertEqual((vertices.dtype, triangles.dtype), (np.float32, np.uint32))
        self.assertLess(int(triangles.max()), len(vertices))
        # World space: the evaluated mesh's bounds moved by the object's location.
        evaluated = monkey.evaluated_get(depsgraph).data
        local = np.empty(len(evaluated.vertices) * 3, np.float32)
        evaluated.vertices.foreach_get("co", local)
        np.testing.assert_allclose(vertices.min(axis=0), local.reshape(-1, 3).min(axis=0) + [1, 2, 3],
                                   atol=1e-5)
