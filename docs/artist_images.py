# SPDX-License-Identifier: GPL-3.0-or-later
"""Make the before/after renders of docs/artist.md and print what they measure:

    BUILD/venv/bpy50/bin/python docs/artist_images.py BUILD [OUT]    # Cycles and Blocks (Blender 5.0)
    blender -b --factory-startup --python docs/artist_images.py -- BUILD [OUT]   # EEVEE (Debian's 3.4)

BUILD is a build folder (the add-on is taken from BUILD/addon, or installed from the extension
zip in a bpy module); OUT defaults to docs/images. Writes small PNG strips:
- color_cycles.png (Blender 4.2+): Spot (its texture) as a mesh | its colour volume with the material earlier
  versions made | with the add-on's material at Cycles' defaults | with Volume bounces 16;
- color_eevee.png (Blender 3.x, whose EEVEE draws volume light on software GL): mesh | volume
  at EEVEE's defaults | at Volumetrics Tile Size 2, Samples 128, Start and End around Spot;
- blocks.png (Blender 4.2+): the Blocks of a sphere smooth shaded (as new faces are from Blender 4.1 on) |
  flat shaded (as the add-on makes them).
and prints, for each volume render, its mean brightness against the mesh's and the largest
difference of the mean colour's chromaticity (rgb / (r + g + b)) from the mesh's, and (Blender
4.2+) what Geometry Nodes' Sample Grid reads of the `color` grid at Spot's surface."""

import math
import os
import sys
import tempfile

if "bpy" not in sys.modules:  # the bpy module: a fresh Blender user folder, read on first import
    os.environ.setdefault("BLENDER_USER_RESOURCES", tempfile.mkdtemp(prefix="hyvox-docs-user-"))
import bpy  # noqa: E402
import numpy as np  # noqa: E402
from mathutils import Vector  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
MESHES = os.environ.get("HYVOX_MESH_DIR", os.path.join(ROOT, "..", "shared", "data", "meshes"))
PANEL = 144  # pixels per side of one image in a strip
BACKGROUND = 0.15  # the world's grey, shown behind the renders


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else sys.argv[1:]
    if not argv:
        raise SystemExit(__doc__)
    return os.path.abspath(argv[0]), os.path.abspath(argv[1] if len(argv) > 1 else os.path.join(HERE, "images"))


def enable_addon(build):
    """The add-on of this build, as the tests enable it (tests/blender/helpers.py)."""
    sys.path.insert(0, os.path.join(ROOT, "tests", "blender"))
    if bpy.app.version >= (4, 2, 0) and not bpy.app.binary_path:
        import run_bpy_tests  # the bpy module: install the extension zip into a fresh user folder

        run_bpy_tests.install_extension(build, os.environ["BLENDER_USER_RESOURCES"])
    else:
        import helpers

        helpers.enable_addon(build)
    import helpers

    return helpers


def spot(helpers):
    """Spot with its texture, as an artist imports it (UV map, Image Texture into Base Color)."""
    hyvox = helpers.hyvox_module()
    vertices, triangles, attributes = hyvox.read_mesh(os.path.join(MESHES, "spot_uv.ply"), attributes=True)
    obj = helpers.mesh_object("Spot", vertices, triangles)
    uv = obj.data.uv_layers.new(name="UVMap")
    uv.data.foreach_set("uv", attributes["uvs"][triangles.reshape(-1)].astype(np.float32).ravel())
    material = bpy.data.materials.new("Spot")
    material.use_nodes = True
    tree = material.node_tree
    texture = tree.nodes.new("ShaderNodeTexImage")
    texture.image = bpy.data.images.load(os.path.join(MESHES, "spot_texture.png"))
    tree.links.new(texture.outputs["Color"], tree.nodes["Principled BSDF"].inputs["Base Color"])
    obj.data.materials.append(material)
    obj.rotation_euler.x = math.pi / 2  # the file is y-up, as Blender's importers turn it
    bpy.context.view_layer.update()
    return obj


def stage(helpers, target, distance=3.4):
    """A camera looking at the target's bounds centre from the front left, a sun, a dim world."""
    scene = bpy.context.scene
    corners = np.array([target.matrix_world @ Vector(c) for c in target.bound_box])
    centre = Vector(((corners.min(axis=0) + corners.max(axis=0)) / 2).tolist())
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.location = centre + Vector((0.55, -0.75, 0.3)).normalized() * distance
    camera.rotation_euler = (centre - camera.location).to_track_quat("-Z", "Y").to_euler()
    scene.collection.objects.link(camera)
    scene.camera = camera
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy = 3.0
    sun.rotation_euler = (math.radians(45), 0.0, math.radians(-30))
    scene.collection.objects.link(sun)
    scene.world = bpy.data.worlds.new("World")
    scene.world.use_nodes = True
    scene.world.node_tree.nodes["Background"].inputs["Color"].default_value = (BACKGROUND,) * 3 + (1.0,)
    # The mesh's outline (alpha) is where brightness is measured.
    helpers.measured_render(scene, PANEL, film_transparent=True)
    scene.cycles.samples = 64
    scene.eevee.taa_render_samples = 16


