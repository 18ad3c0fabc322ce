# SPDX-License-Identifier: GPL-3.0-or-later
"""The README's main job: build a scene from the Stanford bunny and Suzanne in headless
Blender, voxelize both with the add-on's operator, and save the .blend, the .vdb files and
a Cycles CPU render of each volume beside its mesh; then the textured Spot cow voxelized
with its colour (the add-on's Colour option: a `color` grid the volume's material shows),
rendered beside its mesh into render_colour.png, and Crytek Sponza with its vertex colours
into render_colour_sponza.png; then a twisting Suzanne made live and rendered for three
frames with no bake step (Live voxelizes each frame as it renders), the frames side by
side in render_live.png; print the stats.

    blender -b --factory-startup --python demo/run_demo.py -- --build B --output out/demo

Options after `--`: --build DIR (the CMake build with addon/ in it, default: build),
--output DIR (default: out/demo), --resolution N (default 128), --method M (default auto),
--samples N (default 16)."""

import argparse
import os
import sys
import time

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
MESHES = os.path.join(HERE, "..", "..", "shared", "data", "meshes")


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else []
    parser = argparse.ArgumentParser(prog="blender -b --python demo/run_demo.py --")
    parser.add_argument("--build", default="build", help="CMake build folder holding addon/")
    parser.add_argument("--output", default=os.path.join("out", "demo"))
    parser.add_argument("--resolution", type=int, default=128)
    parser.add_argument("--method", default="auto")
    parser.add_argument("--samples", type=int, default=16)
    parser.add_argument("--meshes", default=os.environ.get("HYVOX_MESH_DIR", MESHES))
    return parser.parse_args(argv)


def enable_addon(build):
    import addon_utils

    sys.path.insert(0, os.path.join(os.path.abspath(build), "addon"))
    if addon_utils.enable("hyvox_blender", default_set=True, handle_error=None) is None:
        raise SystemExit(f"could not enable hyvox_blender from {build}/addon (build it first)")


def mesh_from_arrays(name, vertices, triangles):
    import numpy as np

    mesh = bpy.data.meshes.new(name)
    mesh.vertices.add(len(vertices))
    mesh.vertices.foreach_set("co", np.ascontiguousarray(vertices, np.float32).ravel())
    mesh.loops.add(triangles.size)
    mesh.loops.foreach_set("vertex_index", triangles.astype(np.int32).ravel())
    mesh.polygons.add(len(triangles))
    mesh.polygons.foreach_set("loop_start", np.arange(0, triangles.size, 3, dtype=np.int32))
    mesh.polygons.foreach_set("loop_total", np.full(len(triangles), 3, np.int32))
    mesh.update()
    mesh.polygons.foreach_set("use_smooth", np.ones(len(triangles), bool))
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def fit(obj, height, x):
    """Scale obj to the given height, standing on z=0 centred at (x, 0), from its
    world-space bounds (it may be rotated)."""
    from mathutils import Vector

    bpy.context.view_layer.update()
    corners = [obj.matrix_world @ Vector(c) for c in obj.bound_box]
    lo = Vector(min(c[i] for c in corners) for i in range(3))
    hi = Vector(max(c[i] for c in corners) for i in range(3))
    scale = height / (hi.z - lo.z)
    obj.scale = tuple(s * scale for s in obj.scale)
    centre = (lo + hi) / 2 - obj.location
    obj.location = (x - centre.x * scale, -centre.y * scale, -(lo.z - obj.location.z) * scale)
    bpy.context.view_layer.update()


def add_camera(name, location, tilt):
    """A 32 mm camera at `location` looking along +y, tilted down from the vertical by `tilt`."""
    camera = bpy.data.objects.new(name, bpy.data.cameras.new(name))
    camera.location = location
    camera.rotation_euler = (tilt, 0.0, 0.0)
    camera.data.lens = 32
    bpy.context.scene.collection.objects.link(camera)
    return camera


def principled_material(name):
    """A material of one Principled BSDF, built here (the default nodes are not always there
    after a render); returns it and its shader node."""
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    output = nodes.new("ShaderNodeOutputMaterial")
    shader = nodes.new("ShaderNodeBsdfPrincipled")
    material.node_tree.links.new(shader.outputs["BSDF"], output.inputs["Surface"])
    return material, shader


