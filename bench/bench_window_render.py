# SPDX-License-Identifier: GPL-3.0-or-later
"""How often Blender crashes while it renders an animation from its window, by how the
render starts, Render > Lock Interface, and what Python runs on the render thread:

    python3 bench/bench_window_render.py --build build [--renders 150] [--blender blender]

Why: a render started in the window runs on Blender's render thread, and Blender calls
render_init, frame_change_post and render_post there, so Live's frame updates are Python on
that thread while the main thread goes on. Each row is Blender sessions under xvfb-run, each
rendering a 3-frame Cycles animation of a live Icosphere (32 x 32 pixels, the volume's
voxels made for each frame) again and again until the row has its renders or Blender dies;
a session that dies is a crash, and the row goes on in a new session. The main thread polls
for the render's end every 20 ms from a timer (as a script, or the add-on's own timer, does).

Configurations:
- start: `keys` (Ctrl+F12 through the window's events, as an artist starts it) or `script`
  (bpy.ops.render.render("INVOKE_DEFAULT") under bpy.context.temp_override, as a script does);
- lock: Render > Lock Interface on or off;
- python: `live` (a live volume: Live's handlers and one render_post handler run on the
  render thread) or `none` (no handler of hyvox or anyone: only Cycles' own Python)."""

import argparse
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
IN_BLENDER = "bpy" in sys.modules or os.path.basename(sys.executable).startswith("blender")


def rounds_in_blender():
    """Inside Blender: render until told, printing RENDERED after each animation."""
    import tempfile

    import bpy

    sys.path.insert(0, os.path.join(ROOT, "tests", "blender"))
    import helpers
    from test_live import render_setup

    argv = sys.argv[sys.argv.index("--") + 1 :]
    start, lock, python, renders = argv[1], argv[2] == "on", argv[3], int(argv[4])
    out = tempfile.mkdtemp(prefix="hyvox-window-render-")
    state = {"step": "start", "renders": 0}

    def on_render_post(*_args):
        # What the Live test reads on the render thread: the file the volume shows.
        volume = bpy.data.objects.get("Icosphere_voxels")
        state["shown"] = bpy.path.abspath(volume.data.filepath) if volume else ""

    def render():
        bpy.context.scene.render.use_lock_interface = lock
        if start == "keys":
            helpers.press_key("F12", ctrl=True)
            return
        window = bpy.context.window_manager.windows[0]
        with bpy.context.temp_override(window=window, screen=window.screen, area=window.screen.areas[0]):
            bpy.ops.render.render("INVOKE_DEFAULT", animation=True)

    def step():
        if state["step"] == "start":
            helpers.close_splash()
            helpers.hide_viewports()
            helpers.clear_scene()
            bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=3, radius=1.0)
            source = bpy.data.objects["Icosphere"]
            helpers.select_only(source)
            if python == "live":
                bpy.ops.object.hyvox_voxelize(resolution=32, method="cpu", output_dir=out, live=True)
                bpy.app.handlers.render_post.append(on_render_post)
            elif helpers.addon("blender.live.driver").follow_live_volumes():
                os._exit(4)  # no live volume, yet hyvox's handlers are registered
            for frame, x in ((1, 0.0), (10, 1.8)):
                source.location.x = x
                source.keyframe_insert("location", frame=frame)
            render_setup(bpy.context.scene, os.path.join(out, "frame_"))
            bpy.context.scene.frame_start, bpy.context.scene.frame_end = 1, 3
            state["step"] = "render"
            return 0.02
        if bpy.app.is_job_running("RENDER"):
            return 0.02
        if state.get("started"):
            state["renders"] += 1
            print("RENDERED", state["renders"], flush=True)
        if state["renders"] >= renders:
            os._exit(0)
        state["started"] = True
        render()
        return 0.3  # the job is running by then

    helpers.run_in_window(step, lambda message: os._exit(3), seconds=3600)


def session(args, start, lock, python, renders):
    """(renders done, crashed) of one Blender session."""
    command = ["xvfb-run", "-a", args.blender, "--factory-startup", "--enable-event-simulate", "-noaudio"]
    command += ["--python", os.path.abspath(__file__), "--", args.build, start, lock, python, str(renders)]
    try:
        process = subprocess.run(
            command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=120 + 10 * renders
        )
        output, failed = process.stdout, process.returncode != 0
    except subprocess.TimeoutExpired as exc:  # a hang counts as a crash: the artist's work is as lost
        output, failed = exc.stdout.decode() if isinstance(exc.stdout, bytes) else (exc.stdout or ""), True
    done = sum(1 for line in output.splitlines() if line.startswith("RENDERED"))
    return done, failed or done < renders


def main():
    sys.path.insert(0, HERE)
    from bench_results import Column, Table, add_out_argument

    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default="build")
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--renders", type=int, default=150, help="animations rendered per configuration")
    parser.add_argument(
        "--configurations",
        default="keys:on:live,keys:off:live,script:on:live,script:off:live,script:on:none,script:off:none",
        help="start:lock:python, comma separated",
    )
    add_out_argument(parser)
    args = parser.parse_args()
    args.build = os.path.abspath(args.build)
    table = Table(
        "window_render",
        "Renders from Blender's window (3-frame Cycles animations) and the crashes among them",
        [
            Column("start"),
            Column("Lock Interface"),
            Column("Python on the render thread"),
            Column("renders"),
            Column("crashes"),
        ],
    )
    for configuration in args.configurations.split(","):
        start, lock, python = configuration.split(":")
        done = crashes = 0
        while done < args.renders:
            rendered, crashed = session(args, start, lock, python, args.renders - done)
            done += rendered
            crashes += crashed
            print(f"{configuration}: {done} renders, {crashes} crashes", flush=True)
        what = "Live's handlers + a render_post handler" if python == "live" else "none but Cycles' own"
        table.add([start, lock, what, done, crashes])
    table.note(
        "A crash is a Blender session that died (SIGSEGV) or hung before its renders were done. "
        "Debian's Blender 3.4.1 with Python 3.11 under Xvfb; the main thread's crashes are in Python's own "
        "functions called from Blender's context lookup, while the render thread runs Python."
    )
    table.write(args.out)


if __name__ == "__main__":
    if IN_BLENDER:
        rounds_in_blender()
    else:
        main()
