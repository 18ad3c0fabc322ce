# SPDX-License-Identifier: GPL-3.0-or-later
"""Headless entry point for pipelines and render farms:

    blender -b scene.blend --python B/addon/hyvox_blender/cli_blender.py -- \\
        --frames 1-10 --output DIR --resolution 256 [--voxel-size S] [--method cpu] \\
        [--mode conservative|thin|solid] [--tess-gamma G] [--hybrid-cutoff C] [--padding P] \\
        [--objects A,B] [--separate] [--no-color] [--viewport] [--live] [--save OUT.blend] [--stats-json FILE]

The add-on runs as Blender knows it: the extension (Blender 4.2+) this file was installed
with, bl_ext.<repository>.hyvox_blender, else the legacy add-on of this file's folder.
Voxelizes the named objects (default: the selection, or every visible mesh when nothing
is selected) with the add-on's operator, so the result is the same as in the UI. A frame
chunk (--frames 11-20) writes its own files name_0011.vdb...; chunks assemble. Modifiers
and Geometry Nodes are evaluated at render settings, as the render shows the scene
(--viewport: at viewport settings); instances are included. Put Blender options such as
-a (render the animation) before the `--`. --live makes live volumes (docs/live.md): with
-a every rendered frame gets its own voxels, with no frame range and no bake step.
Exits 1 on failure."""

import argparse
import importlib
import json
import os
import sys


def parse_args(argv, package):
    """Options of the add-on's own (output, frames, objects...) plus the voxelize options the
    operator takes, with the schema's names, types and help (hyvox.OPTIONS). Values are
    checked by the operator, which refuses them with the schema's message."""
    properties = importlib.import_module(package + ".blender.ui.properties")
    SCENE_OPTIONS, option_spec = properties.SCENE_OPTIONS, properties.option_spec
    AUTO_METHOD = importlib.import_module(package + ".core.backend").AUTO_METHOD
    parser = argparse.ArgumentParser(
        prog="blender -b FILE --python cli_blender.py --",
        description="Voxelize objects of a .blend into OpenVDB volumes.",
    )
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
    parser.add_argument(
        "--no-color",
        dest="color",
        action="store_false",
        help="no `color` grid (default: the colour the objects' materials show)",
    )
    parser.add_argument(
        "--viewport", action="store_true", help="evaluate modifiers at viewport settings (default: render settings)"
    )
    parser.add_argument(
        "--live",
        action="store_true",
        help="live volumes: they follow the sources, and a render (-a) voxelizes each frame",
    )
    parser.add_argument("--save", help="save the .blend with the volumes to this path")
    parser.add_argument("--stats-json", help="write origin, voxel size, counts and timings here")
    args = parser.parse_args(argv)
    if args.resolution is not None and args.voxel_size is not None:
        parser.error("give --resolution or --voxel-size, not both")
    return args


def addon_package():
    """The module name of the add-on whose folder holds this file: the one Blender lists
    (bl_ext.<repository>.hyvox_blender for an installed extension, hyvox_blender for a
    legacy add-on in a scripts folder), else this folder as a legacy add-on from its parent."""
    import addon_utils

    here = os.path.dirname(os.path.realpath(__file__))
    for module in addon_utils.modules():
        if os.path.dirname(os.path.realpath(getattr(module, "__file__", None) or "")) == here:
            return module.__name__
    root = os.path.dirname(here)
    if root not in sys.path:
        sys.path.insert(0, root)
    return os.path.basename(here)


def enable_addon():
    """Enable this file's add-on (also when not installed, or installed but not enabled in
    the preferences this Blender started with); returns its module name."""
    import addon_utils

    package = addon_package()
    if addon_utils.enable(package, default_set=False, handle_error=None) is None:
        raise SystemExit(f"hyvox: could not enable the add-on {package}")
    return package


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
            o for o in layer.objects if o.type == "MESH" and o.visible_get()
        ]
    for obj in layer.objects:
        obj.select_set(False)
    for obj in chosen:
        obj.select_set(True)
    if chosen:
        layer.objects.active = chosen[0]
    return chosen


def main(argv):
    import bpy

    package = enable_addon()
    args = parse_args(argv, package)
    operators = importlib.import_module(package + ".blender.operators")
    SCENE_OPTIONS = importlib.import_module(package + ".blender.ui.properties").SCENE_OPTIONS
    parse_frame_range = importlib.import_module(package + ".core.settings").parse_frame_range

    choose_objects(args.objects.split(",") if args.objects else None)
    kwargs = {name: getattr(args, name) for name in ("method",) + SCENE_OPTIONS if getattr(args, name) is not None}
    if args.output:
        kwargs["output_dir"] = os.path.abspath(args.output)
    if args.separate:
        kwargs["separate"] = True
    kwargs["evaluation"] = "VIEWPORT" if args.viewport else "RENDER"
    kwargs["color"] = args.color
    kwargs["unique_file_names"] = False  # chunks of one sequence must share their file names
    if args.live:
        kwargs["live"] = True
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
    argv = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else []
    try:
        main(argv)
    except (Exception, SystemExit) as exc:  # every failure: a message and exit code 1
        if isinstance(exc, SystemExit) and exc.code in (0, None):
            raise
        print(f"hyvox: error: {exc}", file=sys.stderr)
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(1)  # Blender would otherwise go on and exit 0
