# SPDX-License-Identifier: GPL-3.0-or-later
"""Live volumes in background mode, where updates are synchronous: when view_layer.update()
or frame_set() returns, the live volume's file holds the voxels of the new state.

The oracle is the module's reference voxelizer on the evaluated mesh, exported here by
Blender's own per-element API (not the add-on's export), on the lattice the volume keeps
(its voxel size, the origin at the whole multiple of it at or below the bounds)."""

import os

import bpy
import numpy as np

import helpers
from helpers import AddonTestCase


def live():
    return helpers.addon("blender.live.driver")


def evaluated_world_mesh(obj):
    """(vertices (N,3) float32 world, triangles (M,3) uint32) of obj as the viewport
    evaluates it, read vertex by vertex and triangle by triangle."""
    evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
    mesh = evaluated.to_mesh()
    try:
        if hasattr(mesh, "calc_loop_triangles"):
            mesh.calc_loop_triangles()
        vertices = np.array([v.co[:] for v in mesh.vertices], np.float32).reshape(-1, 3)
        triangles = np.array([t.vertices[:] for t in mesh.loop_triangles], np.uint32).reshape(-1, 3)
    finally:
        evaluated.to_mesh_clear()
    matrix = np.array(evaluated.matrix_world, np.float32)
    return (vertices @ matrix[:3, :3].T + matrix[:3, 3]).astype(np.float32), triangles


def oracle_voxels(vertices, triangles, voxel_size, mode):
    """World lattice indices of the reference voxelizer's voxels on the fixed lattice."""
    low = vertices[np.unique(triangles)].min(axis=0).astype(np.float64)
    origin = np.floor(low / voxel_size) * voxel_size
    origin -= np.where(origin > low, voxel_size, 0.0)
    grid = helpers.hyvox_module().voxelize(
        vertices, triangles, voxel_size=voxel_size, origin=tuple(origin), method="reference", mode=mode
    )
    offset = np.rint(np.array(grid.origin) / voxel_size).astype(np.int64)
    return {tuple(p) for p in grid.coords().astype(np.int64) + offset}


def file_voxels(path):
    """World lattice indices of a .vdb's voxels (read back with pyopenvdb)."""
    coords, size, zero, _ = helpers.read_vdb(path)
    offset = np.rint((zero - size / 2) / size).astype(np.int64)
    return {tuple(p) for p in coords + offset}


class LiveTestCase(AddonTestCase):
    def make_live(self, obj, mode="conservative", **kw):
        helpers.select_only(obj)
        kw.setdefault("resolution", 24)
        self.assertEqual(self.voxelize(live=True, mode=mode, **kw), {"FINISHED"})
        (volume,) = [o for o in bpy.data.objects if "hyvox_key" in o]
        self.assertTrue(volume.hyvox_live)
        return volume

    def shown_file(self, volume):
        return bpy.path.abspath(volume.data.filepath)

    def assert_holds_the_state(self, volume, source, mode="conservative"):
        path = self.shown_file(volume)
        expected = oracle_voxels(*evaluated_world_mesh(source), float(volume["hyvox_voxel_size"]), mode)
        got = file_voxels(path)
        self.assertTrue(expected, "the oracle has voxels")
        self.assertEqual(len(got ^ expected), 0, f"{len(got)} voxels in {path}, the oracle {len(expected)}")
        # ... and the evaluated volume reads that file now (Blender's second pass after the handler).
        evaluated = volume.evaluated_get(bpy.context.evaluated_depsgraph_get()).data
        self.assertEqual(bpy.path.abspath(evaluated.filepath), path)
        self.assertTrue(evaluated.grids.load())
        self.assertIn("density", [g.name for g in evaluated.grids])

    def runs(self, volume):
        return live()._Live.runs_started.get(volume["hyvox_live_id"], 0)

    def stray_files(self, volume):
        """Files in the output folder that neither a volume shows nor the Live cache holds."""
        kept = {os.path.realpath(p) for p in live().cache().files()}
        kept |= {os.path.realpath(bpy.path.abspath(v.filepath)) for v in bpy.data.volumes if v.filepath}
        return sorted(n for n in os.listdir(self.out) if os.path.realpath(os.path.join(self.out, n)) not in kept)


