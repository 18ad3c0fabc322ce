# SPDX-License-Identifier: GPL-3.0-or-later
"""Benchmark (not a test): the costs of a CLI run that do not grow with the resolution, stage by
stage, for one or more hyvox builds side by side (e.g. a copy of the build before a change):

    /usr/bin/python3 bench/bench_fixed_costs.py BASE/hyvox build/hyvox \\
        [--meshes dragon_stanford_871k.ply.gz] [--res 32,256,512,1024] [--modes conservative,solid] \\
        [--runs 5] [--threads 0] [--labels before,after] [--name fixed_costs] [--out DIR]

Each run is one fresh `hyvox voxelize --method cpu --stats-json` process; the builds alternate
within each round. Per build, mesh, resolution and mode: the medians of the stages the CLI's
stats name (read_mesh, validate: the checks and the grid's planning, edges: solid mode's edge
check, voxelize, write_vdb), of their sum, and of the whole process's wall and CPU time (its
rusage: all threads). The meshes are read from a plain copy in a temporary folder (.ply.gz
unpacked), made as the comparison with cuda_voxelizer makes it. The table goes to DIR/NAME.{json,md} (default
bench/results/fixed_costs).
"""

import argparse
import json
import os
import statistics
import tempfile
import time

from bench_results import Column, Table, add_out_argument
from bench_vs_cuda_voxelizer import plain_copy

HERE = os.path.dirname(os.path.abspath(__file__))
STAGES = ("read_mesh", "validate", "edges", "voxelize", "write_vdb")


def run_once(binary, mesh, res, mode, threads, work):
    stats_path = os.path.join(work, "stats.json")
    argv = [binary, "voxelize", mesh, "-o", os.path.join(work, "out.vdb"), "--method", "cpu", "-q"]
    argv += ["--resolution", str(res), "--mode", mode, "--threads", str(threads), "--stats-json", stats_path]
    devnull = os.open(os.devnull, os.O_WRONLY)
    start = time.perf_counter()
    pid = os.posix_spawn(binary, argv, os.environ, file_actions=[(os.POSIX_SPAWN_DUP2, devnull, 2)])
    _, status, usage = os.wait4(pid, 0)
    wall = (time.perf_counter() - start) * 1e3
    os.close(devnull)
    if status != 0:
        raise SystemExit(f"{binary} failed on {mesh} at {res} (status {status})")
    with open(stats_path, encoding="utf-8") as f:
        timings = json.load(f)["timings_ms"]
    return timings, wall, (usage.ru_utime + usage.ru_stime) * 1e3


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("binaries", nargs="+", help="hyvox executables to compare")
    parser.add_argument("--mesh-dir", default=os.path.join(HERE, "..", "..", "shared", "data", "meshes"))
    parser.add_argument("--meshes", default="dragon_stanford_871k.ply.gz")
    parser.add_argument("--res", default="32,256,512,1024")
    parser.add_argument(
        "--modes", default="conservative", help="--mode values: conservative (the surface), thin, solid"
    )
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--threads", type=int, default=0, help="hyvox --threads (0 = all)")
    parser.add_argument("--labels", help="a comma list naming the builds in the table (default: their paths)")
    parser.add_argument("--name", default="fixed_costs", help="the table's name: DIR/NAME.{json,md}")
    add_out_argument(parser)
    args = parser.parse_args()

    columns = [Column("build"), Column("mesh"), Column("res"), Column("mode")]
    columns += [Column(f"{stage} ms", 1) for stage in STAGES]
    columns += [Column("stages ms", 1), Column("process ms", 1), Column("process CPU ms", 1)]
    labels = dict(zip(args.binaries, args.labels.split(",") if args.labels else args.binaries))
    table = Table(args.name, "The costs around the voxelizer, stage by stage", columns)
    with tempfile.TemporaryDirectory(prefix="hyvox_fixed_costs_") as work:
        for name in args.meshes.split(","):
            mesh = plain_copy(args.mesh_dir, name, work)
            for mode in args.modes.split(","):
                for res in map(int, args.res.split(",")):
                    got = {b: {"stages": {}, "wall": [], "cpu": []} for b in args.binaries}
                    for _ in range(args.runs):
                        for binary in args.binaries:
                            timings, wall, cpu = run_once(binary, mesh, res, mode, args.threads, work)
                            record = got[binary]
                            for stage in (*STAGES, "total"):
                                value = sum(timings.values()) if stage == "total" else timings.get(stage)
                                record["stages"].setdefault(stage, []).append(value)
                            record["wall"].append(wall)
                            record["cpu"].append(cpu)
                    for binary in args.binaries:
                        record = got[binary]
                        medians = [
                            None if None in values else statistics.median(values)
                            for values in (record["stages"][s] for s in (*STAGES, "total"))
                        ]
                        row = [labels[binary], name.split(".")[0], res, mode, *medians]
                        row += [statistics.median(record["wall"]), statistics.median(record["cpu"])]
                        table.add(row)
                        print(
                            " | ".join("" if v is None else f"{v:.1f}" if isinstance(v, float) else str(v) for v in row)
                        )
    table.note(
        f"Medians of {args.runs} runs, the builds alternating within each round; hyvox --threads {args.threads} "
        "(0: all cores), --method cpu. validate: the mesh's checks and the grid's planning (the tiles, the memory "
        "estimate); edges: solid mode's edge check (empty: a build that counts it in validate, or a surface mode)."
    )
    table.write(args.out)


if __name__ == "__main__":
    main()
