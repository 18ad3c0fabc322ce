# SPDX-License-Identifier: GPL-3.0-or-later
"""Benchmark (not a test): hyvox's CLI `voxelize --method cpu` side by side with
cuda_voxelizer's OpenMP CPU path (`-cpu -o binvox`), and hyvox's Python call
(`hyvox.read_mesh` + `hyvox.voxelize` + `VoxelGrid.write_vdb`) beside the CLI's stages.

    /usr/bin/python3 bench/bench_vs_cuda_voxelizer.py --peer PATH/TO/cuda_voxelizer \\
        [--build build] [--runs 3] [--res 128,256,512,1024] [--meshes a.ply,b.ply.gz] \\
        [--threads 0] [--csv out.csv] [--no-python] [--baseline OTHER_BUILD] [--out DIR]

The peer is not part of hyvox: build it yourself (its CPU path needs no CUDA) and pass the
binary. Both programs read the same plain binary PLY: .ply.gz meshes are unpacked into a
temporary folder first, and the peer writes its .binvox there (beside its input). Each run is
one fresh process; the runs of both programs alternate, and every figure is a median of
--runs. Whole process = wall clock around the process, as a user waits for it.

Columns (ms, medians):
  hyvox read / vox / vdb / stages: the CLI's stats JSON: read_mesh, the voxelize stage
      alone, build_vdb + write_vdb, and the sum of all stages; hyvox proc: whole process.
  peer vox / peer proc: the peer's printed "CPU voxelization time"; whole process.
  x proc, x vox: peer / hyvox (above 1: hyvox is faster).
  py read / py vox / py vdb / py sum: the Python call in this process, with the mesh read
      by hyvox.read_mesh, the voxelize call and write_vdb each timed; py/cli = py sum /
      the CLI's stages sum.
  base stages / base proc / x base: with --baseline, another hyvox build (e.g. a copy of
      the build before a change) run in the same alternation: its stages sum and whole
      process, and base proc / hyvox proc (above 1: this build is faster).
  load: the 1-minute load average when the row finished (the machine may be shared).
The table also goes to DIR/vs_cuda_voxelizer.{json,md} (default bench/results/).
"""

import argparse
import csv
import gzip
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

from bench_results import Column, Table, add_out_argument

DEFAULT_MESHES = [
    "bunny_stanford_69k.ply",
    "dragon_stanford_res3_48k.ply",
    "dragon_stanford_res2_203k.ply.gz",
    "dragon_stanford_871k.ply.gz",
    "sponza_crytek_262k_vcolor.ply.gz",
]
HERE = os.path.dirname(os.path.abspath(__file__))


def parse_args():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--peer", required=True, help="the cuda_voxelizer binary (built with its CPU path)")
    parser.add_argument("--build", default=os.path.join(HERE, "..", "build"), help="hyvox build folder")
    parser.add_argument(
        "--mesh-dir",
        default=os.environ.get("HYVOX_MESH_DIR", os.path.join(HERE, "..", "..", "shared", "data", "meshes")),
    )
    parser.add_argument("--meshes", default=",".join(DEFAULT_MESHES))
    parser.add_argument("--res", default="128,256,512,1024")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument(
        "--threads", type=int, default=0, help="hyvox --threads and the peer's OMP_NUM_THREADS (0 = all)"
    )
    parser.add_argument("--csv", help="also write the rows here")
    parser.add_argument("--no-python", action="store_true", help="skip the Python-call columns")
    parser.add_argument("--baseline", help="another hyvox build folder to time beside this one (before/after)")
    add_out_argument(parser)
    return parser.parse_args()


def plain_copy(mesh_dir, name, work):
    """The mesh as a plain binary PLY in `work` (the peer reads no .gz)."""
    source = os.path.join(mesh_dir, name)
    target = os.path.join(work, name[:-3] if name.endswith(".gz") else name)
    if not os.path.exists(target):
        if name.endswith(".gz"):
            with gzip.open(source, "rb") as src, open(target, "wb") as dst:
                shutil.copyfileobj(src, dst)
        else:
            shutil.copyfile(source, target)
    return target


