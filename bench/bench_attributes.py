# SPDX-License-Identifier: GPL-3.0-or-later
"""The price of colour: binary vs colour vs colour + normal voxelization, side by side in one run.

    PYTHONPATH=build/python /usr/bin/python3 bench/bench_attributes.py [--resolutions 256,512]
        [--repeats 3] [--methods cpu] [--mesh-dir ../shared/data/meshes] [--threads N] [--cpu-time]
        [--mode conservative|solid] [--out DIR]

Sponza (vertex colours) and Spot (UVs + 1024² texture). Each line: median wall time of the
voxelize() call (the .vdb is not written) for each variant, runs interleaved so a busy
machine slows all alike, and the ratios to binary, after one untimed binary run (shader
compiles, hybrid's cutoff search). `--methods triangle,fragment,hybrid` prices the GL
methods' colour (pairs clipped on the GPU, summed on the CPU). Target (issue 12): cpu colour + normal at
512 under 2x binary. `--methods cpu,tessellation` adds the tessellation (gamma 2), whose
colour is the mean of its points' values (its tiles shrink so that every brick's sums fit one
storage block: llvmpipe's 128 MiB cuts Sponza at 256 into several); a row that does not fit
the device says so and the bench goes on. `--cpu-time` times the process's CPU time instead
of the wall (with `--threads 1`: the work itself, steadier than the wall on a shared machine).
`--mode solid` prices colour in solid mode (every variant solid; the colour + normal run's
stages `attributes` (the surface's values) and `attributes_inside` (the inside's, by layers)
are printed in ms). The table also goes to DIR/attributes_MODE[_METHODS].{json,md} (default
bench/results/).
"""

import argparse
import pathlib
import statistics
import time

import numpy as np

import hyvox
from bench_results import Column, Table, add_out_argument


def scenes(mesh_dir: pathlib.Path):
    v, t, attrs = hyvox.read_mesh(mesh_dir / "sponza_crytek_262k_vcolor.ply.gz", attributes=True)
    yield "sponza vertex colours", v, t, {"colors": (attrs["colors"][:, :3] * 255).round().astype(np.uint8)}
    v, t, attrs = hyvox.read_mesh(mesh_dir / "spot_uv.ply", attributes=True)
    yield "spot texture", v, t, {"uvs": attrs["uvs"], "texture": mesh_dir / "spot_texture.png"}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--mesh-dir",
        type=pathlib.Path,
        default=pathlib.Path(__file__).resolve().parents[2] / "shared" / "data" / "meshes",
    )
    parser.add_argument("--resolutions", default="256,512")
    parser.add_argument("--methods", default="cpu")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--threads", type=int, default=0, help="voxelize's threads (0: all cores)")
    parser.add_argument("--cpu-time", action="store_true", help="time the process's CPU time, not the wall")
    parser.add_argument("--mode", default="conservative", help="the mode of every variant (conservative, solid)")
    add_out_argument(parser)
    args = parser.parse_args()
    clock = time.process_time if args.cpu_time else time.perf_counter
    variants = {"binary": None, "color": "color", "color+normal": "color,normal"}
    print(
        f"hyvox {hyvox.__version__}; mode {args.mode}; median of {args.repeats} "
        f"({'CPU' if args.cpu_time else 'wall'} seconds, threads {args.threads or 'all'}), ratio to binary"
    )
    result_name = f"attributes_{args.mode}" + ("" if args.methods == "cpu" else "_" + args.methods.replace(",", "_"))
    table = Table(
        result_name,
        f"The price of colour: binary, colour, colour + normal ({args.mode})",
        [Column("scene"), Column("method"), Column("res")]
        + [Column(f"{variant} s", 3) for variant in variants]
        + [
            Column("colour / binary", 2),
            Column("colour + normal / binary", 2),
            Column("voxels"),
            Column("surface values ms", 0),
            Column("inside values ms", 0),
        ],
        extra_machine={"gpu": "EGL: " + ", ".join(d.name for d in hyvox.gl_devices())}
        if args.methods != "cpu"
        else None,
    )
    table.note(
        f"Medians of {args.repeats} {'CPU' if args.cpu_time else 'wall'} seconds of the voxelize() call "
        f"(threads {args.threads or 'all'}), the variants interleaved; surface / inside values: the "
        "colour + normal run's attribute stages (the inside's only in solid mode)."
    )
    print(
        f"{'scene':24} {'method':12} {'res':>5} "
        + " ".join(f"{name:>13}" for name in variants)
        + f" {'color/bin':>10} {'c+n/bin':>8} {'voxels':>10} {'surface ms':>10} {'inside ms':>10}"
    )
    for name, v, t, sources in scenes(args.mesh_dir):
        for method in args.methods.split(","):
            for resolution in (int(r) for r in args.resolutions.split(",")):
                times = {variant: [] for variant in variants}
                voxels = 0
                try:
                    # Untimed first: shader compiles and hybrid's cutoff search (cached per mesh and grid).
                    hyvox.voxelize(v, t, resolution=resolution, method=method, threads=args.threads, mode=args.mode)
                    stages = {}
                    for _ in range(args.repeats):
                        for variant, attributes in variants.items():
                            extra = dict(sources, attributes=attributes) if attributes else {}
                            start = clock()
                            grid = hyvox.voxelize(
                                v,
                                t,
                                resolution=resolution,
                                method=method,
                                threads=args.threads,
                                mode=args.mode,
                                **extra,
                            )
                            times[variant].append(clock() - start)
                            voxels = grid.voxel_count
                            if variant == "color+normal":
                                for stage in ("attributes", "attributes_inside"):
                                    stages.setdefault(stage, []).append(grid.stats["timings_ms"].get(stage, 0.0))
                except hyvox.ResourceError as error:
                    print(f"{name:24} {method:12} {resolution:5} does not fit: {error}", flush=True)
                    table.note(f"{name}, {method} at {resolution}: does not fit ({error}).")
                    continue
                median = {variant: statistics.median(values) for variant, values in times.items()}
                print(
                    f"{name:24} {method:12} {resolution:5} "
                    + " ".join(f"{median[variant]:13.3f}" for variant in variants)
                    + f" {median['color'] / median['binary']:10.2f} {median['color+normal'] / median['binary']:8.2f}"
                    f" {voxels:10}" + "".join(f" {statistics.median(stages[s]):10.0f}" for s in stages),
                    flush=True,
                )
                table.add(
                    [name, method, resolution]
                    + [median[variant] for variant in variants]
                    + [median["color"] / median["binary"], median["color+normal"] / median["binary"], voxels]
                    + [
                        statistics.median(stages["attributes"]),
                        statistics.median(stages["attributes_inside"]) if args.mode == "solid" else None,
                    ]
                )
    table.write(args.out)


if __name__ == "__main__":
    main()
