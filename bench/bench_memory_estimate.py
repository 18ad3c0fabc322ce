# SPDX-License-Identifier: GPL-3.0-or-later
"""The memory estimate against the memory used: `hyvox voxelize` (cpu, writing its .vdb) over
shared meshes at 1024-8192, surface and solid, with and without colour; for each run the peak
resident memory (/usr/bin/time -f %M), the estimate voxelize() made before any work (the
stats' memory_estimate: its largest pass), and the base (the mesh voxelized at resolution 8,
conservative: the process, its libraries and the mesh, which the estimate leaves out). The estimate holds
when base + estimate is at least the peak and at most 1.5 times it.

    python3 bench/bench_memory_estimate.py --cli BUILD/hyvox [--resolutions 1024,2048,4096,8192]
        [--meshes ../shared/data/meshes] [--out bench/results] [--only dragon,sponza]

Writes OUT/memory_estimate.json and .md (bench_results.py); exits 1 when a row's estimate does
not hold."""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from bench_results import Column, Table, add_out_argument  # noqa: E402

# (label, file, colour runs too, the highest resolution of its solid runs): closed and open
# meshes, small and large, with vertex colour. Sponza's solid (an open scene: fast winding
# numbers near 25000 open edges) takes minutes at 2048 on two cores: not above that.
MESHES = [
    ("dragon", "dragon_stanford_871k.ply.gz", False, 8192),
    ("bunny", "bunny_stanford_69k.ply", False, 8192),
    ("armadillo", "armadillo_52k.ply", False, 8192),
    ("sponza", "sponza_crytek_262k_vcolor.ply.gz", True, 2048),
    ("spot", "spot_vcolor.ply", True, 8192),
]


def run(cli, mesh, resolution, mode, colour, work):
    out, stats, timing = (os.path.join(work, n) for n in ("m.vdb", "m.json", "time.txt"))
    command = [
        "/usr/bin/time",
        "-o",
        timing,
        "-f",
        "%M",
        cli,
        "voxelize",
        mesh,
        "-o",
        out,
        "--resolution",
        str(resolution),
        "--mode",
        mode,
        "--method",
        "cpu",
        "-q",
        "--stats-json",
        stats,
    ]
    if colour:
        command += ["--attributes", "color"]
    start = time.time()
    done = subprocess.run(command, capture_output=True, text=True)
    seconds = time.time() - start
    peak = int(open(timing).read().split()[-1]) * 1024
    if done.returncode != 0:
        return {"peak": peak, "seconds": seconds, "refused": done.stderr.strip().splitlines()[-1]}
    with open(stats) as f:
        s = json.load(f)
    os.remove(out)
    return {
        "peak": peak,
        "seconds": seconds,
        "estimate": s["memory_estimate"],
        "leaves": s["leaves"],
        "voxels": s["voxel_count"],
        "tile_bricks": s.get("solid", {}).get("tile_bricks", 0),
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--cli", required=True)
    parser.add_argument("--meshes", default=os.path.join(HERE, "..", "..", "shared", "data", "meshes"))
    parser.add_argument("--resolutions", default="1024,2048,4096,8192")
    add_out_argument(parser)
    parser.add_argument("--only", default="", help="comma list of mesh labels")
    args = parser.parse_args()
    only = set(args.only.split(",")) if args.only else None
    rows = []
    mib = lambda b: b / 2**20
    with tempfile.TemporaryDirectory() as work:
        for label, file, has_colour, solid_limit in MESHES:
            if only and label not in only:
                continue
            mesh = os.path.join(args.meshes, file)
            base = run(args.cli, mesh, 8, "conservative", False, work)["peak"]
            for mode in ("conservative", "solid"):
                for colour in (False, True) if has_colour else (False,):
                    for resolution in map(int, args.resolutions.split(",")):
                        if mode == "solid" and resolution > solid_limit:
                            continue
                        r = run(args.cli, mesh, resolution, mode, colour, work)
                        row = {
                            "mesh": label,
                            "mode": mode,
                            "colour": colour,
                            "resolution": resolution,
                            "base_mib": mib(base),
                            "peak_mib": mib(r["peak"]),
                            "seconds": r["seconds"],
                        }
                        if "refused" in r:
                            row["refused"] = r["refused"]
                        else:
                            e = r["estimate"]
                            row.update(
                                estimate_mib=mib(e["peak"]),
                                ratio=(base + e["peak"]) / r["peak"],
                                passes_mib={
                                    k: mib(e[k])
                                    for k in ("surface_pass", "solid_pass", "attribute_values", "vdb_write")
                                },
                                leaves=r["leaves"],
                                leaves_estimated=e["surface_leaves"],
                                tile_bricks=r["tile_bricks"],
                                inside_bricks_estimated=e["inside_bricks"],
                            )
                        rows.append(row)
                        print(json.dumps(row), flush=True)
    table = Table(
        "memory_estimate",
        "The memory estimate against the memory used",
        [
            Column("mesh"),
            Column("mode"),
            Column("colour"),
            Column("res"),
            Column("peak MiB", 0),
            Column("base MiB", 0),
            Column("estimate MiB", 0),
            Column("(base + estimate) / peak", 2),
            Column("largest pass"),
            Column("leaves"),
            Column("leaves estimated"),
            Column("s", 1),
        ],
    )
    for r in rows:
        largest = max(r["passes_mib"], key=r["passes_mib"].get) if "passes_mib" in r else "refused"
        table.add(
            [
                r["mesh"],
                r["mode"],
                "yes" if r["colour"] else "no",
                r["resolution"],
                r["peak_mib"],
                r["base_mib"],
                r.get("estimate_mib"),
                r.get("ratio"),
                largest,
                r.get("leaves"),
                int(r["leaves_estimated"]) if "leaves_estimated" in r else None,
                r["seconds"],
            ]
        )
    table.note(
        "`hyvox voxelize`, cpu, writing the .vdb, one process per row; peak: its peak resident memory "
        "(`/usr/bin/time -f %M`); base: the same mesh at resolution 8, conservative (the process, its "
        "libraries and the mesh, which the estimate leaves out); the estimate is the largest of its passes, "
        "made before any work. It holds when (base + estimate) / peak lies in [1, 1.5]."
    )
    table.write(args.out)
    bad = [r for r in rows if "ratio" in r and not 1.0 <= r["ratio"] <= 1.5]
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