def build_scene(args):
    from hyvox_blender.core import backend

    # Start from an empty scene (reloading factory settings would disable the add-on).
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    scene = bpy.context.scene

    vertices, triangles = backend.load_module().read_mesh(os.path.join(args.meshes, "bunny_stanford_69k.ply"))
    bunny = mesh_from_arrays("Bunny", vertices, triangles)
    bunny.rotation_euler = (1.5708, 0, 0)  # the scan is y-up
    bpy.context.view_layer.update()
    fit(bunny, 1.6, 1.3)

    bpy.ops.mesh.primitive_monkey_add(size=2.0)
    suzanne = bpy.context.active_object
    suzanne.name = "Suzanne"
    suzanne.modifiers.new("Subdivision", "SUBSURF").levels = 2
    bpy.ops.object.shade_smooth()
    bpy.context.view_layer.update()
    fit(suzanne, 1.4, -3.9)

    mesh_material = bpy.data.materials.new("Clay")
    mesh_material.use_nodes = True
    mesh_material.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.8, 0.75, 0.7, 1)
    for obj in (bunny, suzanne):
        obj.data.materials.append(mesh_material)

    bpy.ops.mesh.primitive_plane_add(size=40)
    floor = bpy.context.active_object
    floor.name = "Floor"

    scene.camera = add_camera("Camera", (0.0, -10.5, 2.3), 1.44)
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy = 3.0
    sun.rotation_euler = (0.7, 0.2, 0.6)
    scene.collection.objects.link(sun)
    world = bpy.data.worlds.new("Sky")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.55, 0.6, 0.7, 1)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.6
    scene.world = world
    return [suzanne, bunny]


def add_textured_spot(args):
    """Spot with its UVs and a material whose Base Color is its texture (the colour source the
    add-on exports), standing where Suzanne stood."""
    import numpy as np
    from hyvox_blender.core import backend

    vertices, triangles, attrs = backend.load_module().read_mesh(
        os.path.join(args.meshes, "spot_uv.ply"), attributes=True
    )
    spot = mesh_from_arrays("Spot", vertices, triangles)
    uv_layer = spot.data.uv_layers.new(name="UVMap")
    uv_layer.data.foreach_set("uv", np.ascontiguousarray(attrs["uvs"][triangles.astype(np.int64)], np.float32).ravel())
    material, shader = principled_material("SpotTexture")
    image = material.node_tree.nodes.new("ShaderNodeTexImage")
    image.image = bpy.data.images.load(os.path.join(args.meshes, "spot_texture.png"))
    material.node_tree.links.new(image.outputs["Color"], shader.inputs["Base Color"])
    spot.data.materials.append(material)
    spot.rotation_euler = (1.5708, 0, 0)  # y-up like the bunny
    spot.rotation_euler[2] = 2.5  # facing the camera, a little to the side
    bpy.context.view_layer.update()
    fit(spot, 1.5, -1.3)
    return spot


def render_settings(scene, args, path):
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = args.samples
    scene.cycles.use_denoising = False  # Debian's Blender is built without OpenImageDenoise
    scene.cycles.max_bounces = 4
    scene.cycles.volume_bounces = 0
    scene.render.resolution_x, scene.render.resolution_y = 960, 360
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "PNG"
    scene.render.filepath = path


def add_vertex_coloured_sponza(args):
    """Crytek Sponza with its per-vertex colours as the active colour attribute, which its
    material's Base Color reads (the colour source the add-on exports), at the scene's left."""
    import numpy as np
    from hyvox_blender.core import backend

    vertices, triangles, attrs = backend.load_module().read_mesh(
        os.path.join(args.meshes, "sponza_crytek_262k_vcolor.ply.gz"), attributes=True
    )
    sponza = mesh_from_arrays("Sponza", vertices, triangles)
    encoded = attrs["colors"][:, :3].astype(np.float64)  # the file's bytes: sRGB
    linear = np.where(encoded <= 0.04045, encoded / 12.92, ((encoded + 0.055) / 1.055) ** 2.4)
    colours = sponza.data.color_attributes.new("Col", "FLOAT_COLOR", "POINT")
    rgba = np.concatenate([linear, np.ones((len(linear), 1))], axis=1).astype(np.float32)
    colours.data.foreach_set("color", rgba.ravel())
    material, shader = principled_material("SponzaColours")
    attribute = material.node_tree.nodes.new("ShaderNodeAttribute")
    attribute.attribute_name = "Col"
    material.node_tree.links.new(attribute.outputs["Color"], shader.inputs["Base Color"])
    sponza.data.materials.append(material)
    sponza.rotation_euler = (1.5708, 0, 0)  # y-up
    bpy.context.view_layer.update()
    fit(sponza, 1.0, -1.6)
    return sponza


