# SPDX-License-Identifier: GPL-3.0-or-later
"""A 1M-triangle evaluated mesh exports into numpy whole and in world space. (How fast is
measured by bench/bench_blender_addon.py, not asserted here.)"""

import bpy
import numpy as np

import helpers
from helpers import AddonTestCase


class ExportLargeMeshTest(AddonTestCase):
    def test_million_triangles(self):
        object_triangles = helpers.addon("blender.export.sources").object_triangles
        bpy.ops.mesh.primitive_monkey_add()
        monkey = bpy.context.active_object
        monkey.modifiers.new("Subdivision", "SUBSURF").levels = 5
        monkey.location = (1.0, 2.0, 3.0)
        depsgraph = bpy.context.evaluated_depsgraph_get()
        vertices, triangles = object_triangles(monkey, depsgraph)
        self.assertEqual((vertices.dtype, triangles.dtype), (np.float32, np.uint32))

        # Independent of the export's foreach_get path: Blender's own per-item API.
        evaluated = monkey.evaluated_get(depsgraph).data
        evaluated.calc_loop_triangles()
        self.assertGreater(len(evaluated.loop_triangles), 1_000_000)
        self.assertEqual(len(triangles), len(evaluated.loop_triangles))
        self.assertEqual(len(vertices), len(evaluated.vertices))
        # Spot-check triangles spread over the whole mesh, and their world positions.
        for index in np.linspace(0, len(triangles) - 1, 257).astype(int):
            expected = tuple(evaluated.loop_triangles[int(index)].vertices)
            self.assertEqual(tuple(int(v) for v in triangles[index]), expected)
            for corner in expected:
                local = evaluated.vertices[corner].co
                np.testing.assert_allclose(vertices[corner], (local.x + 1, local.y + 2, local.z + 3), atol=1e-5)
