# SPDX-License-Identifier: GPL-3.0-or-later
"""A run at render settings skips the render evaluation only where it would change nothing
(blender/export/render_equivalence.py): checked against what a render evaluation actually exports
(blender/export/render_depsgraph.py), for a plain mesh (skipped: the same arrays) and for each thing that
makes renders differ (not skipped)."""

import bpy
import numpy as np

import helpers
from helpers import AddonTestCase


def exported(names, depsgraph):
    """{name: [(vertices, triangles)]} of what the export takes from depsgraph."""
    parts = helpers.addon("blender.export.sources").evaluated_parts(names, depsgraph)
    return {name: [(v.copy(), t.copy()) for v, t, _ in found] for name, found in parts.items()}


def render_and_viewport(names):
    render_depsgraph = helpers.addon("blender.export.render_depsgraph")
    in_render = render_depsgraph.with_render_depsgraph(bpy.context, lambda depsgraph: exported(names, depsgraph))
    return in_render, exported(names, bpy.context.evaluated_depsgraph_get())


def same_arrays(a, b):
    return a.keys() == b.keys() and all(
        len(a[n]) == len(b[n]) and all(np.array_equal(x, y) for p, q in zip(a[n], b[n]) for x, y in zip(p, q))
        for n in a
    )


class RenderEquivalenceTest(AddonTestCase):
    def claim(self, obj):
        same_in_renders = helpers.addon("blender.export.render_equivalence").same_in_renders
        return same_in_renders([obj.name], bpy.context.view_layer)

    def assert_claim_holds(self, obj, expected_claim):
        in_render, in_viewport = render_and_viewport([obj.name])
        claim = self.claim(obj)
        self.assertEqual(claim, expected_claim)
        if claim:
            self.assertTrue(same_arrays(in_render, in_viewport))
        return in_render, in_viewport

    def test_plain_mesh_is_the_same_in_renders(self):
        cube = helpers.cube("Plain")
        cube.rotation_euler = (0.3, 0.2, 0.1)
        self.assert_claim_holds(cube, True)

    def test_modifier_with_render_levels(self):
        cube = helpers.cube("Smooth")
        modifier = cube.modifiers.new("Subdivision", "SUBSURF")
        modifier.levels, modifier.render_levels = 1, 2
        in_render, in_viewport = self.assert_claim_holds(cube, False)
        self.assertFalse(same_arrays(in_render, in_viewport))  # the case the rule is there for

    def test_hidden_in_renders(self):
        cube = helpers.cube("Hidden")
        cube.hide_render = True
        in_render, in_viewport = self.assert_claim_holds(cube, False)
        self.assertNotIn("Hidden", in_render)

    def test_in_a_collection_hidden_in_renders(self):
        outer = bpy.data.collections.new("Outer")
        inner = bpy.data.collections.new("Inner")
        bpy.context.scene.collection.children.link(outer)
        outer.children.link(inner)
        cube = helpers.cube("Nested")
        bpy.context.scene.collection.objects.unlink(cube)
        inner.objects.link(cube)
        try:
            self.assert_claim_holds(cube, True)
            outer.hide_render = True  # hides the child collection's objects too
            in_render, _ = self.assert_claim_holds(cube, False)
            self.assertNotIn("Nested", in_render)
        finally:
            bpy.data.collections.remove(inner)
            bpy.data.collections.remove(outer)

    def test_instancing_and_curves(self):
        parent = helpers.cube("Parent")
        child = helpers.cube("Child", 0.2)
        child.parent = parent
        parent.instance_type = "VERTS"
        self.assertFalse(self.claim(parent))
        self.assertFalse(self.claim(child))
        curve = bpy.data.curves.new("Tube", "CURVE")
        curve.bevel_depth = 0.2
        spline = curve.splines.new("POLY")
        spline.points.add(1)
        tube = bpy.data.objects.new("Tube", curve)
        bpy.context.scene.collection.objects.link(tube)
        self.assertFalse(self.claim(tube))

    def test_hidden_in_the_viewport(self):
        cube = helpers.cube("Unseen")
        cube.hide_viewport = True
        self.assertFalse(self.claim(cube))
        cube.hide_viewport = False
        cube.hide_set(True)
        self.assertFalse(self.claim(cube))

    def test_operator_skips_the_render_only_when_the_rule_says_so(self):
        # The same voxels either way; the render evaluation runs only when the rule says no.
        # The operator exports each frame through frame_export, which asks these two modules.
        exporter = helpers.addon("blender.export.frames")
        render_calls = []
        real_render = exporter.render_depsgraph.with_render_depsgraph
        real_rule = exporter.render_equivalence.same_in_renders

        def counting_render(*args):
            render_calls.append(1)
            return real_render(*args)

        results = []
        for forced_render in (False, True):
            helpers.clear_scene()
            cube = helpers.cube("Plain")
            cube.rotation_euler = (0.3, 0.2, 0.1)
            helpers.select_only(cube)
            exporter.render_depsgraph.with_render_depsgraph = counting_render
            if forced_render:
                exporter.render_equivalence.same_in_renders = lambda names, view_layer: False
            try:
                self.voxelize(voxel_size=0.1)
            finally:
                exporter.render_depsgraph.with_render_depsgraph = real_render
                exporter.render_equivalence.same_in_renders = real_rule
            self.assertEqual(len(render_calls), int(forced_render))
            path = bpy.path.abspath(self.volumes()[0].data.filepath)
            results.append(helpers.sorted_rows(helpers.vdb_world_centres(path)))
        self.assertGreater(len(results[0]), 0)
        np.testing.assert_array_equal(results[0], results[1])