class LiveEditsTest(LiveTestCase):
    def test_edit_modifier_and_transform_are_followed(self):
        for mode in ("conservative", "solid"):
            with self.subTest(mode=mode):
                helpers.clear_scene()
                bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=2, radius=1.0)
                sphere = bpy.context.active_object
                volume = self.make_live(sphere, mode)
                first = self.shown_file(volume)
                self.assert_holds_the_state(volume, sphere, mode)
                # A mesh edit (the evaluated mesh changes, the object does not move).
                sphere.data.vertices[0].co.z += 0.6
                sphere.data.update()
                bpy.context.view_layer.update()
                self.assertNotEqual(self.shown_file(volume), first)
                self.assert_holds_the_state(volume, sphere, mode)
                # A modifier's input.
                displace = sphere.modifiers.new("Grow", "DISPLACE")
                displace.strength = 0.3
                bpy.context.view_layer.update()
                self.assert_holds_the_state(volume, sphere, mode)
                displace.strength = -0.2
                bpy.context.view_layer.update()
                self.assert_holds_the_state(volume, sphere, mode)
                # A transform: the voxels are in world space, the volume is not parented.
                self.assertIsNone(volume.parent)
                sphere.location = (0.37, -0.21, 0.5)
                sphere.rotation_euler = (0.3, 0.0, 0.7)
                bpy.context.view_layer.update()
                self.assert_holds_the_state(volume, sphere, mode)
                # Nothing left half-written.
                self.assertFalse([n for n in os.listdir(self.out) if n.endswith(".partial")])

    def test_edit_mode_changes_are_followed(self):
        import bmesh

        bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=2, radius=1.0)
        sphere = bpy.context.active_object
        volume = self.make_live(sphere)
        bpy.context.view_layer.objects.active = sphere
        bpy.ops.object.mode_set(mode="EDIT")
        try:
            edit = bmesh.from_edit_mesh(sphere.data)
            top = max(edit.verts, key=lambda v: v.co.z)
            top.co.z += 0.7  # the top from 1 to 1.7
            bmesh.update_edit_mesh(sphere.data)
            bpy.context.view_layer.update()
            self.assert_holds_the_state(volume, sphere)  # the oracle reads the edit-mode evaluation too
            self.assertGreater(
                max(p[2] for p in file_voxels(self.shown_file(volume))) * volume["hyvox_voxel_size"], 1.5
            )
        finally:
            bpy.ops.object.mode_set(mode="OBJECT")

    def test_a_burst_of_edits_gives_one_run_with_the_last_state(self):
        bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=2, radius=1.0)
        sphere = bpy.context.active_object
        volume = self.make_live(sphere)
        before = self.runs(volume)
        for edit in range(10):
            sphere.data.vertices[edit].co *= 1.3
            sphere.data.update()
        bpy.context.view_layer.update()
        self.assertLessEqual(self.runs(volume) - before, 2)
        self.assertGreaterEqual(self.runs(volume) - before, 1)
        self.assert_holds_the_state(volume, sphere)

    def test_an_update_that_changes_no_source_runs_nothing(self):
        sphere = helpers.cube(size=1.0)
        other = helpers.cube("Other", size=1.0, location=(3, 0, 0))
        volume = self.make_live(sphere)
        shown = self.shown_file(volume)
        before = self.runs(volume)
        other.location.x = 4.0  # not a source
        volume.location.z += 1.0  # the volume itself
        bpy.context.view_layer.update()
        self.assertEqual(self.runs(volume), before)
        self.assertEqual(self.shown_file(volume), shown)

    def test_a_state_seen_before_comes_from_the_cache(self):
        sphere = helpers.cube(size=1.0)
        volume = self.make_live(sphere)
        first = self.shown_file(volume)
        sphere.location.x = 0.5
        bpy.context.view_layer.update()
        moved = self.shown_file(volume)
        sphere.location.x = 0.0
        bpy.context.view_layer.update()
        self.assertEqual(self.shown_file(volume), first)  # the first file again, not a new one
        sphere.location.x = 0.5
        bpy.context.view_layer.update()
        self.assertEqual(self.shown_file(volume), moved)
        self.assertEqual(len(os.listdir(self.out)), 2)

    def test_switching_off_keeps_the_last_voxels(self):
        sphere = helpers.cube(size=1.0)
        volume = self.make_live(sphere)
        sphere.location.x = 0.5
        bpy.context.view_layer.update()
        last = self.shown_file(volume)
        volume.hyvox_live = False
        sphere.location.x = 1.5
        bpy.context.view_layer.update()
        self.assertEqual(self.shown_file(volume), last)
        self.assertEqual(os.listdir(self.out), [os.path.basename(last)])  # its other states' files went
        volume.hyvox_live = True  # back on: the current state at once
        self.assert_holds_the_state(volume, sphere)

    def test_a_result_made_without_live_can_be_switched_on(self):
        cube = helpers.cube(size=1.0)
        helpers.select_only(cube)
        self.assertEqual(self.voxelize(resolution=16), {"FINISHED"})
        (volume,) = self.volumes()
        self.assertIs(volume.parent, cube)  # a plain run parents the volume
        cube.location.x = 0.9
        bpy.context.view_layer.update()
        volume.hyvox_live = True  # the current state at once, unparented: no double move
        self.assertIsNone(volume.parent)
        self.assert_holds_the_state(volume, cube)
        self.assertEqual(len([m for m in volume.modifiers if m.name.startswith("hyvox Live Source")]), 1)

    def test_the_scene_is_followed_only_while_a_live_volume_exists(self):
        """Blender may call these handlers on its render thread, where Python can crash it:
        with no live volume they are not in Blender's lists at all."""
        following = live().FOLLOWING

        def registered():
            return [name for name, handler in following if handler in getattr(bpy.app.handlers, name)]

        live().follow_live_volumes()
        self.assertEqual(registered(), [], "no live volume in the scene yet")
        cube = helpers.cube(size=1.0)
        volume = self.make_live(cube)
        self.assertEqual(registered(), [name for name, _ in following])
        volume.hyvox_live = False
        self.assertEqual(registered(), [])
        volume.hyvox_live = True
        self.assertEqual(registered(), [name for name, _ in following])
        cube.location.x = 0.4  # and they still follow the edits
        bpy.context.view_layer.update()
        self.assert_holds_the_state(volume, cube)

    def test_a_frame_range_is_refused_with_live(self):
        helpers.select_only(helpers.cube())
        with self.assertRaises(RuntimeError) as caught:
            self.voxelize(live=True, resolution=8, frame_start=1, frame_end=3)
        self.assertIn("frame range", str(caught.exception))


