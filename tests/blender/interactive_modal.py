# SPDX-License-Identifier: GPL-3.0-or-later
"""The interactive (modal) path in a real Blender window, driven by timers:

    xvfb-run -a blender --factory-startup --enable-event-simulate \\
        --python tests/blender/interactive_modal.py -- BUILD_DIR

1. invoke() runs the voxelization on a worker thread and returns RUNNING_MODAL; the
   main loop keeps running (timers fire) until the volume appears; a re-run writes new
   files, and undoing it brings back the first volume with its own file intact; undoing
   the first run removes it.
3. (below) Esc while the .vdb write is held by the test (a stage that never checks the
   token): the operator ends at once all the same; the worker, released afterwards, deletes
   what it staged.
2. A run held on its worker thread until the token is cancelled (so it lasts exactly as long
   as the test wants, on any machine) keeps the UI responsive, and a simulated Esc cancels
   it through the native token: no volume, no files, the operator ends.
Exits 0 on success, 1 on failure (CTest runs it when xvfb-run is installed)."""

import hashlib
import os
import sys
import threading
import tempfile
import time

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import helpers  # noqa: E402

OUT = tempfile.mkdtemp(prefix="hyvox-modal-")
state = {"step": "start", "t0": 0.0, "ticks": [], "max_gap": 0.0, "progress": []}


def fail(message):
    print("MODAL TEST FAILED:", message, flush=True)
    os._exit(1)


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def view3d_override():
    window = bpy.context.window_manager.windows[0]
    return dict(window=window, screen=window.screen)


def running():
    from hyvox_blender.blender.operators import OBJECT_OT_hyvox_voxelize

    return OBJECT_OT_hyvox_voxelize._active


def hold_until_cancelled():
    """Make the add-on's voxelize wait on the worker thread until the run's token is
    cancelled, then call the real one (which raises hyvox.Cancelled for a cancelled token):
    a slow run whose length is an event the test controls, not the machine's speed."""
    from hyvox_blender.core import backend

    real = backend.voxelize

    def held(module, vertices, triangles, settings, method, token=None, **kwargs):
        deadline = time.monotonic() + 60
        while token is not None and not token.cancelled and time.monotonic() < deadline:
            time.sleep(0.01)
        return real(module, vertices, triangles, settings, method, token=token, **kwargs)

    held.original = real
    backend.voxelize = held


WRITE = {"entered": threading.Event(), "release": threading.Event(), "thread": None}


def hold_the_write():
    """Make the next run's .vdb write wait for WRITE["release"] (set by the test only), and
    ignore the cancel token: a stage that cannot be interrupted, whose end the test decides."""
    from hyvox_blender.core import backend

    real = getattr(backend.voxelize, "original", backend.voxelize)

    class HeldGrid:
        def __init__(self, grid):
            self._grid = grid

        def __getattr__(self, name):
            return getattr(self._grid, name)

        def write_vdb(self, path, cancel=None, **options):
            WRITE["thread"] = threading.current_thread()
            WRITE["entered"].set()
            WRITE["release"].wait(60)
            return self._grid.write_vdb(path, **options)  # no token: it cannot be cancelled

    def voxelize_then_hold(*args, **kwargs):
        backend.voxelize = real
        return HeldGrid(real(*args, **kwargs))

    backend.voxelize = voxelize_then_hold


def invoke(**kw):
    with bpy.context.temp_override(**view3d_override()):
        return bpy.ops.object.hyvox_voxelize("INVOKE_DEFAULT", output_dir=OUT, **kw)


