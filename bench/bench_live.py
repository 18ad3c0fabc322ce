# SPDX-License-Identifier: GPL-3.0-or-later
"""Benchmark (not a test): Live's edit-to-new-voxels latency against Blender's own live
volume paths, in official Blender 5.0 (the bpy module of the test venvs):

    build/venv/bpy50/bin/python bench/bench_live.py --build build \\
        [--meshes suzanne4,bunny,spot,dragon] [--resolutions 128,256,512] [--modes solid,surface] \\
        [--edits 5] [--animation-frames 24] [--out bench/results]

For each mesh and resolution, one edit after the other (a vertex moved by a tenth of a
voxel, alternately up and down), the time from the edit until the new grid is loaded in the
evaluated volume (view_layer.update() returns, then the evaluated volume's `density` grid
loads), median of the edits after one untimed warm-up edit:
- hyvox Live (Auto, so cpu on llvmpipe and hybrid on a hardware GPU), solid (Mode Solid,
  the add-on's default) and surface; where the update's time goes: export and
  swap (the main thread's part in the UI), key (hashing the input), voxelize, write, and
  Blender (its re-evaluation, the .vdb's load and the edit's own evaluation);
- Geometry Nodes' Mesh to Density Grid on another object (Object Info of the source), and
  the Mesh to Volume modifier, at the same voxel size and a band of one voxel (their defaults,
  0.2, are world units); both fill the inside, neither has a surface-only mode in 5.0.
Then the main thread's time per update for the 100k-triangle Buddha, and the animated
Suzanne (level 3, 64k triangles, a Wave modifier) at 128: new voxel frames a second when
frame_set() steps through the animation (background mode: each frame is voxelized
before frame_set() returns). Writes the tables as bench/results/live.{json,md} and
live_breakdown.{json,md} (bench_results.py)."""

import argparse
import os
import statistics
import sys
import tempfile
import time

import bpy
import numpy as np

sys.path[:0] = [
    os.path.dirname(os.path.abspath(__file__)),
    os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "demo"),
]
from bench_results import add_out_argument  # noqa: E402
import blender_bench  # noqa: E402
from run_demo import enable_addon, mesh_from_arrays  # noqa: E402  (the demo's scene helpers)

MESHES = {
    "suzanne4": "Suzanne, subdivision level 4",
    "bunny": "bunny_stanford_69k.ply",
    "spot": "spot_uv.ply + spot_texture.png (texture colour)",
    "dragon": "dragon_stanford_871k.ply.gz",
}


def parse_args():
    argv = sys.argv[1:]
    if "--" in argv:
        argv = argv[argv.index("--") + 1 :]
    parser = argparse.ArgumentParser(prog="bench_live.py")
    parser.add_argument("--build", default="build")
    parser.add_argument(
        "--mesh-dir",
        default=os.environ.get(
            "HYVOX_MESH_DIR",
            os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "data", "meshes"),
        ),
    )
    parser.add_argument("--meshes", default=",".join(MESHES))
    parser.add_argument("--resolutions", default="128,256,512")
    parser.add_argument("--modes", default="solid,surface")
    parser.add_argument("--edits", type=int, default=5, help="timed edits per case (after one warm-up)")
    parser.add_argument("--skip-blender", action="store_true", help="hyvox Live only")
    parser.add_argument("--animation-frames", type=int, default=24)
    add_out_argument(parser)
    return parser.parse_args(argv)


def addon(name):
    import importlib

    return importlib.import_module("hyvox_blender." + name)


# -- scenes -------------------------------------------------------------------------------
def clear():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for collection in (bpy.data.meshes, bpy.data.volumes, bpy.data.materials, bpy.data.images, bpy.data.node_groups):
        for block in list(collection):
            collection.remove(block)


def suzanne(level):
    bpy.ops.mesh.primitive_monkey_add(size=2.0)
    obj = bpy.context.active_object
    modifier = obj.modifiers.new("Subdivision", "SUBSURF")
    modifier.levels = level
    bpy.ops.object.modifier_apply(modifier=modifier.name)
    return obj


