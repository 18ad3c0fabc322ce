# SPDX-License-Identifier: GPL-3.0-or-later
"""Shared pieces of the headless add-on tests: enabling the add-on from a build, scene
set-up, and reading .vdb files back with pyopenvdb."""

import importlib
import os
import subprocess
import sys
import tempfile
import unittest

import bpy
import numpy as np

MESH_DIR = os.environ.get(
    "HYVOX_MESH_DIR", os.path.join(os.path.dirname(__file__), "..", "..", "..", "shared", "data", "meshes")
)


# The add-on's module name and the folders its files and its hyvox module must come from:
# the legacy add-on from B/addon (Debian's Blender, run_tests.py), or the extension
# installed from B/hyvox_blender-*.zip (Blender 4.2+, run_bpy_tests.py sets these).
ADDON_PACKAGE = "hyvox_blender"
ADDON_DIR = ""
MODULE_DIR = ""


def enable_addon(build_dir):
    global ADDON_DIR, MODULE_DIR
    import addon_utils

    addon_path = os.path.join(build_dir, "addon")
    if addon_path not in sys.path:
        sys.path.insert(0, addon_path)
    module = addon_utils.enable(ADDON_PACKAGE, default_set=True, handle_error=None)
    if module is None:
        raise RuntimeError(f"could not enable hyvox_blender from {addon_path}")
    ADDON_DIR = os.path.join(addon_path, "hyvox_blender")
    MODULE_DIR = os.path.join(ADDON_DIR, "hyvox")  # the build copies the module inside
    return module


def run_blender(*args, env=None, timeout=120):
    """`blender -b --factory-startup -noaudio ARGS...`, a child Blender, its output captured
    as text: what a test cannot see in its own Blender (a .blend opened fresh, a headless
    script's exit code) it sees in one started the same way as every other test's."""
    return subprocess.run(
        [bpy.app.binary_path, "-b", "--factory-startup", "-noaudio", *args],
        capture_output=True,
        text=True,
        timeout=timeout,
        env=env,
    )


def run_cli_script(blend, *args, blender_args=(), timeout=120):
    """The add-on's headless entry point, cli_blender.py, on `blend` in a child Blender
    (run_blender): `args` go to the script, `blender_args` to Blender after the script
    (-a renders the animation)."""
    import hyvox_blender

    script = os.path.join(os.path.dirname(hyvox_blender.__file__), "cli_blender.py")
    return run_blender(blend, "--python", script, *blender_args, "--", *args, timeout=timeout)


def addon(submodule=""):
    """The enabled add-on's package, or one of its submodules ("core.backend")."""
    return importlib.import_module(ADDON_PACKAGE + ("." + submodule if submodule else ""))


def addon_preferences():
    return bpy.context.preferences.addons[ADDON_PACKAGE].preferences


def hyvox_module():
    return addon("core.backend").load_module()


def clear_scene():
    """An empty scene without reloading files (which would reset add-on state)."""
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for coll in (
        bpy.data.meshes,
        bpy.data.volumes,
        bpy.data.materials,
        bpy.data.curves,
        bpy.data.cameras,
        bpy.data.lights,
    ):
        for block in list(coll):
            coll.remove(block)
    scene = bpy.context.scene
    scene.frame_set(1)
    for prop in (
        "resolution",
        "voxel_size",
        "method",
        "mode",
        "inside",
        "separate",
        "output_dir",
        "use_frame_range",
        "size_mode",
        "color",
    ):
        scene.hyvox.property_unset(prop)


def mesh_object(name, vertices, faces, location=(0, 0, 0)):
    mesh = bpy.data.meshes.new(name)
    mesh.vertices.add(len(vertices))
    mesh.vertices.foreach_set("co", np.asarray(vertices, np.float32).ravel())
    faces = np.asarray(faces, np.int32).reshape(len(faces), -1 if len(faces) else 3)
    mesh.loops.add(faces.size)
    mesh.loops.foreach_set("vertex_index", faces.ravel())
    mesh.polygons.add(len(faces))
    mesh.polygons.foreach_set("loop_start", np.arange(0, faces.size, faces.shape[1], dtype=np.int32))
    mesh.polygons.foreach_set("loop_total", np.full(len(faces), faces.shape[1], np.int32))
    mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    obj.location = location
    bpy.context.scene.collection.objects.link(obj)
    return obj


def bunny_arrays():
    """(vertices, triangles) of the Stanford bunny as in the file (hyvox.read_mesh)."""
    return hyvox_module().read_mesh(os.path.join(MESH_DIR, "bunny_stanford_69k.ply"))


def bunny():
    return mesh_object("Bunny", *bunny_arrays())


def cube(name="Cube", size=2.0, location=(0, 0, 0)):
    h = size / 2
    v = [(-h, -h, -h), (h, -h, -h), (h, h, -h), (-h, h, -h), (-h, -h, h), (h, -h, h), (h, h, h), (-h, h, h)]
    f = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    return mesh_object(name, v, f, location)


def select_only(*objects):
    for obj in bpy.context.view_layer.objects:
        obj.select_set(False)
    for obj in objects:
        obj.select_set(True)
    bpy.context.view_layer.objects.active = objects[0] if objects else None


