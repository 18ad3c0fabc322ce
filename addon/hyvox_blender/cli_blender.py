# SPDX-License-Identifier: GPL-3.0-or-later
"""Headless entry point for pipelines and render farms:

    blender -b scene.blend --python B/addon/hyvox_blender/cli_blender.py -- \\
        --frames 1-10 --output DIR --resolution 256 [--voxel-size S] [--method cpu] \\
        [--mode conservative|thin|solid] [--tess-gamma G] [--hybrid-cutoff C] [--padding P] \\
        [--objects A,B] [--separate] [--no-color] [--viewport] [--save OUT.blend] [--stats-json FILE]

Voxelizes the named objects (default: the selection, or every visible mesh when nothing
is selected) with the add-on's operator, so the result is the same as in the UI. A frame
chunk (--frames 11-20) writes its own files name_0011.vdb...; chunks assemble. Modifiers
and Geometry Nodes are evaluated at render settings, as the render shows the scene
(--viewport: at viewport settings); instances are included. Put Blender options such as
-a (render the animation) before the `--`. Exits 1 on failure."""
import argparse
import json
import os
import sys


def parse_args(argv):
    """Options of the add-on's own (output, frames, objects...) plus the voxelize options the
    operator takes, with the schema's names, types and help (hyvox.OPTIONS). Values are
    checked by the operator, which refuses them with the schema's message."""
    from hyvox_blender.blender.properties import SCENE_OPTIONS, option_spec
    from hyvox_blender.core.backend import AUTO_METHOD
    parser = argparse.ArgumentParser(prog="blender -b FILE --python cli_blender.py --",
                                     description="Voxelize objects of a .blend into OpenVDB volumes.")
    parser.add_argument("--output", "-o", help="folder for the .vdb files (default: next to the .blend)")
    types = {"int": int, "float": float, "choice": str, "str": str}
    for name in ("method",) + SCENE_OPTIONS:
        spec = option_spec(name)
        flags = [spec.cli_flag] + (["-r"] if name == "resolution" else [])
        choices = ([AUTO_METHOD] if name == "method" else []) + list(spec.choices) or None
        parser.add_argument(*flags, dest=name, type=types[spec.type], choices=choices, help=spec.help)
    parser.add_argument("--frames", help="frame range, e.g. 1-10 (one .vdb per frame)")
    parser.add_argument("--objects", help="comma-separated object names")
    parser.add_argument("--separate", action="store_true", help="one volume per object")
    parser.add_argument("--no-color", dest="color", action="store_false",
                        help="no `color` grid (default: the colour the objects' materials show)")
    parser.add_argument("--viewport", action="store_true",
                        help="evaluate modifiers at viewport settings (default: render settings)")
    parser.add_argument("--save", help="save the .blend with the volumes to this path")
    parser.add_argument("--stats-json", help="write origin, voxel size, counts and timings here")
    args = parser.parse_args(argv)
    if args.resolution is not None and args.voxel_size is not None:
        parser.error("give --resolution or --voxel-size, not both")
    return args


def enable_addon():
    """Make this file's add-on importable and enabled (also when not installed)."""
    import addon_utils
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    if root not in sys.path:
        sys.path.insert(0, root)
    addon_utils.enable("hyvox_blender", default_set=False, handle_error=None)


def choose_objects(names):
    import bpy
    layer = bpy.context.view_layer
    if names:
        missing = [n for n in names if n not in bpy.data.objects]
        if missing:
            raise SystemExit(f"hyvox: no object named {', '.join(missing)}")
        chosen = [bpy.data.objects[n] for n in names]
    else:
        chosen = list(bpy.context.selected_objects) or [
            o for o in layer.objects if o.type == "MESH" and o.visible_get()]
    for obj in layer.objects:
        obj.select_set(False)
    for obj in chosen:
        obj.select_set(True)
    if chosen:
        layer.objects.active = chosen[0]
    return chosen


def main(argv):
    import bpy
    enable_addon()
    args = parse_args(argv)
    from hyvox_blender.blender import operators
    from hyvox_blender.blender.properties import SCENE_OPTIONS
    from hyvox_blender.core.settings import parse_frame_range

    choose_objects(args.objects.split(",") if args.objects else None)
    kwargs = {name: getattr(args, name) for name in ("method",) + SCENE_OPTIONS if getattr(args, name) is not None}
    if args.output:
        kwargs["output_dir"] = os.path.abspath(args.output)
    if args.separate:
        kwargs["separate"] = True
    if args.mode is not None:
        # The operator fills the interior by its Fill Interior setting (the scene's unless
        # given): an explicit --mode decides it, so --mode thin is not turned into solid.
        kwargs["fill_interior"] = args.mode == "solid"
    kwargs["evaluation"] = "VIEWPORT" if args.viewport else "RENDER"
    kwargs["color"] = args.color
    kwargs["unique_file_names"] = False  # chunks of one sequence must share their file names
    if args.frames:
        frames = parse_frame_range(args.frames)
        if frames != list(range(frames[0], frames[-1] + 1)):
            # The operator voxelizes every frame from start to end; a step would be lost.
            raise SystemExit("hyvox: --frames takes START-END; a frame step is not supported")
        kwargs.update(frame_start=frames[0], frame_end=frames[-1])

    bpy.ops.object.hyvox_voxelize(**kwargs)  # RuntimeError with the report on failure
    if args.stats_json:
        with open(args.stats_json, "w") as f:
            json.dump(operators.last_run_record, f, indent=2)
    if args.save:
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(args.save))


if __name__ == "__main__":
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    try:
        main(argv)
    except (Exception, SystemExit) as exc:  # every failure: a message and exit code 1
        if isinstance(exc, SystemExit) and exc.code in (0, None):
            raise
        print(f"hyvox: error: {exc}", file=sys.stderr)
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(1)  # Blender would otherwise go on and exit 0
