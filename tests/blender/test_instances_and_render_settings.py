# SPDX-License-Identifier: GPL-3.0-or-later
"""What the depsgraph evaluates is what gets voxelized: collection instances and Geometry
Nodes instances with their world matrices, curves and text, and modifiers at render
settings by default (viewport settings on request, also in the headless script)."""

import json
import math
import os

import bpy
import numpy as np
from mathutils import Matrix

import helpers
from helpers import AddonTestCase


def centres(obj):
    return helpers.sorted_rows(helpers.vdb_world_centres(bpy.path.abspath(obj.data.filepath)))


def last_triangles():
    from hyvox_blender.blender import operators

    return [v["triangles"] for v in operators.last_run_record["volumes"]]


def subdivided_cube(viewport_levels=1, render_levels=3):
    cube = helpers.cube("Smooth", 2.0)
    modifier = cube.modifiers.new("Subdivision", "SUBSURF")
    modifier.levels, modifier.render_levels = viewport_levels, render_levels
    return cube


# Catmull-Clark splits every quad into four per level; a cube has 6 quads, 2 triangles each.
def cube_triangles(levels):
    return 6 * 4**levels * 2


class InstancesAndRenderSettingsTest(AddonTestCase):
    def test_collection_instance_is_voxelized_where_it_is_placed(self):
        props = bpy.data.collections.new("Props")  # not in the scene: seen only through the instance
        piece = helpers.cube("Piece", 1.0, (1.0, 0.0, 0.0))
        bpy.context.scene.collection.objects.unlink(piece)
        props.objects.link(piece)
        empty = bpy.data.objects.new("PropsInstance", None)
        empty.instance_type, empty.instance_collection = "COLLECTION", props
        empty.location, empty.rotation_euler = (3.0, 2.0, 1.0), (0.0, 0.0, math.radians(90))
        bpy.context.scene.collection.objects.link(empty)
        # The oracle: the same cube as a plain object at the composed world matrix.
        real = helpers.cube("Real", 1.0)
        bpy.context.view_layer.update()
        real.matrix_world = Matrix(empty.matrix_world) @ Matrix.Translation((1.0, 0.0, 0.0))

        helpers.select_only(empty)
        self.assertEqual(self.voxelize(voxel_size=0.1), {"FINISHED"})
        helpers.select_only(real)
        self.voxelize(voxel_size=0.1)
        instanced, plain = centres(bpy.data.objects["PropsInstance_voxels"]), centres(bpy.data.objects["Real_voxels"])
        self.assertGreater(len(plain), 100)
        np.testing.assert_allclose(instanced, plain, atol=1e-5)
        self.assertAlmostEqual(float(instanced[:, 0].mean()), 3.0, delta=0.05)  # turned to (3, 3, 1)
        self.assertAlmostEqual(float(instanced[:, 1].mean()), 3.0, delta=0.05)

    def test_geometry_nodes_instances_on_points(self):
        piece = helpers.cube("Piece", 0.5)
        piece.hide_render = True  # only its instances count
        points = [(0, 0, 0), (2, 0, 0), (0, 3, 0)]
        scatter = helpers.mesh_object("Scatter", points, [])  # vertices only: no faces of its own
        scatter.location = (0, 0, 1)
        tree = bpy.data.node_groups.new("Scatter", "GeometryNodeTree")
        tree.inputs.new("NodeSocketGeometry", "Geometry")
        tree.outputs.new("NodeSocketGeometry", "Geometry")
        group_in, group_out = tree.nodes.new("NodeGroupInput"), tree.nodes.new("NodeGroupOutput")
        on_points, info = tree.nodes.new("GeometryNodeInstanceOnPoints"), tree.nodes.new("GeometryNodeObjectInfo")
        info.inputs["Object"].default_value = piece
        tree.links.new(group_in.outputs["Geometry"], on_points.inputs["Points"])
        tree.links.new(info.outputs["Geometry"], on_points.inputs["Instance"])
        tree.links.new(on_points.outputs["Instances"], group_out.inputs["Geometry"])
        scatter.modifiers.new("Scatter", "NODES").node_group = tree

        # The oracle: three plain cubes where the points are, voxelized as one volume.
        copies = [helpers.cube(f"Copy{n}", 0.5, (x, y, z + 1)) for n, (x, y, z) in enumerate(points)]
        helpers.select_only(scatter)
        self.assertEqual(self.voxelize(voxel_size=0.05), {"FINISHED"})
        self.assertEqual(last_triangles(), [3 * 12])
        helpers.select_only(*copies)
        self.voxelize(voxel_size=0.05)
        np.testing.assert_allclose(
            centres(bpy.data.objects["Scatter_voxels"]), centres(bpy.data.objects["Copy0_and_2_more_voxels"]), atol=1e-5
        )

    def test_a_mesh_with_instances_keeps_both(self):
        """Instancing on vertices (the parent's own faces and the children it instances)."""
        parent = helpers.cube("Parent", 1.0)
        parent.instance_type = "VERTS"
        parent.show_instancer_for_render = True
        child = helpers.cube("Child", 0.25)
        child.parent = parent
        helpers.select_only(parent)
        self.voxelize(voxel_size=0.05)
        self.assertEqual(last_triangles(), [12 + 8 * 12])  # its own cube and one child per vertex
        c = centres(bpy.data.objects["Parent_voxels"])
        self.assertGreater(c.max(), 0.5 + 0.05)  # the children at the corners reach beyond the cube

    def test_curve_and_text(self):
        bpy.ops.object.text_add(location=(0, 0, 0))
        text = bpy.context.object
        text.data.body, text.data.extrude = "Hi", 0.1
        curve_data = bpy.data.curves.new("Tube", "CURVE")
        curve_data.bevel_depth = 0.2
        spline = curve_data.splines.new("POLY")
        spline.points.add(1)
        spline.points[0].co, spline.points[1].co = (0, 0, 3, 1), (2, 0, 3, 1)
        tube = bpy.data.objects.new("Tube", curve_data)
        bpy.context.scene.collection.objects.link(tube)
        for obj in (text, tube):
            helpers.select_only(obj)
            self.assertEqual(self.voxelize(voxel_size=0.05), {"FINISHED"})
            # The independent count: the evaluated object converted to a mesh by Blender.
            evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
            mesh = evaluated.to_mesh()
            mesh.calc_loop_triangles()
            expected = len(mesh.loop_triangles)
            evaluated.to_mesh_clear()
            self.assertGreater(expected, 0)
            self.assertEqual(last_triangles(), [expected])

    def test_modifiers_at_render_settings_by_default(self):
        cube = subdivided_cube(viewport_levels=1, render_levels=3)
        helpers.select_only(cube)
        self.voxelize(voxel_size=0.1)
        self.assertEqual(last_triangles(), [cube_triangles(3)])
        self.voxelize(voxel_size=0.1, evaluation="VIEWPORT")
        self.assertEqual(last_triangles(), [cube_triangles(1)])
        self.assertEqual(bpy.context.scene.render.engine, "BLENDER_EEVEE")  # the scene's engine is back
        self.assertNotIn(
            "HYVOX_RENDER_EVALUATION", {e.bl_idname for e in bpy.types.RenderEngine.__subclasses__() if e.is_registered}
        )

    def test_hidden_in_renders_falls_back_to_the_viewport_with_a_warning(self):
        cube = subdivided_cube(viewport_levels=1, render_levels=3)
        cube.hide_render = True
        helpers.select_only(cube)
        self.voxelize(voxel_size=0.1)
        self.assertEqual(last_triangles(), [cube_triangles(1)])

    def test_headless_script_uses_render_settings_and_viewport_on_request(self):
        subdivided_cube(viewport_levels=1, render_levels=3)
        blend = os.path.join(self.out, "scene.blend")
        bpy.ops.wm.save_as_mainfile(filepath=blend, copy=True)
        for extra, levels in (([], 3), (["--viewport"], 1)):
            stats = os.path.join(self.out, f"stats{levels}.json")
            done = helpers.run_cli_script(
                blend,
                "--objects",
                "Smooth",
                "--voxel-size",
                "0.1",
                "--method",
                "cpu",
                "--output",
                self.out,
                "--stats-json",
                stats,
                *extra,
            )
            self.assertEqual(done.returncode, 0, done.stderr[-2000:])
            with open(stats) as f:
                self.assertEqual([v["triangles"] for v in json.load(f)["volumes"]], [cube_triangles(levels)])