def spot(mesh_dir, hyvox):
    """Spot welded where its UV seams split it (closed), the texture as the Base Color."""
    vertices, triangles, attributes = hyvox.read_mesh(os.path.join(mesh_dir, "spot_uv.ply"), attributes=True)
    unique, index = np.unique(vertices, axis=0, return_inverse=True)
    obj = mesh_from_arrays("Spot", unique, index.reshape(-1)[triangles].astype(np.uint32))
    uv_layer = obj.data.uv_layers.new(name="UVMap")
    uv_layer.data.foreach_set("uv", attributes["uvs"][triangles.reshape(-1)].ravel())
    material = bpy.data.materials.new("Spot")
    material.use_nodes = True
    texture = material.node_tree.nodes.new("ShaderNodeTexImage")
    texture.image = bpy.data.images.load(os.path.join(mesh_dir, "spot_texture.png"))
    bsdf = material.node_tree.nodes["Principled BSDF"]
    material.node_tree.links.new(texture.outputs["Color"], bsdf.inputs["Base Color"])
    obj.data.materials.append(material)
    return obj


def make_source(name, mesh_dir, hyvox):
    if name == "suzanne4":
        return suzanne(4)
    if name == "spot":
        return spot(mesh_dir, hyvox)
    vertices, triangles = hyvox.read_mesh(os.path.join(mesh_dir, MESHES[name]))
    return mesh_from_arrays(name, vertices, triangles)


def triangle_count(obj):
    mesh = obj.evaluated_get(bpy.context.evaluated_depsgraph_get()).data
    return sum(len(p.vertices) - 2 for p in mesh.polygons)


def is_closed(obj):
    """No boundary edge (each edge in exactly two faces), as the solid mode's auto rule asks."""
    mesh = obj.data
    edges = np.empty(len(mesh.edges) * 2, np.int32)
    mesh.edges.foreach_get("vertices", edges)
    counts = np.zeros(len(mesh.edges), np.int64)
    keys = np.empty(len(mesh.loops), np.int32)
    mesh.loops.foreach_get("edge_index", keys)
    np.add.at(counts, keys, 1)
    return bool(np.all(counts == 2))


# -- the edit and the three ways to follow it ----------------------------------------------
class Edit:
    """Each edit moves another vertex by a tenth of a voxel: every edit is a new state (none
    comes from Live's cache)."""

    def __init__(self, obj, voxel_size):
        self.obj, self.step, self.count = obj, voxel_size * 0.1, 0

    def __call__(self):
        vertices = self.obj.data.vertices
        vertices[(self.count * 7919) % len(vertices)].co.z += self.step
        self.count += 1
        self.obj.data.update()


def timed_edits(edit, after, count):
    """Milliseconds from each edit until after() returned, one warm-up first."""
    times = []
    for index in range(count + 1):
        start = time.perf_counter()
        edit()
        bpy.context.view_layer.update()
        after()
        if index:
            times.append((time.perf_counter() - start) * 1000.0)
    return times


def loaded(volume_object):
    evaluated = volume_object.evaluated_get(bpy.context.evaluated_depsgraph_get())
    geometry = evaluated.evaluated_geometry()
    volume = geometry.volume if geometry is not None else None
    grids = volume.grids if volume is not None else evaluated.data.grids
    assert grids.load(), "the evaluated volume does not load"
    grid = grids.get("density") or (grids[0] if len(grids) else None)
    assert grid is not None and grid.load(), "no grid in the evaluated volume"