class LiveErrorsTest(LiveTestCase):
    def test_an_empty_mesh_keeps_the_last_voxels_and_says_why(self):
        cube = helpers.cube(size=1.0)
        volume = self.make_live(cube)
        shown = self.shown_file(volume)
        vertices = [v.co.copy() for v in cube.data.vertices]
        cube.data.clear_geometry()
        bpy.context.view_layer.update()
        self.assertEqual(self.shown_file(volume), shown)
        self.assertTrue(os.path.exists(shown))
        self.assertIn("no faces", live().status_line(volume))
        # Faces again: Live goes on, the error is gone.
        cube.data.from_pydata(
            [tuple(v) for v in vertices],
            [],
            [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)],
        )
        cube.data.update()
        bpy.context.view_layer.update()
        self.assert_holds_the_state(volume, cube)
        self.assertTrue(live().status_line(volume).startswith("Up to date"))

    def test_a_nan_keeps_the_last_voxels_and_says_why(self):
        cube = helpers.cube(size=1.0)
        volume = self.make_live(cube)
        shown = self.shown_file(volume)
        cube.data.vertices[2].co.x = float("nan")
        cube.data.update()
        bpy.context.view_layer.update()
        self.assertEqual(self.shown_file(volume), shown)
        self.assertIn("not a number or infinite", live().status_line(volume))
        self.assertEqual(self.stray_files(volume), [])

    def test_a_grid_over_the_memory_budget_keeps_the_last_voxels(self):
        cube = helpers.cube(size=1.0)
        volume = self.make_live(cube, mode="solid", resolution=64)
        shown = self.shown_file(volume)
        prefs = helpers.addon_preferences()
        prefs.memory_budget_mib = 16
        try:
            cube.scale = (60.0, 60.0, 60.0)  # the voxel size is kept: 3840 voxels a side, solid
            bpy.context.view_layer.update()
        finally:
            prefs.property_unset("memory_budget_mib")
        self.assertEqual(self.shown_file(volume), shown)
        self.assertIn("memory", live().status_line(volume).lower())
        self.assertEqual(self.stray_files(volume), [])

    def test_deleting_the_source_leaves_no_error_and_no_stray_file(self):
        cube = helpers.cube(size=1.0)
        volume = self.make_live(cube)
        cube.location.x = 0.4
        bpy.context.view_layer.update()
        shown = self.shown_file(volume)
        bpy.data.objects.remove(cube, do_unlink=True)
        bpy.context.view_layer.update()
        self.assertEqual(self.shown_file(volume), shown)
        self.assertTrue(live().status_line(volume).startswith("Waiting"), live().status_line(volume))
        self.assertEqual(self.stray_files(volume), [])

    def test_a_renamed_source_is_followed(self):
        cube = helpers.cube(size=1.0)
        volume = self.make_live(cube)
        cube.name = "Renamed"
        cube.location.x = 0.7
        bpy.context.view_layer.update()
        self.assert_holds_the_state(volume, cube)
        self.assertEqual(volume["hyvox_key"], "Renamed")

    def test_a_hidden_source_is_still_followed(self):
        cube = helpers.cube(size=1.0)
        volume = self.make_live(cube)
        cube.hide_set(True)
        cube.location.x = 0.7
        bpy.context.view_layer.update()
        self.assert_holds_the_state(volume, cube)