def timed_run(command, env):
    start = time.perf_counter()
    done = subprocess.run(command, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    elapsed = (time.perf_counter() - start) * 1000.0
    if done.returncode != 0:
        raise SystemExit(f"failed ({done.returncode}): {' '.join(command)}\n{done.stdout}\n{done.stderr}")
    return elapsed, done.stdout


def run_hyvox(hyvox, mesh, res, threads, work, env):
    out = os.path.join(work, "hyvox.vdb")
    stats_path = os.path.join(work, "hyvox.json")
    proc_ms, _ = timed_run(
        [
            hyvox,
            "voxelize",
            mesh,
            "-o",
            out,
            "--method",
            "cpu",
            "--resolution",
            str(res),
            "--threads",
            str(threads),
            "--stats-json",
            stats_path,
            "-q",
        ],
        env,
    )
    with open(stats_path) as f:
        stats = json.load(f)
    t = stats["timings_ms"]
    return {
        "read": t["read_mesh"],
        "vox": t["voxelize"],
        "vdb": t["build_vdb"] + t["write_vdb"],
        "stages": sum(t.values()),
        "proc": proc_ms,
        "voxels": stats["voxel_count"],
    }


def run_peer(peer, mesh, res, env):
    proc_ms, out = timed_run([peer, "-f", mesh, "-s", str(res), "-cpu", "-o", "binvox"], env)
    vox = re.search(r"CPU voxelization time: ([0-9.]+) ms", out)
    total = re.search(r"Total runtime: ([0-9.]+) ms", out)
    if not vox or not total:
        raise SystemExit("the peer printed no voxelization/total time:\n" + out)
    return {"vox": float(vox.group(1)), "total": float(total.group(1)), "proc": proc_ms}


def run_python(hyvox_module, mesh, res, threads, work):
    out = os.path.join(work, "python.vdb")
    start = time.perf_counter()
    vertices, triangles = hyvox_module.read_mesh(mesh)
    read = time.perf_counter()
    grid = hyvox_module.voxelize(vertices, triangles, method="cpu", resolution=res, threads=threads)
    voxelized = time.perf_counter()
    grid.write_vdb(out, threads)
    written = time.perf_counter()
    return {
        "read": (read - start) * 1e3,
        "vox": (voxelized - read) * 1e3,
        "vdb": (written - voxelized) * 1e3,
        "sum": (written - start) * 1e3,
    }


def median_of(rows, key):
    return statistics.median(r[key] for r in rows)


def main():
    args = parse_args()
    hyvox = os.path.join(args.build, "hyvox")
    env = dict(os.environ)
    if args.threads > 0:
        env["OMP_NUM_THREADS"] = str(args.threads)
    hyvox_module = None
    if not args.no_python:
        sys.path.insert(0, os.path.join(os.path.abspath(args.build), "python"))
        import hyvox as hyvox_module  # noqa: E402 (the build's module)
    columns = [
        "mesh",
        "res",
        "voxels",
        "hyvox read",
        "hyvox vox",
        "hyvox vdb",
        "hyvox stages",
        "hyvox proc",
        "peer vox",
        "peer proc",
        "x proc",
        "x vox",
        "py read",
        "py vox",
        "py vdb",
        "py sum",
        "py/cli",
        "py first",
    ]
    if args.baseline:
        columns += ["base stages", "base proc", "x base"]
    columns.append("load")
    rows = []
    ratios = ("x proc", "x vox", "py/cli", "x base", "load")
    table = Table(
        "vs_cuda_voxelizer",
        "End to end against cuda_voxelizer's CPU path",
        [Column(c, 2 if c in ratios else 1) for c in columns],
    )
    table.note(
        f"ms, medians of {args.runs} runs, one fresh process each, the contenders alternating; x proc / x "
        "vox: the peer's time over hyvox's (above 1: hyvox is faster); py: read_mesh + voxelize + write_vdb "
        "in one Python process, after three untimed calls at the size."
    )
    print("| " + " | ".join(columns) + " |")
    print("|" + "---|" * len(columns))
    with tempfile.TemporaryDirectory(prefix="hyvox_bench_") as work:
        for name in args.meshes.split(","):
            mesh = plain_copy(args.mesh_dir, name, work)
            if hyvox_module is not None:  # the first call pays for loading OpenVDB and the thread pool
                run_python(hyvox_module, mesh, 64, args.threads, work)
            for res in [int(r) for r in args.res.split(",")]:
                ours, peers, pys, bases = [], [], [], []
                # A session's first call at a new size is slower: glibc maps each large block
                # afresh (every page faulted in) until freeing blocks of that size has raised its
                # mmap threshold above them, about three calls (the bunny at 256: 21.9, 19.9,
                # 18.3, then 10.3-10.9 ms). The first is reported on its own ("py first"); "py
                # sum" is the calls after three, as a script or Blender session makes them.
                first_py = None
                if hyvox_module is not None:
                    first_py = run_python(hyvox_module, mesh, res, args.threads, work)
                    for _ in range(2):
                        run_python(hyvox_module, mesh, res, args.threads, work)
                contenders = [
                    lambda: ours.append(run_hyvox(hyvox, mesh, res, args.threads, work, env)),
                    lambda: peers.append(run_peer(args.peer, mesh, res, env)),
                ]
                if args.baseline:
                    contenders.append(
                        lambda: bases.append(
                            run_hyvox(os.path.join(args.baseline, "hyvox"), mesh, res, args.threads, work, env)
                        )
                    )
                if hyvox_module is not None:
                    contenders.append(lambda: pys.append(run_python(hyvox_module, mesh, res, args.threads, work)))
                for run in range(args.runs):
                    # Each run starts with the next contender: whoever runs right after the
                    # peer finds memory it has just used (its dense grid), which slowed the
                    # Python call that always ran after it by up to 2x at 1024.
                    for k in range(len(contenders)):
                        contenders[(run + k) % len(contenders)]()
                row = {"mesh": os.path.basename(mesh), "res": res, "voxels": ours[0]["voxels"]}
                for key in ("read", "vox", "vdb", "stages", "proc"):
                    row["hyvox " + key] = median_of(ours, key)
                row["peer vox"] = median_of(peers, "vox")
                row["peer proc"] = median_of(peers, "proc")
                row["x proc"] = row["peer proc"] / row["hyvox proc"]
                row["x vox"] = row["peer vox"] / row["hyvox vox"]
                for key in ("read", "vox", "vdb", "sum"):
                    row["py " + key] = median_of(pys, key) if pys else float("nan")
                row["py/cli"] = row["py sum"] / row["hyvox stages"]
                row["py first"] = first_py["sum"] if first_py else float("nan")
                if bases:
                    row["base stages"] = median_of(bases, "stages")
                    row["base proc"] = median_of(bases, "proc")
                    row["x base"] = row["base proc"] / row["hyvox proc"]
                row["load"] = os.getloadavg()[0]
                rows.append(row)
                cells = [
                    str(row[c])
                    if isinstance(row[c], (str, int))
                    else (f"{row[c]:.2f}" if c in ("x proc", "x vox", "py/cli", "x base", "load") else f"{row[c]:.1f}")
                    for c in columns
                ]
                print("| " + " | ".join(cells) + " |", flush=True)
                table.add([row[c] for c in columns])
    table.write(args.out)
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=columns)
            writer.writeheader()
            writer.writerows(rows)


if __name__ == "__main__":
    main()
