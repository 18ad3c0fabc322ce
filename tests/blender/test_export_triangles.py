# SPDX-License-Identifier: GPL-3.0-or-later
"""The export's triangles (blender/export/triangles.py, read the fast way each Blender allows)
are Blender's own loop triangles, read here one by one through the per-item API: the same
vertex triples in the same order, for triangles, planar, non-planar, concave and folded
quads, convex, concave and non-planar n-gons, each kind alone and all mixed, as plain
meshes and as evaluated through modifiers."""

import math

import bpy
import numpy as np

import helpers
from helpers import AddonTestCase


def polygon_object(name, vertices, faces):
    """A mesh object of faces of any sizes (from_pydata keeps them in the given order)."""
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([tuple(map(float, v)) for v in vertices], [], [tuple(f) for f in faces])
    mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def random_triangles(rng, count=300):
    points = rng.uniform(-1, 1, (count // 2, 3))
    return points, [tuple(rng.choice(len(points), 3, replace=False)) for _ in range(count)]


def quad_grid(rng, size, jitter):
    """size x size quads over the unit square, heights jittered by up to jitter: with a
    large jitter many quads fold over their 0-2 diagonal, so Blender splits them along 1-3."""
    xs, ys = np.meshgrid(np.arange(size + 1), np.arange(size + 1), indexing="ij")
    points = np.stack([xs.ravel(), ys.ravel(), rng.uniform(-jitter, jitter, xs.size)], 1)
    faces = []
    for i in range(size):
        for j in range(size):
            a = i * (size + 1) + j
            faces.append((a, a + size + 1, a + size + 2, a + 1))
    return points, faces


def concave_quads():
    """Darts concave at each corner in turn: Blender flips the ones concave at 0 or 2."""
    dart = [(0, 0, 0), (2, 0, 0), (0.6, 0.6, 0), (0, 2, 0)]  # concave at corner 2
    points, faces = [], []
    for shift in range(4):
        base = len(points)
        points += [(x + 3 * shift, y, z) for x, y, z in dart]
        faces.append(tuple(base + (k + shift) % 4 for k in range(4)))
    return np.array(points), faces


def ngons(rng):
    points, faces = [], []

    def add(ring):
        base = len(points)
        points.extend(ring)
        faces.append(tuple(range(base, base + len(ring))))

    add([(math.cos(a), math.sin(a), 0) for a in np.linspace(0, 2 * math.pi, 7)[:-1]])  # convex hexagon
    add(
        [
            (
                (1.0 if k % 2 == 0 else 0.4) * math.cos(k * math.pi / 5) + 3,
                (1.0 if k % 2 == 0 else 0.4) * math.sin(k * math.pi / 5),
                0,
            )
            for k in range(10)
        ]
    )  # star
    add([(6, 0, 0), (8, 0, 0), (8, 0.5, 0), (6.5, 0.5, 0), (6.5, 2, 0), (6, 2, 0)])  # L
    add(
        [(math.cos(a) + 10, math.sin(a), rng.uniform(-0.5, 0.5)) for a in np.linspace(0, 2 * math.pi, 9)[:-1]]
    )  # non-planar octagon
    return np.array(points), faces


def merged(*parts):
    points, faces = [], []
    for part_points, part_faces in parts:
        base = len(points)
        points.extend(map(tuple, np.asarray(part_points, float)))
        faces.extend(tuple(base + v for v in face) for face in part_faces)
    return np.array(points), faces


def blender_triangles(mesh):
    """Blender's loop triangles' vertices, one triangle at a time."""
    if hasattr(mesh, "calc_loop_triangles"):
        mesh.calc_loop_triangles()
    return np.array([tuple(t.vertices) for t in mesh.loop_triangles], np.int64).reshape(-1, 3)


class ExportTrianglesTest(AddonTestCase):
    def assert_blender_triangles(self, obj):
        mesh_triangles = helpers.addon("blender.export.triangles")
        evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get()).data
        got = mesh_triangles.loop_triangles(evaluated)
        self.assertEqual(got.dtype, np.uint32)
        expected = blender_triangles(evaluated)
        self.assertGreater(len(expected), 0)
        np.testing.assert_array_equal(got.astype(np.int64), expected)
        # And through the export itself (world space, the same triangles).
        _, exported = helpers.addon("blender.export.sources").object_triangles(
            obj, bpy.context.evaluated_depsgraph_get()
        )
        np.testing.assert_array_equal(exported.astype(np.int64), expected)
        return expected

    def test_each_kind_of_face(self):
        rng = np.random.default_rng(17)
        cases = {
            "triangles": random_triangles(rng),
            "planar_quads": quad_grid(rng, 12, 0.0),
            "non_planar_quads": quad_grid(rng, 12, 0.3),
            "folded_quads": quad_grid(rng, 20, 3.0),
            "concave_quads": concave_quads(),
            "ngons": ngons(rng),
        }
        cases["all_mixed"] = merged(*cases.values())
        for name, (points, faces) in cases.items():
            with self.subTest(name):
                self.assert_blender_triangles(polygon_object(name, points, faces))

    def test_quads_split_along_both_diagonals(self):
        # The case that matters: the test must see Blender take the 1-3 diagonal too.
        points, faces = merged(quad_grid(np.random.default_rng(3), 20, 3.0), concave_quads())
        triangles = self.assert_blender_triangles(polygon_object("Folded", points, faces))
        quads = np.array(faces)
        third_of_first = triangles[0::2, 2]  # (0,1,2) of a quad, or (0,1,3) when split along 1-3
        flipped = third_of_first == quads[:, 3]
        np.testing.assert_array_equal(flipped | (third_of_first == quads[:, 2]), True)
        self.assertGreater(flipped.sum(), 0)
        self.assertGreater((~flipped).sum(), 0)

    def test_evaluated_through_modifiers(self):
        for kind in ("SUBSURF", "TRIANGULATE", "BEVEL"):
            with self.subTest(kind):
                helpers.clear_scene()
                cube = helpers.cube("Cube")
                modifier = cube.modifiers.new(kind, kind)
                if kind == "SUBSURF":
                    modifier.levels = 2
                self.assert_blender_triangles(cube)

    def test_large_mesh_of_quads_then_of_triangles(self):
        bpy.ops.mesh.primitive_monkey_add()
        monkey = bpy.context.active_object
        monkey.modifiers.new("Subdivision", "SUBSURF").levels = 4  # quads only
        self.assert_blender_triangles(monkey)
        monkey.modifiers.new("Triangulate", "TRIANGULATE")  # triangles only
        self.assert_blender_triangles(monkey)