class LiveColourTest(LiveTestCase):
    def test_a_texture_is_read_once_and_again_when_the_image_changes(self):
        colour_export = helpers.addon("blender.export.colour")
        bpy.ops.mesh.primitive_cube_add(size=1.0)  # with UVs
        cube = bpy.context.active_object
        image = bpy.data.images.new("Paint", 4, 4)
        image.pixels.foreach_set(np.tile(np.float32([0.9, 0.1, 0.1, 1.0]), 16))
        material = bpy.data.materials.new("Painted")
        material.use_nodes = True
        texture = material.node_tree.nodes.new("ShaderNodeTexImage")
        texture.image = image
        material.node_tree.links.new(texture.outputs["Color"], material.node_tree.nodes["Principled BSDF"].inputs[0])
        cube.data.materials.append(material)
        reads = []
        real = colour_export._image_pixels
        colour_export._image_pixels = lambda img: reads.append(img.name) or real(img)
        try:
            volume = self.make_live(cube, color=True, resolution=8)
            for x in (0.2, 0.4, 0.6):  # three edits: the pixels are read by the first only
                cube.location.x = x
                bpy.context.view_layer.update()
            self.assertEqual(len(reads) - 1, 1, reads)  # the operator's own export, then Live's first
            before = self.shown_file(volume)
            image.pixels.foreach_set(np.tile(np.float32([0.1, 0.1, 0.9, 1.0]), 16))
            image.update_tag()  # Blender reports the image changed
            bpy.context.view_layer.update()
            self.assertEqual(len(reads) - 1, 2, reads)
            self.assertNotEqual(self.shown_file(volume), before)  # new colours, new voxels' file
        finally:
            colour_export._image_pixels = real


class LiveOutputsTest(LiveTestCase):
    def test_blocks_and_vox_follow(self):
        bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=2, radius=1.0)
        sphere = bpy.context.active_object
        helpers.select_only(sphere)
        self.assertEqual(self.voxelize(live=True, resolution=16, output="BLOCKS", export_vox=True), {"FINISHED"})
        blocks = bpy.data.objects["Icosphere_blocks"]
        mesh_name = blocks.data.name
        sphere.scale = (1.5, 1.0, 1.0)
        bpy.context.view_layer.update()
        self.assertIs(bpy.data.objects.get("Icosphere_blocks"), blocks)  # updated in place
        self.assertEqual(blocks.data.name, mesh_name)
        from test_blocks_output import dense_exposed_faces, vox_voxel_count

        files = [bpy.path.abspath(p) for p in blocks["hyvox_live_files"]]
        (vdb,) = [p for p in files if p.endswith(".vdb")]
        (vox,) = [p for p in files if p.endswith(".vox")]
        ijk = np.array(sorted(file_voxels(vdb)))
        expected = oracle_voxels(*evaluated_world_mesh(sphere), float(blocks["hyvox_voxel_size"]), "conservative")
        self.assertEqual(set(map(tuple, ijk)), expected)
        self.assertEqual(len(blocks.data.polygons), dense_exposed_faces(ijk))
        self.assertEqual(vox_voxel_count(vox), len(ijk))
        co = np.empty(len(blocks.data.vertices) * 3, np.float32)
        blocks.data.vertices.foreach_get("co", co)
        size = float(blocks["hyvox_voxel_size"])
        np.testing.assert_allclose(co.reshape(-1, 3).max(axis=0), (ijk.max(axis=0) + 1) * size, atol=1e-4)