def voxelize_with_colour(obj, args, output, mode):
    """obj alone through the operator with the Colour option; returns its new Volume object."""
    for other in bpy.context.view_layer.objects:
        other.select_set(other is obj)
    bpy.context.view_layer.objects.active = obj
    bpy.ops.object.hyvox_voxelize(
        resolution=args.resolution,
        method=args.method,
        separate=True,
        color=True,
        mode=mode,
        output_dir=os.path.join(output, "vdb"),
    )
    return bpy.data.objects[obj.name + "_voxels"]


LIVE_FRAMES = (1, 2, 3)


def render_live_animation(args, output):
    """A deforming Suzanne (a twist animated over three frames) voxelized by Live, with no
    frame range and no bake: the render voxelizes each frame as it renders it (the source is
    hidden in renders); the frames side by side in render_live.png."""
    import numpy as np

    scene = bpy.context.scene
    bpy.ops.mesh.primitive_monkey_add(size=2.0)
    source = bpy.context.active_object
    source.name = "Twisted"
    source.modifiers.new("Subdivision", "SUBSURF").levels = 2
    twist = source.modifiers.new("Twist", "SIMPLE_DEFORM")
    twist.deform_method, twist.deform_axis = "TWIST", "Z"
    for frame, angle in zip(LIVE_FRAMES, (0.0, 1.6, 3.2)):
        twist.angle = angle
        twist.keyframe_insert("angle", frame=frame)
    bpy.context.view_layer.update()
    fit(source, 1.6, 0.0)
    source.hide_render = True  # only its voxels render
    scene.frame_set(LIVE_FRAMES[0])
    for other in bpy.context.view_layer.objects:
        other.select_set(other is source)
    bpy.context.view_layer.objects.active = source
    bpy.ops.object.hyvox_voxelize(
        resolution=args.resolution, method=args.method, live=True, output_dir=os.path.join(output, "vdb")
    )
    volume = bpy.data.objects[source.name + "_voxels"]
    shader = volume.active_material.node_tree.nodes["Principled Volume"]
    shader.inputs["Color"].default_value = (0.25, 0.55, 0.9, 1)
    shader.inputs["Density"].default_value *= 4.0
    saved = scene.frame_start, scene.frame_end, scene.render.resolution_x, scene.render.filepath, scene.camera
    scene.frame_start, scene.frame_end = LIVE_FRAMES[0], LIVE_FRAMES[-1]
    scene.camera = add_camera("Camera live", (0.0, -5.2, 1.5), 1.42)
    scene.render.resolution_x = 320
    frames = os.path.join(output, "live_frame_")
    scene.render.filepath = frames
    bpy.ops.render.render(animation=True)  # each frame: Live voxelizes it first, synchronously
    images = []
    for frame in LIVE_FRAMES:
        path = f"{frames}{frame:04d}.png"
        image = bpy.data.images.load(path)
        images.append(np.array(image.pixels[:], np.float32).reshape(image.size[1], image.size[0], 4))
        bpy.data.images.remove(image)
        os.remove(path)
    strip = np.concatenate(images, axis=1)
    combined = bpy.data.images.new("render_live", strip.shape[1], strip.shape[0], alpha=True)
    combined.pixels.foreach_set(strip.ravel())
    png = os.path.join(output, "render_live.png")
    combined.filepath_raw, combined.file_format = png, "PNG"
    combined.save()
    bpy.data.images.remove(combined)
    scene.frame_start, scene.frame_end, scene.render.resolution_x, scene.render.filepath, scene.camera = saved
    scene.frame_set(LIVE_FRAMES[0])
    volume.hyvox_live = False  # the .blend keeps frame 1's voxels as a baked result
    source.hide_render = volume.hide_render = True
    return png


