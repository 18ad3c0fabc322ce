# SPDX-License-Identifier: GPL-3.0-or-later
"""CPU time of one `hyvox.voxelize` call (method cpu), two builds side by side.

On a shared machine wall times mostly measure the scheduler; the CPU time of the call
(`time.process_time()`: validate, the voxelize stage, compact and count, all threads) does
not. Each round runs one fresh Python process per build (alternating), which voxelizes once to
warm up and then `--calls` times; the figures are medians over the calls, then over the rounds.

    /usr/bin/python3 bench/bench_voxelize_cpu_time.py --build build --baseline /tmp/main_build \\
        --meshes bunny_stanford_69k.ply,dragon_stanford_res2_203k.ply.gz --res 128,512 --threads 1

The table also goes to DIR/voxelize_cpu_time.{json,md} (--out DIR, default bench/results/).
"""

import argparse
import os
import statistics
import subprocess
import sys

from bench_results import Column, Table, add_out_argument

HERE = os.path.dirname(os.path.abspath(__file__))

ONE_BUILD = r"""
import sys, time, statistics
sys.path.insert(0, sys.argv[1])
import hyvox
vertices, triangles = hyvox.read_mesh(sys.argv[2])
res, threads, calls = int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5])
hyvox.voxelize(vertices, triangles, method="cpu", resolution=res, threads=threads)
cpu, stage, covered = [], [], 0
for _ in range(calls):
    start = time.process_time()
    grid = hyvox.voxelize(vertices, triangles, method="cpu", resolution=res, threads=threads)
    cpu.append((time.process_time() - start) * 1e3)
    stage.append(grid.stats["timings_ms"]["voxelize"])
    covered = grid.stats["cpu"].get("triangles_already_covered", 0)
print(statistics.median(cpu), statistics.median(stage), covered, len(triangles))
"""


def parse_args():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--build", required=True, help="build folder whose python/ holds the module")
    p.add_argument("--baseline", required=True, help="another build (or a copy of its python/ folder's parent)")
    p.add_argument("--mesh-dir", default=os.path.join(HERE, "..", "..", "shared", "data", "meshes"))
    p.add_argument("--meshes", default="bunny_stanford_69k.ply,dragon_stanford_res2_203k.ply.gz")
    p.add_argument("--res", default="128,512")
    p.add_argument("--threads", type=int, default=1)
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--calls", type=int, default=7)
    add_out_argument(p)
    return p.parse_args()


def run_build(build, mesh, res, args):
    out = subprocess.run(
        [
            sys.executable,
            "-c",
            ONE_BUILD,
            os.path.join(os.path.abspath(build), "python"),
            mesh,
            str(res),
            str(args.threads),
            str(args.calls),
        ],
        capture_output=True,
        text=True,
        check=True,
    )
    cpu, stage, covered, triangles = out.stdout.split()
    return float(cpu), float(stage), int(covered), int(triangles)


def main():
    args = parse_args()
    print(
        "| mesh | res | threads | base CPU ms | CPU ms | base / this | base stage ms | stage ms | skipped triangles | load |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|")
    table = Table(
        "voxelize_cpu_time",
        "CPU time of one voxelize() call, two builds side by side",
        [
            Column("mesh"),
            Column("res"),
            Column("threads"),
            Column("base CPU ms", 1),
            Column("CPU ms", 1),
            Column("base / this", 2),
            Column("base stage ms", 1),
            Column("stage ms", 1),
            Column("skipped triangles"),
            Column("triangles"),
            Column("load", 2),
        ],
    )
    table.note(
        f"Medians over {args.calls} calls per process and {args.rounds} rounds of fresh processes, the "
        f"builds alternating; base: {args.baseline}."
    )
    for name in args.meshes.split(","):
        mesh = os.path.join(args.mesh_dir, name)
        for res in [int(r) for r in args.res.split(",")]:
            runs = {"base": [], "this": []}
            for _ in range(args.rounds):
                runs["base"].append(run_build(args.baseline, mesh, res, args))
                runs["this"].append(run_build(args.build, mesh, res, args))
            cpu = {k: statistics.median(r[0] for r in v) for k, v in runs.items()}
            stage = {k: statistics.median(r[1] for r in v) for k, v in runs.items()}
            covered, triangles = runs["this"][-1][2], runs["this"][-1][3]
            print(
                f"| {name} | {res} | {args.threads} | {cpu['base']:.1f} | {cpu['this']:.1f} | "
                f"{cpu['base'] / cpu['this']:.2f} | {stage['base']:.1f} | {stage['this']:.1f} | "
                f"{covered} of {triangles} | {os.getloadavg()[0]:.2f} |",
                flush=True,
            )
            table.add(
                [
                    name,
                    res,
                    args.threads,
                    cpu["base"],
                    cpu["this"],
                    cpu["base"] / cpu["this"],
                    stage["base"],
                    stage["this"],
                    covered,
                    triangles,
                    os.getloadavg()[0],
                ]
            )
    table.write(args.out)


if __name__ == "__main__":
    main()
