# SPDX-License-Identifier: GPL-3.0-or-later
"""Benchmark (not a test): the whole hyvox operator (export, voxelize, write, import)
against Blender's own Mesh to Volume modifier (surface band of one voxel each side, the
same voxel size, depsgraph evaluation timed), on Suzanne subdivided to level 4 (252k
triangles) and level 6 (4M), at 256 and 512 voxels along the longest side.

    blender -b --factory-startup --python bench/bench_blender_addon.py -- --build B \\
        [--levels 4,6] [--resolutions 256,512] [--repeat 3] [--method cpu] [--json FILE] [--out DIR]

Both sides start from the same plain (modifier-applied) mesh so subdivision is not timed.
Prints a table of medians and where hyvox's time goes (the breakdown of the fastest run;
the add-on share, (export + import) / total, is the median of the runs' own shares, and the
export's CPU time the median of the runs').
--skip-mesh-to-volume times hyvox only. The table also goes to DIR/blender_addon.{json,md}
(default bench/results/)."""

import argparse
import json
import os
import shlex
import statistics
import sys
import tempfile
import time

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_results import Column, Table, add_out_argument  # noqa: E402  (beside this script)
from blender_bench import exit_1_on_error, mesh_to_volume  # noqa: E402


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else []
    parser = argparse.ArgumentParser(prog="blender -b --python bench/bench_blender_addon.py --")
    parser.add_argument("--build", default="build")
    parser.add_argument("--levels", default="4,6")
    parser.add_argument("--resolutions", default="256,512")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--method", default="cpu")
    parser.add_argument("--json", help="also write the rows as JSON here")
    parser.add_argument(
        "--skip-mesh-to-volume",
        action="store_true",
        help="time hyvox only (the add-on's own share; Mesh to Volume takes minutes)",
    )
    add_out_argument(parser)
    return parser.parse_args(argv)


def enable_addon(build):
    import addon_utils

    sys.path.insert(0, os.path.join(os.path.abspath(build), "addon"))
    if addon_utils.enable("hyvox_blender", default_set=True, handle_error=None) is None:
        raise SystemExit(f"could not enable hyvox_blender from {build}/addon")


def suzanne(level):
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    bpy.ops.mesh.primitive_monkey_add(size=2.0)
    obj = bpy.context.active_object
    obj.name = f"Suzanne_L{level}"
    modifier = obj.modifiers.new("Subdivision", "SUBSURF")
    modifier.levels = level
    bpy.ops.object.modifier_apply(modifier=modifier.name)
    obj.data.calc_loop_triangles()
    return obj, len(obj.data.loop_triangles)


def time_hyvox(obj, voxel_size, method, out):
    bpy.context.view_layer.objects.active = obj
    for o in bpy.context.view_layer.objects:
        o.select_set(o is obj)
    from hyvox_blender.blender import operators

    # The export's CPU time too (the process's, all threads; the export runs alone on the main
    # thread before voxelizing): on a loaded machine its wall time mostly measures the scheduler.
    export_frame, export_cpu = operators._Run.export_frame, []

    def timed_export(run, frame):
        start_cpu = time.process_time()
        try:
            return export_frame(run, frame)
        finally:
            export_cpu.append((time.process_time() - start_cpu) * 1000.0)

    operators._Run.export_frame = timed_export
    try:
        start = time.perf_counter()
        # A surface, like the Mesh to Volume band it is compared with (the default Mode is Solid).
        bpy.ops.object.hyvox_voxelize(voxel_size=voxel_size, method=method, output_dir=out, mode="conservative")
        total = (time.perf_counter() - start) * 1000.0
    finally:
        operators._Run.export_frame = export_frame
    record = dict(operators.last_run_record)
    timings = dict(record["timings_ms"], export_cpu=sum(export_cpu))
    return total, timings, record["volumes"][0]["voxel_counts"][0]


def time_mesh_to_volume(obj, voxel_size):
    target, modifier = mesh_to_volume(obj, voxel_size)
    if hasattr(modifier, "use_fill_volume"):
        modifier.use_fill_volume = False  # surface band, like hyvox
    if hasattr(modifier, "exterior_band_width"):
        modifier.exterior_band_width = voxel_size
    start = time.perf_counter()
    evaluated = target.evaluated_get(bpy.context.evaluated_depsgraph_get()).data
    ms = (time.perf_counter() - start) * 1000.0
    assert len(evaluated.grids) >= 1, "Mesh to Volume produced no grid"
    volume = target.data
    bpy.data.objects.remove(target, do_unlink=True)
    bpy.data.volumes.remove(volume)
    return ms


