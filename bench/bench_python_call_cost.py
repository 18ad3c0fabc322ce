# SPDX-License-Identifier: GPL-3.0-or-later
"""What hyvox.voxelize costs around its native stages, one Python process per build.

For each build, alternating, `--calls` calls of hyvox.voxelize on a mesh read by
hyvox.read_mesh before each call (fresh arrays, as bench_vs_cuda_voxelizer.py does):
the call's CPU time (time.process_time), the sum of its stats' stage timings (wall, the
native work the CLI times too), its minor page faults and system CPU (getrusage). With
--threads 1 the CPU time minus the stage sum is what the Python call adds.

    /usr/bin/python3 bench/bench_python_call_cost.py --build build --baseline OTHER_BUILD \\
        --mesh /tmp/dragon_stanford_871k.ply --res 128 --threads 1 --calls 20 --rounds 2

The rounds' figures also go to DIR/python_call_cost.{json,md} (--out DIR, default bench/results/).
"""

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import time

from bench_results import Column, Table, add_out_argument


def measure(build, mesh, res, threads, calls):
    sys.path.insert(0, os.path.join(os.path.abspath(build), "python"))
    import hyvox

    rows = []
    for _ in range(calls):
        vertices, triangles = hyvox.read_mesh(mesh)
        usage_before = resource.getrusage(resource.RUSAGE_SELF)
        cpu_before = time.process_time()
        grid = hyvox.voxelize(vertices, triangles, method="cpu", resolution=res, threads=threads)
        cpu_ms = (time.process_time() - cpu_before) * 1e3
        usage_after = resource.getrusage(resource.RUSAGE_SELF)
        rows.append(
            {
                "cpu": cpu_ms,
                "stages": sum(grid.stats["timings_ms"].values()),
                "faults": usage_after.ru_minflt - usage_before.ru_minflt,
                "sys": (usage_after.ru_stime - usage_before.ru_stime) * 1e3,
            }
        )
        del grid, vertices, triangles
    rows = rows[1:]  # the first call also starts the thread pool
    print(
        f"{build}: call CPU median {statistics.median(r['cpu'] for r in rows):.1f} ms (min {min(r['cpu'] for r in rows):.1f}), "
        f"stages' sum min {min(r['stages'] for r in rows):.1f} ms, minor faults {statistics.median(r['faults'] for r in rows):.0f}, "
        f"system CPU median {statistics.median(r['sys'] for r in rows):.1f} ms"
    )
    # The parent collects one line of figures per process for the results' table.
    print(
        "FIGURES "
        + json.dumps(
            [
                build,
                statistics.median(r["cpu"] for r in rows),
                min(r["cpu"] for r in rows),
                min(r["stages"] for r in rows),
                statistics.median(r["faults"] for r in rows),
                statistics.median(r["sys"] for r in rows),
            ]
        ),
        flush=True,
    )


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build")
    parser.add_argument("--baseline", help="another build folder, measured alternately")
    parser.add_argument("--mesh", required=True)
    parser.add_argument("--res", type=int, default=128)
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--calls", type=int, default=20)
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("--one", help=argparse.SUPPRESS)  # internal: measure this build in this process
    add_out_argument(parser)
    args = parser.parse_args()
    if args.one:
        measure(args.one, args.mesh, args.res, args.threads, args.calls)
        return
    if not args.build:
        parser.error("--build is required")
    print(f"load average {os.getloadavg()[0]:.1f}")
    table = Table(
        "python_call_cost",
        f"What hyvox.voxelize costs around its stages: {os.path.basename(args.mesh)} at {args.res}",
        [
            Column("build"),
            Column("call CPU median ms", 1),
            Column("call CPU min ms", 1),
            Column("stages' sum min ms", 1),
            Column("minor faults", 0),
            Column("system CPU median ms", 1),
        ],
    )
    table.note(
        f"One process per build and round ({args.rounds} rounds), {args.calls} calls each (the first "
        f"left out), threads {args.threads}."
    )
    builds = [b for b in (args.baseline, args.build) if b]
    for _ in range(args.rounds):
        for build in builds:  # one process per build: the modules cannot share one
            done = subprocess.run(
                [
                    sys.executable,
                    __file__,
                    "--one",
                    build,
                    "--mesh",
                    args.mesh,
                    "--res",
                    str(args.res),
                    "--threads",
                    str(args.threads),
                    "--calls",
                    str(args.calls),
                ],
                check=True,
                capture_output=True,
                text=True,
            )
            for line in done.stdout.splitlines():
                if line.startswith("FIGURES "):
                    table.add(json.loads(line[len("FIGURES ") :]))
                else:
                    print(line, flush=True)
    print(f"load average {os.getloadavg()[0]:.1f}")
    table.write(args.out)


if __name__ == "__main__":
    main()