def hyvox_live(source, voxel_size, mode, colour, edits, out):
    for obj in bpy.context.scene.objects:
        obj.select_set(obj is source)
    bpy.context.view_layer.objects.active = source
    result = bpy.ops.object.hyvox_voxelize(
        voxel_size=voxel_size,
        mode="solid" if mode == "solid" else "conservative",
        color=colour,
        live=True,
        output_dir=out,
    )
    assert result == {"FINISHED"}, result
    volume = bpy.data.objects[source.name + "_voxels"]
    live = addon("blender.live.driver")
    ident = volume["hyvox_live_id"]
    stages = []

    def after():
        loaded(volume)
        stages.append(dict(live._Live.timings[ident]))

    latencies = timed_edits(Edit(source, voxel_size), after, edits)
    stages = stages[1:]
    method = volume.get("hyvox_method", "")
    voxels = addon("blender.operators").last_run_record["volumes"][0]["voxel_counts"][0]
    bpy.data.objects.remove(volume, do_unlink=True)
    bpy.context.view_layer.update()
    breakdown = {
        name: statistics.median(s.get(name, 0.0) for s in stages)
        for name in ("export", "key", "voxelize", "write", "swap")
    }
    breakdown["blender"] = statistics.median(
        lat - sum(s.get(n, 0.0) for n in ("export", "key", "voxelize", "write", "swap"))
        for lat, s in zip(latencies, stages)
    )
    return {
        "ms": statistics.median(latencies),
        "all_ms": latencies,
        "breakdown_ms": breakdown,
        "method": method,
        "voxels": voxels,
        "main_thread_ms": statistics.median(s["main"] for s in stages),
        "main_thread_cpu_ms": statistics.median(s["main_cpu"] for s in stages),
    }


def density_grid_node(source, voxel_size, edits):
    reader = bpy.data.objects.new("DensityGrid", bpy.data.meshes.new("DensityGrid"))
    bpy.context.scene.collection.objects.link(reader)
    tree = bpy.data.node_groups.new("Mesh to Density Grid", "GeometryNodeTree")
    tree.interface.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    info = tree.nodes.new("GeometryNodeObjectInfo")
    info.transform_space = "RELATIVE"
    info.inputs["Object"].default_value = source
    grid = tree.nodes.new("GeometryNodeMeshToDensityGrid")
    grid.inputs["Voxel Size"].default_value = voxel_size
    grid.inputs["Gradient Width"].default_value = voxel_size  # the default, 0.2, is in world units
    tree.links.new(info.outputs["Geometry"], grid.inputs["Mesh"])
    store = tree.nodes.new("GeometryNodeStoreNamedGrid")
    store.data_type = "FLOAT"
    store.inputs["Name"].default_value = "density"
    volume = tree.nodes.new("GeometryNodeVolumeCube")  # an empty volume to store the grid in
    volume.inputs["Resolution X"].default_value = volume.inputs["Resolution Y"].default_value = 2
    volume.inputs["Resolution Z"].default_value = 2
    tree.links.new(volume.outputs["Volume"], store.inputs["Volume"])
    tree.links.new(grid.outputs[0], store.inputs["Grid"])
    output = tree.nodes.new("NodeGroupOutput")
    tree.links.new(store.outputs["Volume"], output.inputs["Geometry"])
    reader.modifiers.new("Grid", "NODES").node_group = tree
    times = timed_edits(Edit(source, voxel_size), lambda: loaded(reader), edits)
    bpy.data.objects.remove(reader, do_unlink=True)
    bpy.data.node_groups.remove(tree)
    return statistics.median(times)


def mesh_to_volume(source, voxel_size, edits):
    target, _ = blender_bench.mesh_to_volume(source, voxel_size)
    times = timed_edits(Edit(source, voxel_size), lambda: loaded(target), edits)
    volume = target.data
    bpy.data.objects.remove(target, do_unlink=True)
    bpy.data.volumes.remove(volume)
    return statistics.median(times)


