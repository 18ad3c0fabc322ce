# SPDX-License-Identifier: GPL-3.0-or-later
"""The colour an evaluated mesh shows, per triangle corner (core/colour.py's PartColour),
from the first of:
1. the mesh's active render colour attribute (point or face-corner domain, byte or float:
   Blender hands both out as linear floats);
2. per material slot, an Image Texture node feeding the Base Color of the material's
   surface shader (Principled BSDF, or any shader with a Color input), sampled at the
   active render UV map (the node's own Vector input is not followed);
3. per material slot, that Base Color's value (linear, as Blender keeps it), or the
   material's viewport colour when it has no nodes; no material: Blender's default grey.
An image's pixels are handed over as Blender holds them: bytes of an sRGB image stay
sRGB-encoded (uint8, hyvox decodes them), float or non-sRGB images are linear floats."""

from typing import Dict, Optional, Tuple

import bpy
import numpy as np

from ...core.colour import DEFAULT_GREY, PartColour, sample_bilinear

# image name -> (key, texture in hyvox's form), filled once per export
ImageCache = Dict[str, Tuple[str, np.ndarray]]


def _linked_from(socket) -> Optional[bpy.types.Node]:
    """The node feeding socket, through reroutes."""
    while socket is not None and socket.is_linked:
        node = socket.links[0].from_node
        if node.type != "REROUTE":
            return node
        socket = node.inputs[0]
    return None


def _surface_colour_socket(material: bpy.types.Material):
    """The Base Color (or Color) input of the shader on the material's active output."""
    if not material.use_nodes or material.node_tree is None:
        return None
    outputs = [n for n in material.node_tree.nodes if n.type == "OUTPUT_MATERIAL"]
    output = next((n for n in outputs if n.is_active_output), outputs[0] if outputs else None)
    shader = _linked_from(output.inputs["Surface"]) if output is not None else None
    if shader is None:
        return None
    for name in ("Base Color", "Color"):
        if name in shader.inputs:
            return shader.inputs[name]
    return None


def _image_pixels(image: bpy.types.Image) -> np.ndarray:
    """The image as hyvox.voxelize takes it: (H,W,C), row 0 = top."""
    width, height = image.size
    channels = image.channels
    pixels = np.empty(width * height * channels, np.float32)
    image.pixels.foreach_get(pixels)
    pixels = pixels.reshape(height, width, channels)[::-1, :, : min(channels, 4)]
    if channels < 3:  # grey: repeat into RGB
        pixels = np.repeat(pixels[..., :1], 3, axis=-1)
    elif channels == 4 and np.all(pixels[..., 3] == 1.0):
        pixels = pixels[..., :3]  # opaque: no `alpha` grid
    if not image.is_float and image.colorspace_settings.name == "sRGB":
        # A byte image's float pixels are its bytes / 255, still sRGB-encoded: back to bytes.
        return np.ascontiguousarray(np.round(pixels * 255.0).astype(np.uint8))
    return np.ascontiguousarray(pixels)


def material_source(material: Optional[bpy.types.Material], images: ImageCache):
    """("image", key, pixels) or ("flat", rgba) for one slot's material."""
    if material is None:
        return ("flat", DEFAULT_GREY)
    socket = _surface_colour_socket(material)
    if socket is None:
        return ("flat", tuple(material.diffuse_color))
    node = _linked_from(socket)
    if node is not None and node.type == "TEX_IMAGE" and node.image is not None and node.image.size[0] > 0:
        image = node.image
        if image.name_full not in images:
            images[image.name_full] = (image.name_full, _image_pixels(image))
        key, pixels = images[image.name_full]
        return ("image", key, pixels)
    value = socket.default_value
    return ("flat", tuple(value) if len(value) == 4 else tuple(value) + (1.0,))


def _render_colour_attribute(mesh: bpy.types.Mesh):
    attributes = getattr(mesh, "color_attributes", None)
    if attributes is None or not len(attributes):
        return None
    index = attributes.render_color_index
    return attributes[index] if 0 <= index < len(attributes) else attributes[0]


def _corner_indices(mesh: bpy.types.Mesh, field: str) -> np.ndarray:
    out = np.empty(len(mesh.loop_triangles) * 3, np.int32)
    mesh.loop_triangles.foreach_get(field, out)
    return out


def mesh_colour(evaluated: bpy.types.Object, mesh: bpy.types.Mesh, images: ImageCache) -> Optional[PartColour]:
    """The PartColour of an evaluated mesh whose loop triangles are computed; None when it
    has neither a colour attribute nor a material."""
    triangle_count = len(mesh.loop_triangles)
    attribute = _render_colour_attribute(mesh)
    if attribute is not None and attribute.domain in {"POINT", "CORNER"}:
        values = np.empty(len(attribute.data) * 4, np.float32)
        attribute.data.foreach_get("color", values)
        rows = _corner_indices(mesh, "vertices" if attribute.domain == "POINT" else "loops")
        return PartColour(corner_colors=values.reshape(-1, 4)[rows])

    slots = [s.material for s in evaluated.material_slots] or list(mesh.materials)
    if not any(m is not None for m in slots):
        return None  # nothing chose a colour: the object adds no colour to its group
    sources = [material_source(m, images) for m in slots] or [("flat", DEFAULT_GREY)]
    slot_of = np.zeros(triangle_count, np.int32)
    mesh.loop_triangles.foreach_get("material_index", slot_of)
    slot_of = np.clip(slot_of, 0, len(sources) - 1)
    palette = np.array([s[1] if s[0] == "flat" else DEFAULT_GREY for s in sources], np.float32)
    colour = PartColour(corner_colors=np.repeat(palette[slot_of], 3, axis=0))
    images_used = {s[1] for s in sources if s[0] == "image"}
    uv_layer = next((layer for layer in mesh.uv_layers if layer.active_render), None)
    if images_used and uv_layer is not None:
        # Triangles of the first image's slots take the texture; another image's slots in
        # the same mesh are sampled at their corners (one image per voxelize call).
        first = next(s for s in sources if s[0] == "image")
        textured = np.array([s[0] == "image" and s[1] == first[1] for s in sources])[slot_of]
        uvs = np.empty(len(uv_layer.data) * 2, np.float32)
        uv_layer.data.foreach_get("uv", uvs)
        colour.uvs = uvs.reshape(-1, 2)[_corner_indices(mesh, "loops")]
        colour.texture, colour.texture_key, colour.textured = first[2], first[1], textured
        for source_index, source in enumerate(sources):
            if source[0] == "image" and source[1] != first[1]:
                corners = np.repeat(slot_of == source_index, 3)
                colour.corner_colors[corners] = sample_bilinear(source[2], colour.uvs[corners])
    return colour
