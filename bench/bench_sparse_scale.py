# SPDX-License-Identifier: GPL-3.0-or-later
"""Benchmark (not a test): how the sparse, tiled voxelizer scales with resolution.

    python3 bench/bench_sparse_scale.py --build build [--res 1024,2048,4096,8192] \\
        [--methods cpu] [--dense-up-to 4096] [--json FILE] [--plot FILE.png] [--out DIR] MESH...

Each run is the CLI (`hyvox voxelize MESH -o OUT.vdb --stats-json`) in its own process, so
its peak RSS (from wait4) is its own. Per run: the stages (read, voxelize incl. tiles,
building the OpenVDB grid, writing the file), output voxels, leaves, tiles, peak RSS, the
OpenVDB grid's own memory (Grid::memUsage, the `vdb_bytes` the CLI reports) and time per
output voxel. "dense" runs the same with one tile over the whole grid (--tile-size = the
longest side and a budget that admits it): the memory of the old dense bit grid.
--plot draws peak memory against resolution (needs matplotlib). The table also goes to
DIR/sparse_scale[_METHODS].{json,md} (default bench/results/)."""

import argparse
import json
import os
import pathlib
import subprocess
import sys
import tempfile
import time

from bench_results import Column, Table, add_out_argument

MIB = 1 << 20
COLUMNS = [
    Column("mesh"),
    Column("res"),
    Column("method"),
    Column("tiling"),
    Column("read ms", 0),
    Column("voxelize ms", 0),
    Column("build grid ms", 0),
    Column("write ms", 0),
    Column("voxels"),
    Column("leaves"),
    Column("tiles"),
    Column("peak RSS MiB", 0),
    Column("float grid MiB", 0),
    Column("RSS / grid", 2),
    Column("ns / voxel", 0),
]


def run_cli(cli, mesh, res, method, extra, out_dir):
    vdb, stats_path = out_dir / "out.vdb", out_dir / "stats.json"
    args = [
        cli,
        "voxelize",
        mesh,
        "-o",
        str(vdb),
        "--resolution",
        str(res),
        "--method",
        method,
        "--stats-json",
        str(stats_path),
        "-q",
    ] + extra
    start = time.perf_counter()
    process = subprocess.Popen(args, stderr=subprocess.PIPE, text=True)
    _, status, usage = os.wait4(process.pid, 0)
    wall = time.perf_counter() - start
    error = process.stderr.read().strip()
    process.stderr.close()
    if os.waitstatus_to_exitcode(status) != 0:
        return {"error": error.splitlines()[0] if error else f"exit {status}"}
    stats = json.loads(stats_path.read_text())
    vdb.unlink()
    return {"stats": stats, "rss_mib": usage.ru_maxrss / 1024, "wall_s": wall}


def row(mesh, res, method, kind, result):
    base = {"mesh": pathlib.Path(mesh).name.split(".")[0], "res": res, "method": method, "kind": kind}
    if "error" in result:
        return {**base, "error": result["error"]}
    s, t = result["stats"], result["stats"]["timings_ms"]
    voxelize_ms = sum(v for k, v in t.items() if k not in ("read_mesh", "build_vdb", "write_vdb"))
    return {
        **base,
        "read_ms": t.get("read_mesh", 0),
        "voxelize_ms": voxelize_ms,
        "build_vdb_ms": t.get("build_vdb", 0),
        "write_ms": t.get("write_vdb", 0),
        "wall_s": result["wall_s"],
        "voxels": s["voxel_count"],
        "leaves": s["leaves"],
        "tiles": s["tiles"],
        "rss_mib": result["rss_mib"],
        "vdb_mib": s.get("vdb_bytes", 0) / MIB,
        "ns_per_voxel": 1e6 * (voxelize_ms + t.get("build_vdb", 0)) / max(s["voxel_count"], 1),
    }


def table_row(r):
    """The row as the results' table holds it (a refused run: its message in the read column)."""
    if "error" in r:
        return [r["mesh"], r["res"], r["method"], r["kind"], "refused: " + r["error"]] + [None] * (len(COLUMNS) - 5)
    return [
        r["mesh"],
        r["res"],
        r["method"],
        r["kind"],
        r["read_ms"],
        r["voxelize_ms"],
        r["build_vdb_ms"],
        r["write_ms"],
        r["voxels"],
        r["leaves"],
        r["tiles"],
        r["rss_mib"],
        r["vdb_mib"],
        r["rss_mib"] / max(r["vdb_mib"], 1e-9),
        r["ns_per_voxel"],
    ]


def print_row(r):
    if "error" in r:
        print(f"{r['mesh']:>10} {r['res']:>5} {r['method']:>7} {r['kind']:>6}  refused: {r['error']}", flush=True)
        return
    print(
        f"{r['mesh']:>10} {r['res']:>5} {r['method']:>7} {r['kind']:>6} {r['read_ms']:>8.0f} {r['voxelize_ms']:>9.0f} "
        f"{r['build_vdb_ms']:>8.0f} {r['write_ms']:>8.0f} {r['voxels']:>12} {r['leaves']:>9} {r['tiles']:>6} "
        f"{r['rss_mib']:>8.0f} {r['vdb_mib']:>8.0f} {r['rss_mib'] / max(r['vdb_mib'], 1e-9):>6.2f} "
        f"{r['ns_per_voxel']:>7.1f}",
        flush=True,
    )