def animated_suzanne(mode, frames, out, resolution=128):
    clear()
    obj = suzanne(3)
    wave = obj.modifiers.new("Wave", "WAVE")
    wave.height, wave.width, wave.speed = 0.15, 0.6, 0.1
    scene = bpy.context.scene
    scene.frame_set(1)
    for o in bpy.context.scene.objects:
        o.select_set(o is obj)
    bpy.context.view_layer.objects.active = obj
    bpy.ops.object.hyvox_voxelize(
        resolution=resolution, mode="solid" if mode == "solid" else "conservative", live=True, output_dir=out
    )
    volume = bpy.data.objects[obj.name + "_voxels"]
    live = addon("blender.live.driver")
    ident = volume["hyvox_live_id"]
    before = live._Live.runs_started.get(ident, 0)
    start = time.perf_counter()
    for frame in range(2, frames + 2):
        scene.frame_set(frame)
    seconds = time.perf_counter() - start
    runs = live._Live.runs_started.get(ident, 0) - before
    assert runs == frames, f"{runs} runs for {frames} frames"
    triangles = triangle_count(obj)
    clear()
    return {"mode": mode, "frames": frames, "fps": frames / seconds, "triangles": triangles}


# -- the report ---------------------------------------------------------------------------
def speedup(live_row, node_ms):
    """How many times faster than the node Live is, or None."""
    return node_ms / live_row["ms"] if live_row is not None and node_ms else None


def targets_met(row):
    """The issue's targets: surface 10x the node everywhere; solid 10x on closed meshes,
    5x on open ones (their inside is the winding number's)."""
    checks = [
        (speedup(row.get("surface"), row.get("node_ms")), 10.0),
        (speedup(row.get("solid"), row.get("node_ms")), 10.0 if row["closed"] else 5.0),
    ]
    checks = [(value, target) for value, target in checks if value is not None]
    return None if not checks else all(value >= target for value, target in checks)


def tables(rows, main_thread, animation, edits):
    """The results: `live` (Live against Blender's own paths, the main thread and the animation
    as notes) and `live_breakdown` (where an update's time goes)."""
    from bench_results import Column, Table

    about = (
        f"Blender {bpy.app.version_string} (bpy module); median of {edits} edits after one warm-up; hyvox method Auto."
    )
    live = Table(
        "live",
        "Live against Blender's own live volumes (edit to new voxels)",
        [
            Column("mesh"),
            Column("triangles"),
            Column("closed"),
            Column("res"),
            Column("hyvox Live solid ms", 0),
            Column("hyvox Live surface ms", 0),
            Column("Mesh to Density Grid ms", 0),
            Column("Mesh to Volume ms", 0),
            Column("solid vs node"),
            Column("surface vs node"),
            Column("targets (solid, surface)"),
            Column("met"),
        ],
    )
    live.note(about)
    for r in rows:
        solid, surface, node = r.get("solid"), r.get("surface"), r.get("node_ms")

        def times(live_row):
            value = speedup(live_row, node)
            return None if value is None else f"{value:.1f}x"

        live.add(
            [
                r["mesh"],
                r["triangles"],
                r["closed"],
                r["resolution"],
                solid and solid["ms"],
                surface and surface["ms"],
                node,
                r.get("modifier_ms"),
                times(solid),
                times(surface),
                f"{10 if r['closed'] else 5}x, 10x",
                targets_met(r),
            ]
        )
    if main_thread:
        live.note(
            f"Main thread per update, {main_thread['mesh']} ({main_thread['triangles']:,} triangles, "
            f"surface at {main_thread['resolution']}): {main_thread['ms']:.1f} ms by the wall clock, "
            f"{main_thread['cpu_ms']:.1f} ms of its own CPU time (of which export "
            f"{main_thread['export_ms']:.1f}, swap {main_thread['swap_ms']:.1f}); target <= 10 ms: "
            f"{'met' if main_thread['ms'] <= 10 else 'not met'} by the wall clock, "
            f"{'met' if main_thread['cpu_ms'] <= 10 else 'not met'} in CPU time."
        )
    for x in animation:
        live.note(
            f"Animated Suzanne level 3 ({x['triangles']:,} triangles, Wave) at 128, {x['mode']}: "
            f"{x['fps']:.1f} new voxel frames a second over {x['frames']} frames; target >= 10: "
            f"{'met' if x['fps'] >= 10 else 'not met'}."
        )
    breakdown = Table(
        "live_breakdown",
        "Where a Live update's time goes",
        [Column("mesh"), Column("res"), Column("mode"), Column("method")]
        + [
            Column(name, 1)
            for name in (
                "export ms",
                "key ms",
                "voxelize ms",
                "write ms",
                "swap ms",
                "Blender ms",
                "total ms",
                "main thread ms",
                "main thread CPU ms",
            )
        ],
    )
    breakdown.note(
        about + " Medians. Main thread: what the UI's main thread spends (the export, the run's "
        "set-up, the swap; wall clock, and its own CPU time); Blender: its evaluation after the swap, "
        "which loads the new .vdb, and the edit's own."
    )
    for r in rows:
        for mode in ("solid", "surface"):
            x = r.get(mode)
            if x is None:
                continue
            b = x["breakdown_ms"]
            breakdown.add(
                [
                    r["mesh"],
                    r["resolution"],
                    mode,
                    x["method"],
                    b["export"],
                    b["key"],
                    b["voxelize"],
                    b["write"],
                    b["swap"],
                    b["blender"],
                    x["ms"],
                    x["main_thread_ms"],
                    x["main_thread_cpu_ms"],
                ]
            )
    return [live, breakdown]