def read_vdb(path, grid_name="density"):
    """(ijk (K,3) int64, voxel size, index->world translation, grid) of a .vdb's active
    voxels (vdb_dump.read). Where this Python has no pyopenvdb (the bpy module's venv),
    Debian's Python reads the file in a child process and grid is None."""
    import vdb_dump

    try:
        import pyopenvdb  # noqa: F401
    except ImportError:
        python = os.environ.get("HYVOX_VDB_PYTHON", "/usr/bin/python3")
        with tempfile.TemporaryDirectory(prefix="hyvox-vdb-") as tmp:
            out = os.path.join(tmp, "grid.npz")
            subprocess.run([python, vdb_dump.__file__, path, grid_name, out], check=True, timeout=120)
            with np.load(out) as data:
                return data["coords"], data["size"], data["zero"], None
    return vdb_dump.read(path, grid_name)


def vdb_world_centres(path):
    coords, size, zero, _ = read_vdb(path)
    return zero + coords * size


def sorted_rows(a, decimals=6):
    a = np.round(np.asarray(a, dtype=np.float64), decimals)
    return a[np.lexsort(a.T[::-1])]


def run_suite(names):
    """Run the unittest cases `names` (test_x or test_x.Case.test_y) and return the exit
    code. wasSuccessful() is also true when nothing ran or everything was skipped: CTest would
    report those as passes, so they fail here (skips are not allowed)."""
    suite = unittest.TestSuite(unittest.defaultTestLoader.loadTestsFromName(name) for name in names)
    result = unittest.TextTestRunner(stream=sys.stdout, verbosity=2).run(suite)
    if result.testsRun == 0 or result.skipped:
        print(f"FAILED: {result.testsRun} tests ran, {len(result.skipped)} skipped (skips are not allowed)")
        return 1
    return 0 if result.wasSuccessful() else 1


def measured_render(scene, pixels, film_transparent=False):
    """The render settings the render tests measure by: a square image `pixels` wide, 32-bit
    float EXR of the scene's linear values (view transform Standard), Cycles on the CPU without
    denoising (Debian's Blender has no OpenImageDenoise), two threads."""
    scene.render.resolution_x = scene.render.resolution_y = pixels
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = film_transparent
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.view_settings.view_transform = "Standard"
    scene.cycles.device = "CPU"
    scene.cycles.use_denoising = False
    scene.render.threads_mode = "FIXED"
    scene.render.threads = 2


def render_pixels(path):
    """Render the scene's camera to `path` (its format as set in the scene) and read it back:
    (height, width, 4) float64 RGBA, bottom row first as Blender stores it."""
    scene = bpy.context.scene
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(path)
    width, height = image.size
    pixels = np.array(image.pixels[:], dtype=np.float64).reshape(height, width, 4)
    bpy.data.images.remove(image)
    return pixels


class AddonTestCase(unittest.TestCase):
    """Each test starts from an empty scene with its own output folder."""

    def setUp(self):
        clear_scene()
        self._tmp = tempfile.TemporaryDirectory(prefix="hyvox-test-")
        self.out = self._tmp.name

    def tearDown(self):
        self._tmp.cleanup()

    def voxelize(self, **kw):
        kw.setdefault("output_dir", self.out)
        kw.setdefault("method", "cpu")
        # The tests written for surfaces ask for one; Solid (the default) is tested apart.
        kw.setdefault("mode", "conservative")
        return bpy.ops.object.hyvox_voxelize(**kw)

    def volumes(self):
        return sorted((o for o in bpy.data.objects if o.type == "VOLUME"), key=lambda o: o.name)

    def scene_state(self):
        """What 'scene unchanged' compares."""
        return (
            sorted(o.name for o in bpy.data.objects),
            len(bpy.data.volumes),
            len(bpy.data.materials),
            bpy.context.scene.frame_current,
        )


# -- tests in a real window (xvfb-run blender --enable-event-simulate --python TEST -- BUILD) --
def run_in_window(step, fail, seconds, prepare=None):
    """Enable the add-on from the build named after `--` (prepare(build) first, when given),
    then call step() from a timer until it ends the process (its return value is the next
    interval); an exception in it, or `seconds` without an end, is fail(message)."""
    import traceback

    argv = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else []
    build = argv[0] if argv else "build"
    if prepare is not None:
        prepare(build)
    enable_addon(build)

    def tick():
        try:
            return step()
        except Exception:
            traceback.print_exc()
            fail("exception in the test")

    bpy.app.timers.register(tick, first_interval=1.0)
    bpy.app.timers.register(lambda: fail("timed out") or None, first_interval=float(seconds))


def close_splash():
    """A click beside the splash screen, as an artist would: it takes the keyboard's events."""
    window = bpy.context.window_manager.windows[0]
    window.event_simulate("LEFTMOUSE", "PRESS", x=20, y=window.height // 2)
    window.event_simulate("LEFTMOUSE", "RELEASE", x=20, y=window.height // 2)


def press_key(key, ctrl=False):
    window = bpy.context.window_manager.windows[0]
    window.event_simulate(key, "PRESS", ctrl=ctrl)
    window.event_simulate(key, "RELEASE", ctrl=ctrl)


def hide_viewports():
    """Info editors instead of 3D Views: on Xvfb's software GL a viewport redraw (about a
    second for the 69k-triangle bunny) would hide what a test measures."""
    for area in bpy.context.window_manager.windows[0].screen.areas:
        if area.type == "VIEW_3D":
            area.type = "INFO"