def render(path):
    """(PANEL, PANEL, 4) float RGBA, bottom row first."""
    scene = bpy.context.scene
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(path)
    pixels = np.array(image.pixels[:], np.float64).reshape(PANEL, PANEL, 4)
    bpy.data.images.remove(image)
    return pixels


def save_strip(panels, path):
    """The renders side by side over the world's grey, as an 8-bit sRGB PNG."""
    strip = np.concatenate(panels, axis=1)
    alpha = strip[..., 3:4]
    rgb = np.clip(strip[..., :3] + (1.0 - alpha) * BACKGROUND, 0.0, 1.0)
    encoded = np.where(rgb <= 0.0031308, rgb * 12.92, 1.055 * rgb ** (1 / 2.4) - 0.055)
    image = bpy.data.images.new("strip", strip.shape[1], strip.shape[0])
    image.pixels.foreach_set(
        np.concatenate([encoded, np.ones_like(encoded[..., :1])], axis=-1).astype(np.float32).ravel()
    )
    image.filepath_raw, image.file_format = path, "PNG"
    image.save()
    bpy.data.images.remove(image)
    print("wrote", path)


def compare(name, pixels, mesh, mask):
    """Mean brightness against the mesh's, and the chromaticity difference."""
    volume_rgb, mesh_rgb = pixels[..., :3][mask].mean(axis=0), mesh[..., :3][mask].mean(axis=0)
    chroma = np.abs(volume_rgb / volume_rgb.sum() - mesh_rgb / mesh_rgb.sum()).max()
    print(f"| {name} | {volume_rgb.mean():.3f} | {volume_rgb.mean() / mesh_rgb.mean():.2f} | {chroma:.3f} |")


def colour_images(helpers, out, work):
    scene = bpy.context.scene
    source = spot(helpers)
    helpers.select_only(source)
    bpy.ops.object.hyvox_voxelize(resolution=128, method="cpu", output_dir=work)  # the defaults: Solid, Color
    volume = next(o for o in bpy.data.objects if o.type == "VOLUME")
    stage(helpers, source)
    kept = volume.data.materials[0]

    def show(mesh_shown):
        source.hide_render, volume.hide_render = not mesh_shown, mesh_shown

    print(f"\nBlender {bpy.app.version_string}: Spot at 128, Solid, Color")
    print("| render | mean brightness | against the mesh | chromaticity difference |")
    print("|---|---:|---:|---:|")
    if bpy.app.version < (4, 2, 0):
        eevee_images(source, volume, show, out, work)
        return
    scene.render.engine = "CYCLES"
    show(True)
    mesh = render(os.path.join(work, "mesh.exr"))
    mask = mesh[..., 3] > 0.5  # Spot's outline
    panels = [mesh]
    from test_looks_density import legacy_material  # the material earlier versions made

    volume.data.materials[0] = legacy_material(volume["hyvox_voxel_size"], has_color=True)
    show(False)
    panels.append(render(os.path.join(work, "earlier.exr")))
    compare("Cycles, earlier material", panels[-1], mesh, mask)
    volume.data.materials[0] = kept
    panels.append(render(os.path.join(work, "after.exr")))
    compare("Cycles, defaults", panels[-1], mesh, mask)
    for bounces in (4, 8, 16):
        scene.cycles.volume_bounces = bounces
        scene.cycles.max_bounces = max(scene.cycles.max_bounces, bounces)
        pixels = render(os.path.join(work, f"bounces{bounces}.exr"))
        compare(f"Cycles, Volume bounces {bounces}", pixels, mesh, mask)
    panels.append(pixels)
    save_strip(panels, os.path.join(out, "color_cycles.png"))
    print("\n| Spot's vertices: Sample Grid / the voxel's colour | 5 % | 50 % | 95 % |")
    print("|---|---:|---:|---:|")
    sample_grid_at_the_surface(source, volume)