def main():
    args = parse_args()
    bpy.ops.wm.read_factory_settings(use_empty=True)
    enable_addon(args.build)
    hyvox = addon("core.backend").load_module()
    modes = [m for m in args.modes.split(",") if m]
    rows, animation, main_thread = [], [], None
    with tempfile.TemporaryDirectory(prefix="hyvox-bench-live-") as out:
        for name in [m for m in args.meshes.split(",") if m]:
            clear()
            source = make_source(name, args.mesh_dir, hyvox)
            triangles, closed = triangle_count(source), is_closed(source)
            extent = max(source.dimensions)
            for resolution in [int(x) for x in args.resolutions.split(",")]:
                voxel_size = extent / resolution
                row = {
                    "mesh": name,
                    "triangles": triangles,
                    "closed": closed,
                    "resolution": resolution,
                    "voxel_size": voxel_size,
                }
                for mode in modes:
                    row[mode] = hyvox_live(source, voxel_size, mode, name == "spot", args.edits, out)
                    print(
                        f"{name} {resolution} hyvox {mode}: {row[mode]['ms']:.0f} ms {row[mode]['breakdown_ms']}",
                        flush=True,
                    )
                if not args.skip_blender:
                    row["node_ms"] = density_grid_node(source, voxel_size, args.edits)
                    row["modifier_ms"] = mesh_to_volume(source, voxel_size, args.edits)
                    print(
                        f"{name} {resolution}: Mesh to Density Grid {row['node_ms']:.0f} ms, "
                        f"Mesh to Volume {row['modifier_ms']:.0f} ms",
                        flush=True,
                    )
                rows.append(row)
        # The main thread's share for 100k triangles: the Buddha (exactly 100,000).
        clear()
        vertices, triangles = hyvox.read_mesh(os.path.join(args.mesh_dir, "happy_buddha_100k.ply"))
        buddha = mesh_from_arrays("Buddha", vertices, triangles)
        result = hyvox_live(buddha, max(buddha.dimensions) / 256, "surface", False, args.edits, out)
        main_thread = {
            "mesh": "happy_buddha_100k",
            "triangles": len(triangles),
            "resolution": 256,
            "ms": result["main_thread_ms"],
            "cpu_ms": result["main_thread_cpu_ms"],
            "export_ms": result["breakdown_ms"]["export"],
            "swap_ms": result["breakdown_ms"]["swap"],
        }
        print(f"main thread per update, 100k triangles: {main_thread}", flush=True)
        for mode in modes:
            animation.append(animated_suzanne(mode, args.animation_frames, out))
            print(f"animated Suzanne {mode}: {animation[-1]['fps']:.1f} frames/s", flush=True)
    for table in tables(rows, main_thread, animation, args.edits):
        table.write(args.out)


if __name__ == "__main__":
    blender_bench.exit_1_on_error(main)
    sys.stdout.flush()
    os._exit(0)