def step():
    now = time.perf_counter()
    if state["ticks"]:
        state["max_gap"] = max(state["max_gap"], now - state["ticks"][-1])
    state["ticks"].append(now)
    s = state["step"]
    if s == "start":
        helpers.hide_viewports()
        helpers.clear_scene()
        cube = helpers.cube()
        helpers.select_only(cube)
        bpy.context.scene.hyvox.padding = 1  # from the scene, not the operator's default
        result = invoke(method="cpu", resolution=64)
        print("invoke ->", result, flush=True)
        if result != {"RUNNING_MODAL"}:
            fail(f"invoke returned {result}, expected RUNNING_MODAL")
        state.update(step="wait_first", t0=now, max_gap=0.0, ticks=[now])
    elif s == "wait_first":
        if running() is None:
            if "Cube_voxels" not in bpy.data.objects:
                fail("the modal run ended without a volume")
            # The redo panel (Adjust Last Operation) shows the values the run used.
            last = bpy.context.window_manager.operators[-1]
            shown = (last.bl_idname, last.properties.resolution, last.properties.padding, last.properties.method)
            if shown != ("OBJECT_OT_hyvox_voxelize", 64, 1, "cpu"):
                fail(f"the redo panel shows {shown}, not what the run used")
            bpy.context.scene.hyvox.property_unset("padding")
            path = bpy.path.abspath(bpy.data.objects["Cube_voxels"].data.filepath)
            state.update(first_file=path, first_digest=digest(path))
            print("modal run finished; a re-run", flush=True)
            result = invoke(method="cpu", resolution=32)
            if result != {"RUNNING_MODAL"}:
                fail(f"the re-run's invoke returned {result}")
            state.update(step="wait_rerun", t0=now)
        elif now - state["t0"] > 30:
            fail("the modal run did not finish in 30 s")
    elif s == "wait_rerun":
        if running() is None:
            rerun_file = bpy.path.abspath(bpy.data.objects["Cube_voxels"].data.filepath)
            if rerun_file == state["first_file"]:
                fail("the re-run rewrote the first run's file")
            print("re-run finished; undo it", flush=True)
            with bpy.context.temp_override(**view3d_override()):
                bpy.ops.ed.undo()
            state["step"] = "check_rerun_undo"
        elif now - state["t0"] > 30:
            fail("the re-run did not finish in 30 s")
    elif s == "check_rerun_undo":
        # Undo brings back the first run's volume, and its file still holds the first voxels.
        obj = bpy.data.objects.get("Cube_voxels")
        path = bpy.path.abspath(obj.data.filepath) if obj is not None else None
        if path != state["first_file"] or digest(path) != state["first_digest"]:
            fail(f"after undoing the re-run the volume reads {path}, not the first run's intact file")
        print("undo of the re-run restored the first volume and file; undo the first run", flush=True)
        with bpy.context.temp_override(**view3d_override()):
            bpy.ops.ed.undo()
        state["step"] = "check_undo"
    elif s == "check_undo":
        if "Cube_voxels" in bpy.data.objects:
            fail("undo did not remove the volume")
        print("undo removed the volume", flush=True)
        helpers.clear_scene()
        bunny = helpers.bunny()
        helpers.select_only(bunny)
        for f in os.listdir(OUT):
            os.remove(os.path.join(OUT, f))
        state.update(step="settle", t0=now)
    elif s == "settle":
        if now - state["t0"] < 0.5:
            return 0.05
        hold_until_cancelled()
        result = invoke(method="cpu", resolution=64)
        if result != {"RUNNING_MODAL"}:
            fail(f"slow invoke returned {result}")
        print(f"invoke took {(time.perf_counter() - now) * 1000:.0f} ms", flush=True)
        now = time.perf_counter()  # measure the gaps from here: the run is on its worker
        state.update(step="slow", t0=now, max_gap=0.0, ticks=[now])
    elif s == "slow":
        run = running()
        if run is None:
            fail("the slow run ended before it could be cancelled")
        state["progress"].append(run.pipeline.progress)
        if now - state["t0"] > 1.0:
            print("ticks:", [round((b - a) * 1000) for a, b in zip(state["ticks"], state["ticks"][1:])], flush=True)
            print("progress samples:", [round(p, 3) for p in state["progress"]], flush=True)
            print(f"longest main-loop gap while voxelizing: {state['max_gap'] * 1000:.0f} ms", flush=True)
            # A run on the main thread would block it for the whole run (seconds); the bound
            # leaves room for a loaded CI machine without hiding a real freeze.
            if state["max_gap"] > 0.9:
                fail("the UI stalled while the worker ran")
            helpers.press_key("ESC")
            state.update(step="cancelled", t0=now)
    elif s == "cancelled":
        if running() is not None:
            if now - state["t0"] > 5:
                fail("Esc did not stop the run within 5 s")
            return 0.05
        if any(o.type == "VOLUME" for o in bpy.data.objects):
            fail("a cancelled run created a volume")
        if os.listdir(OUT):
            fail(f"a cancelled run left files: {os.listdir(OUT)}")
        print(f"Esc cancelled the run in {(now - state['t0']) * 1000:.0f} ms", flush=True)
        # 3. Esc during a stage that never looks at the token (a .vdb write held by the test):
        # the operator must end anyway, without waiting for that stage.
        hold_the_write()
        result = invoke(method="cpu", resolution=32)
        if result != {"RUNNING_MODAL"}:
            fail(f"the held-write invoke returned {result}")
        state.update(step="wait_write", t0=now)
    elif s == "wait_write":
        if not WRITE["entered"].is_set():
            if now - state["t0"] > 30:
                fail("the run never reached its write")
            return 0.05
        helpers.press_key("ESC")
        state.update(step="write_cancelled", t0=now)
    elif s == "write_cancelled":
        if running() is not None:
            if now - state["t0"] > 5:
                fail("Esc waited for a stage that does not check for cancellation")
            return 0.05
        if WRITE["release"].is_set():
            fail("the write was released before the operator ended")
        if any(o.type == "VOLUME" for o in bpy.data.objects):
            fail("a cancelled run created a volume")
        print("Esc ended the operator while the write was still held; releasing it", flush=True)
        WRITE["release"].set()
        state.update(step="write_released", t0=now)
    elif s == "write_released":
        if WRITE["thread"] is not None and WRITE["thread"].is_alive() or os.listdir(OUT):
            if now - state["t0"] > 30:
                fail(f"the abandoned run left files: {os.listdir(OUT)}")
            return 0.05
        print("the abandoned worker ended and deleted what it had staged", flush=True)
        print("MODAL TEST PASSED", flush=True)
        os._exit(0)
    return 0.05


helpers.run_in_window(step, fail, seconds=120)
