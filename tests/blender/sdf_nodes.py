# SPDX-License-Identifier: GPL-3.0-or-later
"""Blender 5's SDF grid nodes on a Signed Distance volume (run in the bpy 5.x releases only:
earlier Blenders have no SDF grid nodes): Object Info -> Get Named Grid `sdf` -> SDF Grid Offset
-> Grid to Mesh gives a closed mesh at the offset distance from the source surface."""

import bpy
import numpy as np

import helpers
from helpers import AddonTestCase

VOXEL = 0.05
OFFSET = 0.12


def offset_mesh(volume_object, distance):
    """A new object whose Geometry Nodes read the volume's `sdf`, offset it and mesh it: its
    evaluated vertices (world) and how many faces use each of its edges."""
    tree = bpy.data.node_groups.new("SDF Offset", "GeometryNodeTree")
    tree.interface.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    nodes, links = tree.nodes, tree.links
    output = nodes.new("NodeGroupOutput")
    info = nodes.new("GeometryNodeObjectInfo")
    info.inputs["Object"].default_value = volume_object
    info.transform_space = "RELATIVE"
    grid = nodes.new("GeometryNodeGetNamedGrid")
    grid.data_type = "FLOAT"
    grid.inputs["Name"].default_value = "sdf"
    offset = nodes.new("GeometryNodeSDFGridOffset")
    offset.inputs["Distance"].default_value = distance
    to_mesh = nodes.new("GeometryNodeGridToMesh")
    to_mesh.inputs["Threshold"].default_value = 0.0  # the zero crossing (the node's default, 0.1, suits a density)
    links.new(info.outputs["Geometry"], grid.inputs["Volume"])
    links.new(grid.outputs["Grid"], offset.inputs["Grid"])
    links.new(offset.outputs["Grid"], to_mesh.inputs["Grid"])
    links.new(to_mesh.outputs["Mesh"], output.inputs["Geometry"])
    probe = helpers.mesh_object("Probe", [], [])
    modifier = probe.modifiers.new("SDF", "NODES")
    modifier.node_group = tree
    depsgraph = bpy.context.evaluated_depsgraph_get()
    mesh = probe.evaluated_get(depsgraph).to_mesh()
    vertices = np.empty(len(mesh.vertices) * 3, np.float32)
    mesh.vertices.foreach_get("co", vertices)
    # Each face corner names the edge that follows it: a closed mesh uses every edge twice.
    loop_edges = np.empty(len(mesh.loops), np.int32)
    mesh.loops.foreach_get("edge_index", loop_edges)
    uses = np.bincount(loop_edges, minlength=len(mesh.edges))
    return vertices.reshape(-1, 3).astype(np.float64), uses


class SdfNodesTest(AddonTestCase):
    def test_offset_and_grid_to_mesh_follow_the_source(self):
        bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=1.0, location=(0, 0, 0))
        sphere = bpy.context.active_object
        helpers.select_only(sphere)
        self.assertEqual(self.voxelize(voxel_size=VOXEL, signed_distance=True), {"FINISHED"})
        (volume,) = self.volumes()
        for distance in (0.0, OFFSET, -OFFSET):
            with self.subTest(distance=distance):
                vertices, uses = offset_mesh(volume, distance)
                self.assertGreater(len(vertices), 1000)
                self.assertTrue(np.all(uses == 2), "the mesh is not closed")
                # The faceted sphere lies between radius 1 and its faces' depth below it
                # (a face's middle: cos(pi / 64) cos(pi / 32)); SDF Grid Offset grows the
                # surface by `distance` (negative: shrinks it); the mesh's vertices, linearly
                # interpolated between voxel centres, stray a fraction of a voxel.
                radius = np.linalg.norm(vertices, axis=1) - distance
                facets = 1 - np.cos(np.pi / 64) * np.cos(np.pi / 32)
                self.assertGreater(radius.min(), 1 - facets - 0.3 * VOXEL, distance)
                self.assertLess(radius.max(), 1 + 0.3 * VOXEL, distance)
                self.assertLess(abs(np.median(radius) - 1), facets, distance)