def render_setup(scene, out):
    """A tiny deterministic Cycles render: orthographic camera down -z, white world."""
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.data.type = "ORTHO"
    camera.data.ortho_scale = 5.0
    camera.location = (0.5, 0, 10)
    scene.collection.objects.link(camera)
    scene.camera = camera
    world = bpy.data.worlds.new("White")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (1, 1, 1, 1)
    scene.world = world
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 16
    scene.cycles.seed = 3
    scene.cycles.use_denoising = False
    scene.cycles.max_bounces = 0
    if hasattr(scene.cycles, "volume_biased"):  # 5.0: ray marching; its unbiased default takes ~12 s a frame here
        scene.cycles.volume_biased = True
    scene.render.resolution_x = scene.render.resolution_y = 32
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.threads_mode = "FIXED"
    scene.render.threads = 2
    scene.render.filepath = os.path.join(out, "frame_")


def read_frames(out, frames):
    images = []
    for frame in frames:
        image = bpy.data.images.load(os.path.join(out, f"frame_{frame:04d}.exr"))
        images.append(np.array(image.pixels[:], np.float64).reshape(image.size[1], image.size[0], 4)[..., :3])
        bpy.data.images.remove(image)
    return images


class LiveRenderTest(LiveTestCase):
    def test_render_animation_gives_each_frame_the_operators_voxels(self):
        """Render Animation (as `blender -b -a`) of an animated source with a modifier that
        renders differently from the viewport: each frame renders with the voxels the
        operator (a frame range, evaluated at render settings) gives at that frame."""
        scene = bpy.context.scene
        bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=1, radius=0.8)
        source = bpy.context.active_object
        subsurf = source.modifiers.new("Smooth", "SUBSURF")
        subsurf.levels, subsurf.render_levels = 0, 2
        for frame, x in ((1, 0.0), (2, 0.45), (3, 1.1)):
            source.location.x = x
            source.keyframe_insert("location", frame=frame)
        scene.frame_start, scene.frame_end = 1, 3
        scene.frame_set(1)
        render_dir = os.path.join(self.out, "renders")
        render_setup(scene, render_dir)
        # The oracle: the operator's own volume sequence of frames 1-3.
        helpers.select_only(source)
        self.assertEqual(self.voxelize(voxel_size=0.1, mode="solid", frame_start=1, frame_end=3), {"FINISHED"})
        (sequence,) = self.volumes()
        expected = [file_voxels(os.path.join(self.out, n)) for n in sorted(os.listdir(self.out)) if n.endswith(".vdb")]
        self.assertEqual(len(expected), 3)
        sequence.name = "Sequence"
        sequence["hyvox_key"] = "not a result any more"  # the live run must not replace it
        sequence.hide_render = True
        source.hide_render = True
        scene.frame_set(1)
        helpers.select_only(source)
        self.assertEqual(self.voxelize(voxel_size=0.1, mode="solid", live=True), {"FINISHED"})
        volume = bpy.data.objects["Icosphere_voxels"]
        rendered_files = []

        def record(scene_, *_):
            rendered_files.append(bpy.path.abspath(volume.data.filepath))

        bpy.app.handlers.render_post.append(record)
        try:
            bpy.ops.render.render(animation=True)
        finally:
            bpy.app.handlers.render_post.remove(record)
        self.assertEqual(len(rendered_files), 3)
        for frame, (path, voxels) in enumerate(zip(rendered_files, expected), start=1):
            self.assertEqual(len(file_voxels(path) ^ voxels), 0, f"frame {frame}: {path}")
        live_images = read_frames(render_dir, (1, 2, 3))
        # The same frames rendered from the operator's sequence look the same.
        volume.hide_render, sequence.hide_render = True, False
        bpy.ops.render.render(animation=True)
        sequence_images = read_frames(render_dir, (1, 2, 3))
        # Each live frame looks like the operator's frame of the same number, more than like
        # any other (the renders are noisy: Cycles samples volumes at random).
        distance = np.array([[np.abs(a - b).mean() for b in sequence_images] for a in live_images])
        print("mean pixel difference, live frames (rows) against the operator's (columns):\n", distance)
        self.assertEqual(list(distance.argmin(axis=1)), [0, 1, 2])