def main():
    args = parse_args()
    enable_addon(args.build)
    output = os.path.abspath(args.output)
    os.makedirs(output, exist_ok=True)
    sources = build_scene(args)

    for obj in bpy.context.view_layer.objects:
        obj.select_set(obj in sources)
    bpy.context.view_layer.objects.active = sources[0]
    bpy.ops.object.hyvox_voxelize(
        resolution=args.resolution, method=args.method, separate=True, output_dir=os.path.join(output, "vdb")
    )
    from hyvox_blender.blender import operators

    # Show each volume beside its mesh: move it 2.6 units along +x (on top of the
    # half-voxel correction the add-on put on its transform).
    for source in sources:
        volume = bpy.data.objects[source.name + "_voxels"]
        volume.location.x += 2.6
        shader = volume.active_material.node_tree.nodes["Principled Volume"]
        shader.inputs["Color"].default_value = (0.9, 0.45, 0.15, 1)
        shader.inputs["Density"].default_value *= 4.0

    blend = os.path.join(output, "demo.blend")
    bpy.context.preferences.filepaths.save_version = 0  # saved twice below: no demo.blend1
    bpy.ops.wm.save_as_mainfile(filepath=blend)
    png = os.path.join(output, "render.png")
    render_settings(bpy.context.scene, args, png)
    start = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    render_s = time.perf_counter() - start
    summary = list(operators.last_summary)

    # Colour: Spot's texture into a `color` grid, filled (the add-on's default Mode, Solid:
    # the inside takes its colours from the surface inward); its volume shows it through the
    # add-on's material, with the volume bounces docs/artist.md asks for.
    shown = [bpy.data.objects[name] for name in ("Bunny", "Suzanne", "Bunny_voxels", "Suzanne_voxels")]
    for obj in shown:
        obj.hide_render = True
    spot = add_textured_spot(args)
    volume = voxelize_with_colour(spot, args, output, mode="solid")
    volume.location.x += 2.6
    cycles = bpy.context.scene.cycles
    bounces = cycles.max_bounces, cycles.volume_bounces
    cycles.max_bounces = cycles.volume_bounces = 16
    summary += operators.last_summary
    colour_png = os.path.join(output, "render_colour.png")
    bpy.context.scene.render.filepath = colour_png
    start = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    render_s += time.perf_counter() - start

    # Sponza's vertex colours the same way, as a surface seen from above (its roof is open).
    spot.hide_render = volume.hide_render = True
    sponza = add_vertex_coloured_sponza(args)
    sponza_volume = voxelize_with_colour(sponza, args, output, mode="conservative")
    summary += operators.last_summary
    sponza_volume.location.x += 3.2
    scene = bpy.context.scene
    camera = scene.camera
    scene.camera = add_camera("Camera above", (0.0, -4.2, 4.6), 0.75)
    sponza_png = os.path.join(output, "render_colour_sponza.png")
    scene.render.filepath = sponza_png
    start = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    render_s += time.perf_counter() - start
    scene.camera = camera
    sponza.hide_render = sponza_volume.hide_render = True
    cycles.max_bounces, cycles.volume_bounces = bounces

    # Live: an animated, deforming source rendered for a few frames with no bake step.
    start = time.perf_counter()
    live_png = render_live_animation(args, output)
    live_s = time.perf_counter() - start
    for obj in shown:
        obj.hide_render = False
    # the .blend opens on the first scene's look
    bpy.ops.wm.save_as_mainfile(filepath=blend)

    print("\n=== hyvox demo ===")
    for line in summary:
        print(line)
    print(
        f"render {render_s:.1f} s; Live, frames {LIVE_FRAMES[0]}-{LIVE_FRAMES[-1]} voxelized as they "
        f"rendered: {live_s:.1f} s"
    )
    print("blend :", blend)
    print("render:", png, colour_png, sponza_png, live_png)


if __name__ == "__main__":
    try:
        main()
    except Exception as exc:
        import traceback

        traceback.print_exc()
        print(f"hyvox demo failed: {exc}", file=sys.stderr)
        sys.stdout.flush()
        os._exit(1)
