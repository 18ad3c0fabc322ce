# SPDX-License-Identifier: GPL-3.0-or-later
"""The material of a hyvox volume: a Principled Volume whose density is the `density` grid
times the density of the run (core/volume_look.py), and whose Color is the albedo that makes
the `color` grid's surface colour look right, when the run made colour.

The Density is a plain value, set by each run: Cycles 5.0 takes seconds longer per render to
prepare a volume whose density comes through a node it cannot fold into a constant (such as
an Attribute node reading the object). The material remembers the value it was given
(DENSITY_KEY), so a re-run tells its own value from one the artist set, and keeps the
artist's.

The nodes the add-on makes carry names starting with NODE_PREFIX, so a re-run that keeps
the volume's material can tell its own nodes from the artist's: sync() adds the colour
nodes when the grids gained a `color` grid (the Color socket still the add-on's grey),
takes them out when they lost it (a missing grid would read black), and upgrades a material
made by an earlier version of the add-on (its density the 1 / voxel size it set, its colour
the `color` attribute linked straight in). Whatever else the artist changed or linked stays."""

from typing import Optional

import bpy

from ...core import volume_look

NODE_PREFIX = "hyvox "
# The Principled Volume's Color without a `color` grid: the albedo of Blender's grey surface.
GREY = (volume_look.surface_albedo(volume_look.SURFACE_GREY),) * 3 + (1.0,)
LEGACY_GREY = (0.8, 0.8, 0.8, 1.0)  # what earlier versions set
DENSITY_KEY = "hyvox_density"  # on the material: the Density the add-on last set
COLOR = NODE_PREFIX + "Color"
GRID_DENSITY = NODE_PREFIX + "Grid Density"
COLOR_SUM = NODE_PREFIX + "Color Sum"
COLOR_SQUARE = NODE_PREFIX + "Color Square"
COLOR_WEIGHT = NODE_PREFIX + "Color Weight"
COLOR_PRODUCT = NODE_PREFIX + "Color Product"
ALBEDO = NODE_PREFIX + "Albedo"
COLOR_NODES = (COLOR, GRID_DENSITY, COLOR_SUM, COLOR_SQUARE, COLOR_WEIGHT, COLOR_PRODUCT, ALBEDO)


def _node(tree, kind: str, name: str, label: str, location):
    node = tree.nodes.new(kind)
    node.name, node.label, node.location = name, label, location
    return node


def _attribute(tree, name: str, label: str, attribute: str, kind: str, location):
    node = _node(tree, "ShaderNodeAttribute", name, label, location)
    node.attribute_type = kind
    node.attribute_name = attribute
    return node


def output_shader(material, socket: str, node_type: str) -> Optional[bpy.types.Node]:
    """The node of `node_type` feeding the material output's `socket`, or None (then that
    part of the material is the artist's own)."""
    if material is None or not material.use_nodes or material.node_tree is None:
        return None
    for node in material.node_tree.nodes:
        if node.type == "OUTPUT_MATERIAL" and node.inputs[socket].links:
            source = node.inputs[socket].links[0].from_node
            return source if source.type == node_type else None
    return None


def _volume_shader(material) -> Optional[bpy.types.Node]:
    return output_shader(material, "Volume", "PRINCIPLED_VOLUME")


def _set_density(material, shader, density: float) -> None:
    shader.inputs["Density"].default_value = density
    material[DENSITY_KEY] = density


def _close(value: float, other: float) -> bool:
    return abs(value - other) <= 1e-5 * max(abs(other), 1e-30)


def _link_color(tree, shader) -> None:
    """Color = the albedo core/volume_look.py gives the surface colour c = color / density:
    4 c / (1 + c)^2, written as 4 color density / (density + color)^2 (the same where
    density > 0, and 0 where both grids fade to 0: Blender's vector division by 0 gives 0)."""
    x, y = shader.location
    color = _attribute(tree, COLOR, "Color grid", "color", "GEOMETRY", (x - 1000, y + 80))
    density = _attribute(tree, GRID_DENSITY, "Density grid", "density", "GEOMETRY", (x - 1000, y - 120))
    total = _node(tree, "ShaderNodeVectorMath", COLOR_SUM, "Density + Color", (x - 750, y + 120))
    total.operation = "ADD"
    square = _node(tree, "ShaderNodeVectorMath", COLOR_SQUARE, "Squared", (x - 500, y + 120))
    square.operation = "MULTIPLY"
    weight = _node(tree, "ShaderNodeMath", COLOR_WEIGHT, "4 x Density", (x - 750, y - 100))
    weight.operation = "MULTIPLY"
    weight.inputs[1].default_value = 4.0
    product = _node(tree, "ShaderNodeVectorMath", COLOR_PRODUCT, "4 x Density x Color", (x - 500, y - 60))
    product.operation = "SCALE"
    albedo = _node(tree, "ShaderNodeVectorMath", ALBEDO, "Albedo", (x - 250, y + 40))
    albedo.operation = "DIVIDE"
    links = tree.links
    links.new(color.outputs["Vector"], total.inputs[0])
    links.new(density.outputs["Fac"], total.inputs[1])
    links.new(total.outputs["Vector"], square.inputs[0])
    links.new(total.outputs["Vector"], square.inputs[1])
    links.new(density.outputs["Fac"], weight.inputs[0])
    links.new(color.outputs["Vector"], product.inputs[0])
    links.new(weight.outputs["Value"], product.inputs["Scale"])
    links.new(product.outputs["Vector"], albedo.inputs[0])
    links.new(square.outputs["Vector"], albedo.inputs[1])
    links.new(albedo.outputs["Vector"], shader.inputs["Color"])


