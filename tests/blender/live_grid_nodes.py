# SPDX-License-Identifier: GPL-3.0-or-later
"""Blender 5.0+: Geometry Nodes on another object read a live volume's grids (Object Info,
then Get Named Grid) and follow when Live updates them: Grid to Mesh of `density` gives a
mesh over the voxels, Sample Grid of `color` gives the source's colour, and both change
when the source is edited. Registered for the bpy 5.x venvs only (the grid nodes are 5.0's)."""

import bpy
import numpy as np

import helpers
from helpers import AddonTestCase


def reader_tree(volume, centre):
    """Object Info (the volume) -> Get Named Grid density -> Grid to Mesh, and on that mesh
    an attribute `sampled`: Sample Grid of `color` at the point `centre`."""
    tree = bpy.data.node_groups.new("Read hyvox grids", "GeometryNodeTree")
    tree.interface.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    nodes, link = tree.nodes, tree.links.new
    info = nodes.new("GeometryNodeObjectInfo")
    info.transform_space = "RELATIVE"
    info.inputs["Object"].default_value = volume
    density = nodes.new("GeometryNodeGetNamedGrid")
    density.data_type = "FLOAT"
    density.inputs["Name"].default_value = "density"
    link(info.outputs["Geometry"], density.inputs["Volume"])
    to_mesh = nodes.new("GeometryNodeGridToMesh")
    to_mesh.inputs["Threshold"].default_value = 0.5
    link(density.outputs["Grid"], to_mesh.inputs["Grid"])
    colour = nodes.new("GeometryNodeGetNamedGrid")
    colour.data_type = "VECTOR"
    colour.inputs["Name"].default_value = "color"
    link(info.outputs["Geometry"], colour.inputs["Volume"])
    sample = nodes.new("GeometryNodeSampleGrid")
    sample.data_type = "VECTOR"
    link(colour.outputs["Grid"], sample.inputs["Grid"])
    where = nodes.new("FunctionNodeInputVector")
    where.vector = centre
    link(where.outputs[0], sample.inputs["Position"])
    store = nodes.new("GeometryNodeStoreNamedAttribute")
    store.data_type, store.domain = "FLOAT_VECTOR", "POINT"
    store.inputs["Name"].default_value = "sampled"
    link(to_mesh.outputs["Mesh"], store.inputs["Geometry"])
    link(sample.outputs["Value"], store.inputs["Value"])
    output = nodes.new("NodeGroupOutput")
    link(store.outputs["Geometry"], output.inputs["Geometry"])
    return tree


def evaluated(reader):
    """(vertex positions (N,3), the `sampled` colour of the first point) of the reader."""
    mesh = reader.evaluated_get(bpy.context.evaluated_depsgraph_get()).data
    co = np.empty(len(mesh.vertices) * 3, np.float32)
    mesh.vertices.foreach_get("co", co)
    sampled = np.array(mesh.attributes["sampled"].data[0].vector[:]) if len(mesh.vertices) else None
    return co.reshape(-1, 3), sampled


class LiveGridNodesTest(AddonTestCase):
    def test_grid_nodes_follow_the_live_volume(self):
        source = helpers.cube(size=1.0)
        material = bpy.data.materials.new("Red")
        material.use_nodes = True
        bsdf = material.node_tree.nodes["Principled BSDF"]
        bsdf.inputs["Base Color"].default_value = (0.8, 0.1, 0.05, 1.0)
        source.data.materials.append(material)
        helpers.select_only(source)
        self.assertEqual(self.voxelize(live=True, voxel_size=0.1, mode="solid", color=True), {"FINISHED"})
        volume = bpy.data.objects["Cube_voxels"]
        reader = bpy.data.objects.new("Reader", bpy.data.meshes.new("Reader"))
        bpy.context.scene.collection.objects.link(reader)
        reader.modifiers.new("Read", "NODES").node_group = reader_tree(volume, (0.02, 0.03, 0.01))
        bpy.context.view_layer.update()
        points, colour = evaluated(reader)
        self.assertGreater(len(points), 0)
        # The mesh wraps the voxels: the cube's half size 0.5, within a voxel.
        np.testing.assert_allclose(points.max(axis=0), [0.5] * 3, atol=0.1)
        np.testing.assert_allclose(colour, (0.8, 0.1, 0.05), atol=1e-3)

        source.scale.x = 2.0  # an edit of the source
        bpy.context.view_layer.update()
        points, colour = evaluated(reader)
        np.testing.assert_allclose(points.max(axis=0), [1.0, 0.5, 0.5], atol=0.1)
        np.testing.assert_allclose(points.min(axis=0), [-1.0, -0.5, -0.5], atol=0.1)
        np.testing.assert_allclose(colour, (0.8, 0.1, 0.05), atol=1e-3)
        bsdf.inputs["Base Color"].default_value = (0.1, 0.2, 0.9, 1.0)  # an edit of its material
        bpy.context.view_layer.update()
        points, colour = evaluated(reader)
        np.testing.assert_allclose(colour, (0.1, 0.2, 0.9), atol=1e-3)
