# SPDX-License-Identifier: GPL-3.0-or-later
"""Benchmark (not a test): whole `hyvox voxelize` processes of two or more builds, alternating,
one fresh process per run. Each round starts only once the machine was idle for a moment (both
cores at least 95% idle over 0.3 s), so that a shared machine's other work disturbs fewer runs;
it may still start during a round, hence the quantiles. Prints per build the wall time (spawn
to reap: start, stages and exit) and the process's CPU time (its rusage: all threads).

    /usr/bin/python3 bench/bench_cli_ab.py BASE/hyvox build/hyvox --mesh /tmp/bunny.ply --res 128

The table also goes to DIR/cli_ab.{json,md} (--out DIR, default bench/results/).
"""

import argparse
import os
import statistics
import time

from bench_results import Column, Table, add_out_argument


def cpu_times():
    values = list(map(int, open("/proc/stat").readline().split()[1:]))
    return sum(values), values[3] + values[4]  # all, idle + iowait


def wait_until_idle(limit_s):
    give_up = time.time() + limit_s
    while time.time() < give_up:
        before = cpu_times()
        time.sleep(0.3)
        after = cpu_times()
        if (after[1] - before[1]) / max(1, after[0] - before[0]) >= 0.95:
            return True
    return False


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("binaries", nargs="+", help="hyvox executables to compare")
    parser.add_argument("--mesh", required=True)
    parser.add_argument("--res", default="128")
    parser.add_argument("--runs", type=int, default=40)
    parser.add_argument(
        "--vdb-prefix", default="/tmp/hyvox_cli_ab", help="the runs' output prefix (one .vdb per binary)"
    )
    parser.add_argument("--idle-wait", type=float, default=60, help="seconds to wait for an idle machine per round")
    parser.add_argument("--extra", default="", help="more voxelize options, e.g. '--threads 1'")
    add_out_argument(parser)
    args = parser.parse_args()
    extra = args.extra.split()
    wall = {b: [] for b in args.binaries}
    cpu = {b: [] for b in args.binaries}
    devnull = os.open(os.devnull, os.O_WRONLY)
    skipped = 0
    for round_number in range(args.runs):
        if not wait_until_idle(args.idle_wait):
            skipped += 1
            continue
        order = args.binaries if round_number % 2 == 0 else args.binaries[::-1]
        for binary in order:
            out = f"{args.vdb_prefix}.{args.binaries.index(binary)}.vdb"
            argv = [binary, "voxelize", args.mesh, "-o", out, "--resolution", args.res, "--method", "cpu", "-q", *extra]
            start = time.perf_counter()
            pid = os.posix_spawn(binary, argv, os.environ, file_actions=[(os.POSIX_SPAWN_DUP2, devnull, 2)])
            _, status, usage = os.wait4(pid, 0)
            wall[binary].append((time.perf_counter() - start) * 1e3)
            cpu[binary].append((usage.ru_utime + usage.ru_stime) * 1e3)
            if status != 0:
                raise SystemExit(f"{binary} failed (status {status})")
    print(
        f"{os.path.basename(args.mesh)} at {args.res}: {len(wall[args.binaries[0]])} rounds "
        f"({skipped} skipped: never idle), load now {os.getloadavg()[0]:.2f}"
    )
    print("| build | wall p10 | wall p30 | wall median | wall p70 | CPU median |")
    print("|---|---:|---:|---:|---:|---:|")
    table = Table(
        "cli_ab",
        f"Whole CLI processes of two builds: {os.path.basename(args.mesh)} at {args.res}",
        [
            Column("build"),
            Column("wall p10 ms", 2),
            Column("wall p30 ms", 2),
            Column("wall median ms", 2),
            Column("wall p70 ms", 2),
            Column("CPU median ms", 2),
        ],
    )
    table.note(
        f"{len(wall[args.binaries[0]])} rounds, each started once the machine was idle "
        f"({skipped} skipped: never idle); the builds alternate."
    )
    for binary in args.binaries:
        if len(wall[binary]) < 2:
            continue
        q = statistics.quantiles(wall[binary], n=10)
        print(
            f"| {binary} | {q[0]:.2f} | {q[2]:.2f} | {statistics.median(wall[binary]):.2f} | {q[6]:.2f} | "
            f"{statistics.median(cpu[binary]):.2f} |"
        )
        table.add([binary, q[0], q[2], statistics.median(wall[binary]), q[6], statistics.median(cpu[binary])])
    table.write(args.out)


if __name__ == "__main__":
    main()