def read_m2v_table(path):
    """(mesh, res) -> peak RSS MiB of OpenVDB's side, from bench_mesh_to_volume's printed table."""
    rss = {}
    for line in pathlib.Path(path).read_text().splitlines():
        words = line.split()
        if len(words) >= 12 and words[1].isdigit() and words[-1] == "MiB":
            rss[(words[0].split(".")[0], int(words[1]))] = float(words[-2])
    return rss


def plot(rows, path, m2v=None):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.5))
    for key in sorted({(r["mesh"], r["kind"]) for r in rows}):
        points = [(r["res"], r["rss_mib"]) for r in rows if (r["mesh"], r["kind"]) == key and "rss_mib" in r]
        if points:
            ax.plot(*zip(*points), marker="o", label=f"{key[0]} hyvox {key[1]} {rows[0]['method']} (peak RSS)")
    for mesh in sorted({r["mesh"] for r in rows}):
        points = [
            (r["res"], r["vdb_mib"]) for r in rows if r["mesh"] == mesh and r["kind"] == "sparse" and "vdb_mib" in r
        ]
        if points:
            ax.plot(*zip(*points), linestyle=":", marker="x", label=f"{mesh} OpenVDB float grid (memUsage)")
    for mesh in sorted({r["mesh"] for r in rows}):
        dense = sorted({r["res"] for r in rows if r["mesh"] == mesh})
        ax.plot(dense, [r**3 / 8 / MIB for r in dense], linestyle="--", color="grey", linewidth=0.8)
        points = sorted((res, mib) for (name, res), mib in (m2v or {}).items() if name == mesh)
        if points:
            ax.plot(*zip(*points), marker="s", label=f"{mesh} OpenVDB meshToUnsignedDistanceField (peak RSS)")
    ax.plot([], [], linestyle="--", color="grey", label="dense bit grid of the box (the old path's budget)")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("voxels along the longest side")
    ax.set_ylabel("MiB")
    ax.set_title("Peak memory of a CLI run vs resolution (cpu method)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("meshes", nargs="*")
    parser.add_argument("--build", default="build")
    parser.add_argument("--res", default="1024,2048,4096,8192")
    parser.add_argument("--methods", default="cpu")
    parser.add_argument("--dense-up-to", type=int, default=0, help="also run one whole-grid tile up to this resolution")
    parser.add_argument("--budget-mib", type=int, default=16384)
    parser.add_argument("--json")
    parser.add_argument("--plot")
    parser.add_argument("--m2v-log", help="bench_mesh_to_volume's printed table, for OpenVDB's peak RSS in the plot")
    parser.add_argument("--from-json", help="plot the rows of an earlier --json instead of running")
    add_out_argument(parser)
    args = parser.parse_args()
    cli = str(pathlib.Path(args.build) / "hyvox")
    m2v = read_m2v_table(args.m2v_log) if args.m2v_log else None
    if args.from_json:
        plot(json.loads(pathlib.Path(args.from_json).read_text()), args.plot, m2v)
        return
    rows = []
    table = Table(
        "sparse_scale" + ("" if args.methods == "cpu" else "_" + args.methods.replace(",", "_")),
        "Large grids: the sparse, tiled voxelizer from the CLI, end to end",
        COLUMNS,
    )
    table.note(
        f"One CLI process per row (`hyvox voxelize --memory-budget-mib {args.budget_mib}`), its peak RSS "
        "from wait4; float grid: the OpenVDB grid's own memory (Grid::memUsage); ns / voxel: voxelize + "
        "build grid per output voxel. tiling dense: one tile over the whole grid."
    )
    print(
        f"{'mesh':>10} {'res':>5} {'method':>7} {'kind':>6} {'read':>8} {'voxelize':>9} {'vdb':>8} {'write':>8} "
        f"{'voxels':>12} {'leaves':>9} {'tiles':>6} {'RSS MiB':>8} {'VDB MiB':>8} {'RSS/VDB':>6} {'ns/vox':>7}"
    )
    with tempfile.TemporaryDirectory(prefix="hyvox-scale-") as tmp:
        out_dir = pathlib.Path(tmp)
        for mesh in args.meshes:
            for res in [int(r) for r in args.res.split(",")]:
                for method in args.methods.split(","):
                    budget = ["--memory-budget-mib", str(args.budget_mib)]
                    result = row(mesh, res, method, "sparse", run_cli(cli, mesh, res, method, budget, out_dir))
                    rows.append(result)
                    print_row(result)
                    table.add(table_row(result))
                    if res <= args.dense_up_to:
                        dense = [
                            "--tile-size",
                            str(res),
                            "--memory-budget-mib",
                            str(max(args.budget_mib, 4 * res**3 // 8 // MIB + 64)),
                        ]
                        result = row(mesh, res, method, "dense", run_cli(cli, mesh, res, method, dense, out_dir))
                        rows.append(result)
                        print_row(result)
                        table.add(table_row(result))
    table.write(args.out)
    if args.json:
        pathlib.Path(args.json).write_text(json.dumps(rows, indent=1))
    if args.plot:
        plot(rows, args.plot, m2v)


if __name__ == "__main__":
    sys.exit(main())
