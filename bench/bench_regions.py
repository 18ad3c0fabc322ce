# SPDX-License-Identifier: GPL-3.0-or-later
"""Benchmark (not a test): one grid voxelized as a job of regions (docs/regions.md) against
the one-machine run: each task's peak memory and wall time, and the merge's.

    python3 bench/bench_regions.py --build build [--res 4096] [--regions 4] [--mesh MESH]
        [--out bench/results] [-- VOXELIZE OPTIONS...]

Every task is the CLI in its own process under `/usr/bin/time -f "%e %M"` (wall seconds,
peak resident KiB): `hyvox voxelize MESH -o whole.vdb --resolution R`, then for K = 0..N-1
`hyvox voxelize MESH -o part_K.vdb --resolution R --region K/N`, then `hyvox merge part_*.vdb
-o merged.vdb`. The merged file is checked against the whole run's (the same bytes but the
file's random UUID). Writes OUT/regions.json and OUT/regions.md and prints the table; the
.vdb files are removed. Default: the 871k dragon's surface at 4096."""

import argparse
import json
import pathlib
import subprocess
import sys
import tempfile

from bench_results import Column, Table, add_out_argument

REPO = pathlib.Path(__file__).resolve().parents[1]
MIB = 1 << 20
UUID = slice(21, 57)  # the .vdb header's random UUID


def timed(args):
    """(wall s, peak RSS MiB, stdout) of one command under /usr/bin/time."""
    done = subprocess.run(["/usr/bin/time", "-f", "%e %M", *map(str, args)], capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"failed ({done.returncode}): {' '.join(map(str, args))}\n{done.stderr}")
    wall, kib = done.stderr.strip().splitlines()[-1].split()
    return float(wall), int(kib) / 1024, done.stdout


def same_but_uuid(a, b):
    x, y = bytearray(a.read_bytes()), bytearray(b.read_bytes())
    x[UUID] = y[UUID] = b""
    return x == y


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=str(REPO / "build"), help="the build folder (its hyvox CLI)")
    parser.add_argument("--res", type=int, default=4096)
    parser.add_argument("--regions", type=int, default=4)
    parser.add_argument(
        "--mesh", default=str(REPO.parent / "shared" / "data" / "meshes" / "dragon_stanford_871k.ply.gz")
    )
    add_out_argument(parser)
    parser.add_argument("options", nargs="*", help="further voxelize options (after --), e.g. --mode solid")
    args = parser.parse_args()
    cli = pathlib.Path(args.build) / "hyvox"
    mesh = pathlib.Path(args.mesh)
    common = ["--resolution", args.res, "-q", *args.options]
    rows = []
    with tempfile.TemporaryDirectory(prefix="hyvox-regions-") as folder:
        folder = pathlib.Path(folder)

        def voxelize(name, *extra):
            stem = name.replace(" ", "_").replace("/", "of")
            out, stats = folder / f"{stem}.vdb", folder / f"{stem}.json"
            wall, rss, _ = timed([cli, "voxelize", mesh, "-o", out, "--stats-json", stats, *common, *extra])
            s = json.loads(stats.read_text())
            rows.append(
                {
                    "task": name,
                    "wall_s": wall,
                    "peak_rss_mib": rss,
                    "voxels": s["voxel_count"],
                    "leaves": s["leaves"],
                    "file_mib": out.stat().st_size / MIB,
                    "box": s.get("region") and [s["region"]["lo"], s["region"]["hi"]],
                    "dims": s["dims"],
                }
            )
            print(f"{name:>10} {wall:8.2f} s {rss:9.1f} MiB {s['voxel_count']:>12} voxels", flush=True)
            return out

        whole = voxelize("whole")
        parts = [voxelize(f"part {k}/{args.regions}", "--region", f"{k}/{args.regions}") for k in range(args.regions)]
        merged = folder / "merged.vdb"
        wall, rss, _ = timed([cli, "merge", *parts, "-o", merged, "-q"])
        rows.append(
            {
                "task": "merge",
                "wall_s": wall,
                "peak_rss_mib": rss,
                "voxels": rows[0]["voxels"],
                "leaves": rows[0]["leaves"],
                "file_mib": merged.stat().st_size / MIB,
                "box": None,
                "dims": rows[0]["dims"],
            }
        )
        print(f"{'merge':>10} {wall:8.2f} s {rss:9.1f} MiB", flush=True)
        identical = same_but_uuid(whole, merged)

    part_rows = rows[1:-1]
    largest_part = max(r["peak_rss_mib"] for r in part_rows) / rows[0]["peak_rss_mib"]
    table = Table(
        "regions",
        f"Regions of one grid: {mesh.name} at {args.res}, {args.regions} regions",
        [
            Column("task"),
            Column("box (voxels lo..hi)"),
            Column("wall s", 2),
            Column("peak RSS MiB", 1),
            Column("RSS / whole", 2),
            Column("voxels"),
            Column("leaves"),
            Column("file MiB", 1),
        ],
    )
    for r in rows:
        box = "-" if not r["box"] else f"{r['box'][0]}..{r['box'][1]}"
        table.add(
            [
                r["task"],
                box,
                r["wall_s"],
                r["peak_rss_mib"],
                r["peak_rss_mib"] / rows[0]["peak_rss_mib"],
                r["voxels"],
                r["leaves"],
                r["file_mib"],
            ]
        )
    table.note(
        'One process per task (`/usr/bin/time -f "%e %M"`). Merged file equals the whole run\'s (bytes but '
        f"the UUID): {'yes' if identical else 'NO'}. Parts: {sum(r['wall_s'] for r in part_rows):.2f} s of "
        f"tasks in all, the longest {max(r['wall_s'] for r in part_rows):.2f} s; the largest part's peak "
        f"memory is {largest_part:.2f} of the whole run's."
    )
    table.write(args.out)
    if not identical:
        sys.exit("the merged file differs from the whole run's")


if __name__ == "__main__":
    main()