def _set_density_attribute(shader) -> None:
    if "Density Attribute" in shader.inputs:  # a socket in Blender 4.x
        shader.inputs["Density Attribute"].default_value = "density"
    elif hasattr(shader, "density_attribute"):
        shader.density_attribute = "density"


def make(name: str, has_color: bool, density: float) -> bpy.types.Material:
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    tree = material.node_tree
    tree.nodes.clear()
    output = tree.nodes.new("ShaderNodeOutputMaterial")
    output.location = (300, 0)
    shader = tree.nodes.new("ShaderNodeVolumePrincipled")
    shader.location = (0, 0)
    shader.inputs["Color"].default_value = GREY
    _set_density_attribute(shader)
    _set_density(material, shader, density)
    if has_color:
        _link_color(tree, shader)
    tree.links.new(shader.outputs["Volume"], output.inputs["Volume"])
    return material


def _remove_unlinked(tree, node) -> None:
    if node is not None and not any(socket.links for socket in node.outputs):
        tree.nodes.remove(node)


def _same(color, other) -> bool:
    return all(abs(a - b) < 1e-6 for a, b in zip(color, other))


def _color_source(shader):
    links = shader.inputs["Color"].links
    return links[0].from_node if links else None


def _is_legacy_color(node) -> bool:
    """An earlier version's colour: the `color` attribute linked straight to Color."""
    return (
        node is not None
        and node.type == "ATTRIBUTE"
        and node.attribute_name == "color"
        and not node.name.startswith(NODE_PREFIX)
    )


def _remove_color_nodes(tree) -> None:
    for name in COLOR_NODES:
        node = tree.nodes.get(name)
        if node is not None:
            tree.nodes.remove(node)


def sync(material, has_color: bool, density: float, legacy_voxel_size: float = 0.0) -> None:
    """Bring a kept material in line with the new grids and density (see the module's
    docstring). legacy_voxel_size: the replaced volume's voxel size, whose 1 / size an
    earlier version set as the Density."""
    shader = _volume_shader(material)
    if shader is None:
        return
    tree = material.node_tree
    socket = shader.inputs["Density"]
    ours = material.get(DENSITY_KEY)
    if not socket.links and (
        (ours is not None and _close(socket.default_value, float(ours)))
        or (ours is None and legacy_voxel_size > 0 and _close(socket.default_value, 1.0 / legacy_voxel_size))
    ):
        _set_density(material, shader, density)

    source = _color_source(shader)
    ours = source is not None and source.name == ALBEDO
    legacy = _is_legacy_color(source)
    value = tuple(shader.inputs["Color"].default_value)
    at_grey = source is None and any(_same(value, grey) for grey in (GREY, LEGACY_GREY))
    if has_color and (at_grey or legacy):
        if legacy:
            tree.links.remove(shader.inputs["Color"].links[0])
            _remove_unlinked(tree, source)
        _remove_color_nodes(tree)  # leftovers the artist unlinked
        _link_color(tree, shader)
    elif not has_color and at_grey:
        shader.inputs["Color"].default_value = GREY
    elif not has_color and (ours or legacy):
        tree.links.remove(shader.inputs["Color"].links[0])
        if legacy:
            _remove_unlinked(tree, source)
        _remove_color_nodes(tree)
        shader.inputs["Color"].default_value = GREY


def for_result(kept, name: str, has_color: bool, density: float, legacy_voxel_size: float = 0.0) -> bpy.types.Material:
    """The material a new volume gets: the replaced volume's (kept, brought in line by
    sync), or a new one."""
    if kept is None:
        return make(name, has_color, density)
    sync(kept, has_color, density, legacy_voxel_size)
    return kept
