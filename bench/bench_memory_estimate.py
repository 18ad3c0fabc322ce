# SPDX-License-Identifier: GPL-3.0-or-later
"""The memory estimate against the memory used: `hyvox voxelize` (cpu, writing its .vdb) over
shared meshes at 1024-8192, surface and solid, with and without colour; for each run the peak
resident memory (/usr/bin/time -f %M), the estimate voxelize() made before any work (the
stats' memory_estimate: its largest pass), and the base (the mesh voxelized at resolution 8,
conservative: the process, its libraries and the mesh, which the estimate leaves out). The estimate holds
when base + estimate is at least the peak and at most 1.5 times it.

    python3 bench/bench_memory_estimate.py --cli BUILD/hyvox [--resolutions 1024,2048,4096,8192]
        [--meshes ../shared/data/meshes] [--out bench/results] [--only dragon,sponza]

Writes OUT/memory_estimate.json and OUT/memory_estimate.md."""

import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))

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
    parser.add_argument("--out", default=os.path.join(HERE, "results"))
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
    header = (
        f"Memory estimate against the peak resident memory of `hyvox voxelize` (cpu, writing the .vdb), "
        f"{platform.node()}, {os.cpu_count()} cores, `python3 bench/bench_memory_estimate.py "
        f"--resolutions {args.resolutions}`. base: the mesh at resolution 8, conservative (process and mesh); "
        f"ratio: (base + estimate) / peak, which should lie in [1, 1.5]."
    )
    lines = [
        "| mesh | mode | colour | res | peak MiB | base MiB | estimate MiB | ratio | largest pass | "
        "leaves (est.) | s |",
        "|---|---|---|---:|---:|---:|---:|---:|---|---|---:|",
    ]
    for r in rows:
        if "refused" in r:
            lines.append(
                f"| {r['mesh']} | {r['mode']} | {'yes' if r['colour'] else 'no'} | {r['resolution']} | "
                f"{r['peak_mib']:.0f} | {r['base_mib']:.0f} | refused | | | | {r['seconds']:.1f} |"
            )
            continue
        largest = max(r["passes_mib"], key=r["passes_mib"].get)
        lines.append(
            f"| {r['mesh']} | {r['mode']} | {'yes' if r['colour'] else 'no'} | {r['resolution']} | "
            f"{r['peak_mib']:.0f} | {r['base_mib']:.0f} | {r['estimate_mib']:.0f} | {r['ratio']:.2f} | "
            f"{largest} | {r['leaves']} ({r['leaves_estimated']}) | {r['seconds']:.1f} |"
        )
    text = header + "\n\n" + "\n".join(lines) + "\n"
    print(text)
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "memory_estimate.md"), "w") as f:
        f.write(text)
    with open(os.path.join(args.out, "memory_estimate.json"), "w") as f:
        json.dump({"command": " ".join(sys.argv), "rows": rows}, f, indent=1)
    bad = [r for r in rows if "ratio" in r and not 1.0 <= r["ratio"] <= 1.5]
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
