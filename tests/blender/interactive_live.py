# SPDX-License-Identifier: GPL-3.0-or-later
"""Live in a real Blender window (the UI path: a worker thread, polled by a timer):

    xvfb-run -a blender --factory-startup --enable-event-simulate \\
        --python tests/blender/interactive_live.py -- BUILD_DIR

A run's length is an event the test controls, never the machine's speed: the add-on's
voxelize is wrapped so that a run waits on its worker thread until the test releases it
or its token is cancelled (then the wrapper records when it saw the cancel).
1. Sculpt-like edits (vertices moved, a frame of the test's own timer each) while the
   first run is held: the event loop keeps ticking (the largest gap between ticks is far
   below the hold: the main thread never waits for a voxelization); the burst ends with
   at most two runs and the voxels of the last edit.
2. Esc during a held run: the worker sees the cancel within 0.5 s; the volume keeps its
   voxels and no file of the cancelled run is left.
3. Live switched off during a held run: the same.
4. Undo and redo: the volume shows the voxels of the state returned to.
5. Frames changed while a run is held (playback that voxelizing cannot keep up with): the
   newest frame wins, in at most two runs.
6. Render Animation from the window (a job: Live runs on the render thread, with the
   interface locked, as turning Live on set): each frame renders with its own voxels,
   against the reference voxelizer.
7. The source deleted during a held run: cancelled, no error, no stray file.
Exits 0 on success, 1 on failure (CTest runs it under xvfb-run)."""

import os
import sys
import tempfile
import threading
import time

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import helpers  # noqa: E402

OUT = tempfile.mkdtemp(prefix="hyvox-live-")
CANCEL_WITHIN = 0.5  # seconds from Esc (or the switch) to the worker seeing the cancel
state = {"step": "start", "t0": 0.0, "ticks": [], "max_gap": 0.0, "edits": 0}


def fail(message):
    print("LIVE TEST FAILED:", message, flush=True)
    os._exit(1)


class Hold:
    """Wraps the add-on's backend.voxelize: while armed, the next call waits on its worker
    until released or cancelled."""

    armed = False
    entered = threading.Event()
    release = threading.Event()
    cancel_seen = None
    calls = 0

    @classmethod
    def install(cls):
        from hyvox_blender.core import backend

        real = backend.voxelize

        def held(module, vertices, triangles, settings, method, token=None, **kwargs):
            cls.calls += 1
            if cls.armed:
                cls.armed = False
                cls.entered.set()
                deadline = time.monotonic() + 60
                while not cls.release.is_set() and not token.cancelled and time.monotonic() < deadline:
                    time.sleep(0.002)
                if token.cancelled:
                    cls.cancel_seen = time.perf_counter()
            return real(module, vertices, triangles, settings, method, token=token, **kwargs)

        backend.voxelize = held

    @classmethod
    def arm(cls):
        cls.armed, cls.cancel_seen = True, None
        cls.entered.clear()
        cls.release.clear()


def live():
    from hyvox_blender.blender.live import driver as module

    return module


def window_override():
    window = bpy.context.window_manager.windows[0]
    return dict(window=window, screen=window.screen, area=window.screen.areas[0])


def volume():
    return bpy.data.objects["Icosphere_voxels"]


def source():
    return bpy.data.objects.get("Icosphere")


def shown_file():
    return bpy.path.abspath(volume().data.filepath)


def idle():
    return not live().scheduler().active()


def runs():
    return live()._Live.runs_started.get(volume()["hyvox_live_id"], 0)


def oracle_voxels(obj):
    """World lattice indices of the reference voxelizer's voxels for obj's evaluated mesh."""
    from test_live import evaluated_world_mesh, oracle_voxels as voxels

    return voxels(*evaluated_world_mesh(obj), float(volume()["hyvox_voxel_size"]), "conservative")


def file_voxels(path):
    from test_live import file_voxels as voxels

    return voxels(path)


def new_files():
    """Files in the output folder that were not there when the last run was armed."""
    return sorted(set(os.listdir(OUT)) - state["files_before"])


def arm():
    state["files_before"] = set(os.listdir(OUT))
    Hold.arm()


def record_rendered(*_args):
    state["rendered"].append(shown_file())


def render_setup(scene, path):
    from test_live import render_setup as setup

    setup(scene, path)


def held_edit(next_step):
    """An edit whose run will be held, then next_step (which waits for the run to start)."""
    arm()
    sculpt(source(), 0.05)
    go(next_step)


def check_burst(what):
    """After a burst (edits or frames) during a held run: at most two runs, the last state's voxels."""
    made = runs() - state["runs_before"]
    print(f"{what} gave {made} runs", flush=True)
    if made > 2:
        fail(f"{made} runs for {what} (at most 2)")
    if file_voxels(shown_file()) != oracle_voxels(source()):
        fail(f"after {what} the volume does not hold the last state's voxels")