def _ms(value):
    """Milliseconds for the table; '-' where Mesh to Volume was skipped."""
    return "-" if value is None else f"{value:.0f}"


def _speedup(value):
    return "-" if value is None else f"{value:.1f}x"


def main():
    args = parse_args()
    enable_addon(args.build)
    rows = []
    with tempfile.TemporaryDirectory(prefix="hyvox-bench-") as out:
        for level in [int(x) for x in args.levels.split(",")]:
            obj, triangles = suzanne(level)
            extent = max(obj.dimensions)
            for resolution in [int(x) for x in args.resolutions.split(",")]:
                voxel_size = extent / resolution
                runs = [time_hyvox(obj, voxel_size, args.method, out) for _ in range(args.repeat)]
                m2v = (
                    None
                    if args.skip_mesh_to_volume
                    else [time_mesh_to_volume(obj, voxel_size) for _ in range(args.repeat)]
                )
                best = min(runs, key=lambda r: r[0])
                row = {
                    "level": level,
                    "triangles": triangles,
                    "resolution": resolution,
                    "voxel_size": voxel_size,
                    "method": args.method,
                    "hyvox_ms": statistics.median(r[0] for r in runs),
                    "mesh_to_volume_ms": statistics.median(m2v) if m2v else None,
                    "voxels": best[2],
                    "breakdown_ms": best[1],
                    # The add-on's own overhead (export + import) as a share of each run's total.
                    "addon_share": statistics.median((r[1]["export"] + r[1]["import"]) / r[1]["total"] for r in runs),
                    "export_cpu_ms": statistics.median(r[1]["export_cpu"] for r in runs),
                }
                row["speedup"] = row["mesh_to_volume_ms"] / row["hyvox_ms"] if m2v else None
                rows.append(row)
                print(
                    f"L{level} {resolution}: hyvox {row['hyvox_ms']:.0f} ms, "
                    f"Mesh to Volume {_ms(row['mesh_to_volume_ms'])} ms",
                    flush=True,
                )

    print(
        f"\nBlender {bpy.app.version_string}, {os.cpu_count()} CPUs, hyvox method {args.method}, "
        f"median of {args.repeat}, load average {os.getloadavg()[0]:.1f}"
    )
    print(
        "| mesh | triangles | res | hyvox operator ms | Mesh to Volume ms | speed-up | "
        "export | voxelize | write | import | add-on share | export CPU | voxels |"
    )
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        b = r["breakdown_ms"]
        print(
            f"| Suzanne L{r['level']} | {r['triangles']:,} | {r['resolution']} | {r['hyvox_ms']:.0f} | "
            f"{_ms(r['mesh_to_volume_ms'])} | {_speedup(r['speedup'])} | {b['export']:.0f} | "
            f"{b['voxelize']:.0f} | {b['write']:.0f} | {b['import']:.0f} | {100 * r['addon_share']:.0f}% | "
            f"{r['export_cpu_ms']:.0f} | {r['voxels']:,} |"
        )
    table = Table(
        "blender_addon",
        "The add-on end to end against Blender's Mesh to Volume",
        [
            Column("mesh"),
            Column("triangles"),
            Column("res"),
            Column("hyvox operator ms", 0),
            Column("Mesh to Volume ms", 0),
            Column("Mesh to Volume / hyvox", 1),
            Column("export ms", 0),
            Column("voxelize ms", 0),
            Column("write ms", 0),
            Column("import ms", 0),
            Column("add-on share %", 0),
            Column("export CPU ms", 0),
            Column("voxels"),
        ],
        command=shlex.join([os.path.basename(sys.argv[0])] + sys.argv[1:]),
    )
    table.note(
        f"Blender {bpy.app.version_string}, hyvox method {args.method}, medians of {args.repeat}; "
        "the stages are the fastest run's; add-on share: (export + import) / the operator's total; both "
        "sides make a surface from the same modifier-applied mesh."
    )
    for r in rows:
        b = r["breakdown_ms"]
        table.add(
            [
                f"Suzanne L{r['level']}",
                r["triangles"],
                r["resolution"],
                r["hyvox_ms"],
                r["mesh_to_volume_ms"],
                r["speedup"],
                b["export"],
                b["voxelize"],
                b["write"],
                b["import"],
                100 * r["addon_share"],
                r["export_cpu_ms"],
                r["voxels"],
            ]
        )
    table.write(args.out)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=2)


if __name__ == "__main__":
    exit_1_on_error(main)