def sample_grid_at_the_surface(source, volume):
    """Geometry Nodes' Sample Grid (Trilinear) of `color` at Spot's vertices, as it is and
    divided by Sample Grid of `density`, against the colour the `color` grid holds at the
    nearest voxel (Nearest Neighbor): percentiles of the ratio (1 is right)."""
    tree = bpy.data.node_groups.new("Sample colour", "GeometryNodeTree")
    tree.interface.new_socket("Geometry", in_out="INPUT", socket_type="NodeSocketGeometry")
    tree.interface.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    nodes, links = tree.nodes, tree.links
    info = nodes.new("GeometryNodeObjectInfo")
    info.inputs["Object"].default_value = volume
    info.transform_space = "RELATIVE"
    geometry = nodes.new("NodeGroupInput").outputs[0]
    for grid, kind in (("color", "VECTOR"), ("density", "FLOAT")):
        for interpolation in ("Trilinear", "Nearest Neighbor"):
            get = nodes.new("GeometryNodeGetNamedGrid")
            get.data_type, get.inputs["Name"].default_value = kind, grid
            links.new(info.outputs["Geometry"], get.inputs["Volume"])
            sample = nodes.new("GeometryNodeSampleGrid")
            sample.data_type = kind
            sample.inputs["Interpolation"].default_value = interpolation
            links.new(get.outputs["Grid"], sample.inputs["Grid"])
            store = nodes.new("GeometryNodeStoreNamedAttribute")
            store.data_type = "FLOAT_VECTOR" if kind == "VECTOR" else "FLOAT"
            store.inputs["Name"].default_value = f"{grid} {interpolation}"
            links.new(geometry, store.inputs["Geometry"])
            links.new(sample.outputs["Value"], store.inputs["Value"])
            geometry = store.outputs["Geometry"]
    links.new(geometry, nodes.new("NodeGroupOutput").inputs[0])
    modifier = source.modifiers.new("Sample colour", "NODES")
    modifier.node_group = tree
    mesh = source.evaluated_get(bpy.context.evaluated_depsgraph_get()).data

    def read(name, width):
        values = np.empty(len(mesh.vertices) * width, np.float32)
        mesh.attributes[name].data.foreach_get("vector" if width == 3 else "value", values)
        return values.reshape(-1, width) if width == 3 else values

    trilinear, nearest = read("color Trilinear", 3), read("color Nearest Neighbor", 3)
    density = read("density Trilinear", 1)
    held = nearest.sum(axis=1) > 0
    for name, values in (
        ("Sample Grid of color", trilinear),
        ("divided by Sample Grid of density", trilinear / np.maximum(density, 1e-6)[:, None]),
    ):
        ratio = values[held].sum(axis=1) / nearest[held].sum(axis=1)
        print(f"| {name} | " + " | ".join(f"{q:.3f}" for q in np.percentile(ratio, [5, 50, 95])) + " |")
    source.modifiers.remove(modifier)


def eevee_images(source, volume, show, out, work):
    """EEVEE 3.x (4.2-5.0 draws no volume light on this machine's software GL)."""
    scene = bpy.context.scene
    scene.render.engine = "BLENDER_EEVEE"
    show(True)
    mesh = render(os.path.join(work, "eevee_mesh.exr"))
    mask = mesh[..., 3] > 0.5  # Spot's outline
    panels = [mesh]
    show(False)
    panels.append(render(os.path.join(work, "eevee_defaults.exr")))
    compare("EEVEE, defaults", panels[-1], mesh, mask)
    eevee = scene.eevee
    eevee.volumetric_tile_size = "2"
    compare("EEVEE, Tile Size 2", render(os.path.join(work, "eevee_tile2.exr")), mesh, mask)
    eevee.volumetric_samples, eevee.volumetric_start, eevee.volumetric_end = 128, 1.0, 6.0
    panels.append(render(os.path.join(work, "eevee_fine.exr")))
    compare("EEVEE, Tile Size 2, Samples 128, Start 1 m, End 6 m", panels[-1], mesh, mask)
    save_strip(panels, os.path.join(out, "color_eevee.png"))


def blocks_image(helpers, out, work):
    helpers.clear_scene()
    bpy.ops.mesh.primitive_uv_sphere_add(radius=1.0, segments=32, ring_count=16)
    source = bpy.context.active_object
    helpers.select_only(source)
    bpy.ops.object.hyvox_voxelize(resolution=16, method="cpu", output_dir=work, output="BLOCKS")
    blocks = bpy.data.objects["Sphere_blocks"]
    source.hide_render = True
    stage(helpers, blocks, distance=4.2)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    faces = len(blocks.data.polygons)
    panels = []
    for smooth in (True, False):
        blocks.data.polygons.foreach_set("use_smooth", np.full(faces, smooth))
        blocks.data.update()
        panels.append(render(os.path.join(work, f"blocks_{'smooth' if smooth else 'flat'}.exr")))
    save_strip(panels, os.path.join(out, "blocks.png"))


def main():
    build, out = arguments()
    os.makedirs(out, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="hyvox-docs-") as work:
        helpers = enable_addon(build)
        helpers.clear_scene()
        colour_images(helpers, out, work)
        if bpy.app.version >= (4, 2, 0):
            blocks_image(helpers, out, work)


if __name__ == "__main__":
    try:
        main()
    except BaseException:
        import traceback

        traceback.print_exc()
        sys.stdout.flush()
        os._exit(1)
    sys.stdout.flush()
    os._exit(0)