def sculpt(obj, amount):
    """Push a few vertices outward, as a brush stroke's step does."""
    mesh = obj.data
    co = np.empty(len(mesh.vertices) * 3, np.float32)
    mesh.vertices.foreach_get("co", co)
    co = co.reshape(-1, 3)
    near = np.argsort(np.linalg.norm(co - co[0], axis=1))[:12]
    co[near] *= np.float32(1.0 + amount)
    mesh.vertices.foreach_set("co", co.ravel())
    mesh.update()


def wait(condition, what, seconds=30):
    """True once condition() holds; fails after `seconds` in this step."""
    if condition():
        return True
    if time.perf_counter() - state["t0"] > seconds:
        fail(f"{what}: not within {seconds} s")
    return False


def go(step_name):
    state.update(step=step_name, t0=time.perf_counter())


def step():
    now = time.perf_counter()
    if state["ticks"]:
        state["max_gap"] = max(state["max_gap"], now - state["ticks"][-1])
    state["ticks"].append(now)
    s = state["step"]
    if s == "start":
        helpers.close_splash()  # it would take the keyboard's events
        helpers.hide_viewports()
        helpers.clear_scene()
        bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=3, radius=1.0)
        helpers.select_only(source())
        if bpy.context.scene.render.use_lock_interface:
            fail("the factory settings lock the interface while rendering: the test of the switch means nothing")
        result = bpy.ops.object.hyvox_voxelize(
            resolution=32, method="cpu", output_dir=OUT, live=True, mode="conservative"
        )
        if result != {"FINISHED"} or not volume().hyvox_live:
            fail(f"the live volume was not made: {result}")
        if not bpy.context.scene.render.use_lock_interface:
            fail("turning Live on did not lock the interface for renders")
        Hold.install()
        go("settle")
    elif s == "settle":
        if wait(idle, "Live settles after the first run"):
            # 1. A stroke of sculpt-like edits while the first run is held.
            Hold.arm()
            state.update(runs_before=runs(), edits=0, ticks=[now], max_gap=0.0)
            go("sculpt")
    elif s == "sculpt":
        sculpt(source(), 0.02)
        state["edits"] += 1
        if state["edits"] >= 10 and now - state["t0"] > 1.5:
            if not Hold.entered.is_set():
                fail("no run started during the stroke")
            gap = state["max_gap"]
            print(
                f"largest gap between timer ticks while Live ran: {gap * 1000:.0f} ms "
                f"({state['edits']} edits in {now - state['t0']:.2f} s, the first run held throughout)",
                flush=True,
            )
            # Blocking on the held run would leave a gap as long as the stroke (over 1.5 s).
            if gap > 0.75:
                fail(f"the UI stalled for {gap * 1000:.0f} ms while a run was held")
            Hold.release.set()
            go("sculpt_done")
        return 0.02
    elif s == "sculpt_done":
        if wait(idle, "the runs after the stroke end"):
            check_burst(f"a stroke of {state['edits']} edits")
            # 2. Esc during a held run.
            state["before_esc"] = shown_file()
            held_edit("esc_wait")
    elif s == "esc_wait":
        if wait(Hold.entered.is_set, "a run starts after the edit"):
            state["pressed"] = time.perf_counter()
            helpers.press_key("ESC")
            go("esc_check")
    elif s == "esc_check":
        if wait(lambda: Hold.cancel_seen is not None and idle(), "Esc cancels the run"):
            delay = Hold.cancel_seen - state["pressed"]
            print(f"Esc: the worker saw the cancel {delay * 1000:.0f} ms after the key", flush=True)
            if delay > CANCEL_WITHIN:
                fail(f"Esc stopped the run after {delay:.2f} s")
            if shown_file() != state["before_esc"] or new_files():
                fail(f"the cancelled run changed the volume or left files: {new_files()}")
            if "Cancelled" not in live().status_line(volume()):
                fail(f"the panel says {live().status_line(volume())!r} after Esc")
            # 3. Live switched off during a held run.
            held_edit("off_wait")
    elif s == "off_wait":
        if wait(Hold.entered.is_set, "a run starts after the edit"):
            state["pressed"] = time.perf_counter()
            volume().hyvox_live = False
            go("off_check")
    elif s == "off_check":
        if wait(lambda: Hold.cancel_seen is not None and idle(), "switching Live off cancels the run"):
            delay = Hold.cancel_seen - state["pressed"]
            print(f"Live off: the worker saw the cancel {delay * 1000:.0f} ms after the switch", flush=True)
            if delay > CANCEL_WITHIN:
                fail(f"switching Live off stopped the run after {delay:.2f} s")
            if shown_file() != state["before_esc"] or not os.path.exists(shown_file()):
                fail("switching Live off did not keep the last voxels")
            if os.listdir(OUT) != [os.path.basename(shown_file())]:
                fail(f"switching Live off left other files: {os.listdir(OUT)}")
            # 4. Undo and redo.
            volume().hyvox_live = True
            go("undo_prepare")
    elif s == "undo_prepare":
        if wait(idle, "Live catches up when switched on"):
            with bpy.context.temp_override(**window_override()):
                bpy.ops.ed.undo_push(message="state A")
            state["a_file"], state["a_voxels"] = shown_file(), file_voxels(shown_file())
            source().location.x = 0.8
            go("undo_b")
    elif s == "undo_b":
        if wait(lambda: idle() and shown_file() != state["a_file"], "Live follows the move"):
            with bpy.context.temp_override(**window_override()):
                bpy.ops.ed.undo_push(message="state B")
            state["b_voxels"] = file_voxels(shown_file())
            with bpy.context.temp_override(**window_override()):
                bpy.ops.ed.undo()
            go("undo_check")
    elif s == "undo_check":
        if wait(lambda: idle() and abs(source().location.x) < 1e-6, "undo returns to state A"):
            if file_voxels(shown_file()) != state["a_voxels"] or file_voxels(shown_file()) != oracle_voxels(source()):
                fail("after undo the volume does not show state A's voxels")
            with bpy.context.temp_override(**window_override()):
                bpy.ops.ed.redo()
            go("redo_check")
    elif s == "redo_check":
        if wait(lambda: idle() and abs(source().location.x - 0.8) < 1e-6, "redo returns to state B"):
            if file_voxels(shown_file()) != state["b_voxels"]:
                fail("after redo the volume does not show state B's voxels")
            print("undo and redo show the voxels of the states they return to", flush=True)
            # 5. Frames faster than voxelizing: keyframes, then frames changed during a held run.
            obj = source()
            for frame, x in ((1, 0.0), (10, 1.8)):
                obj.location.x = x
                obj.keyframe_insert("location", frame=frame)
            bpy.context.scene.frame_set(1)
            go("frames_settle")
    elif s == "frames_settle":
        if wait(idle, "Live settles at frame 1"):
            Hold.arm()
            state.update(runs_before=runs(), frame=1)
            bpy.context.scene.frame_set(2)
            go("frames")
    elif s == "frames":
        if not Hold.entered.is_set():
            wait(Hold.entered.is_set, "a run starts on the frame change")
            return 0.02
        if state["frame"] < 9:
            state["frame"] += 1
            bpy.context.scene.frame_set(state["frame"])
            return 0.02
        Hold.release.set()
        go("frames_check")
    elif s == "frames_check":
        if wait(idle, "the frames' runs end"):
            check_burst("frames 2-9 while a run was held")
            # 6. Render Animation in the UI (a job on the render thread): each frame its voxels.
            scene = bpy.context.scene
            render_setup(scene, os.path.join(OUT, "renders", "frame_"))
            scene.frame_start, scene.frame_end = 1, 3
            state["rendered"] = []
            bpy.app.handlers.render_post.append(record_rendered)
            # Ctrl+F12, as an artist starts it. Not bpy.ops.render.render() under a context
            # override: Blender 3.4 (Python 3.11) can crash when the render thread's handlers
            # run while the main thread is still in a Python-called operator (docs/live.md).
            helpers.press_key("F12", ctrl=True)
            go("render_wait")
    elif s == "render_wait":
        if wait(
            lambda: len(state["rendered"]) == 3 and not bpy.app.is_job_running("RENDER") and idle(),
            "Render Animation ends",
            seconds=60,
        ):
            bpy.app.handlers.render_post.remove(record_rendered)
            for frame, path in enumerate(state["rendered"], start=1):
                bpy.context.scene.frame_set(frame)
                if file_voxels(path) != oracle_voxels(source()):
                    fail(f"frame {frame} rendered with voxels that are not its own ({path})")
            if len(set(state["rendered"])) != 3:
                fail(f"the three frames rendered with {len(set(state['rendered']))} files")
            print("Render Animation in the window gave each frame its own voxels", flush=True)
            # 7. The source deleted during a held run.
            held_edit("delete_wait")
    elif s == "delete_wait":
        if wait(Hold.entered.is_set, "a run starts after the edit"):
            state["before_delete"] = shown_file()
            bpy.data.objects.remove(source(), do_unlink=True)
            go("delete_check")
    elif s == "delete_check":
        if wait(lambda: Hold.cancel_seen is not None and idle(), "deleting the source cancels the run"):
            line = live().status_line(volume())
            if not line.startswith("Waiting") or shown_file() != state["before_delete"] or new_files():
                fail(f"after deleting the source: {line!r}, files of the cancelled run: {new_files()}")
            print(f"deleting the source cancelled the run; the panel says {line!r}", flush=True)
            print("LIVE TEST PASSED", flush=True)
            os._exit(0)
    return 0.02


helpers.run_in_window(step, fail, seconds=150)
