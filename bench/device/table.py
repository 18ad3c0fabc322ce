#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Turns bench_device's CSV into Markdown tables beside the JCGT 2013 paper's Table 1 (GTX 480,
thin binary voxelization into a dense 3D texture; ms), printed and, with --out DIR, written as
results (DIR/device_table1, device_attributes, device_threads .json and .md) for
docs/benchmarks.md.

    python3 bench/device/table.py table1.csv [--info gl_info.txt] [--device device.txt]
                                  [--res 128,256,512,1024] [--mode thin] [--out DIR]

Table 1: per scene and resolution the GPU times (GL timer queries, pass 1 + pass 2; medians)
of triangle, fragment and hybrid @ its auto cutoff with the pass split, the tessellation
method's GPU time and bias, the cpu method's own stage, each method's check against cpu, and
the paper's figures for the matching scene with paper hybrid / our hybrid ("x paper").
Then the thread scaling of the cpu method (threads@RES steps), if the run got that far.
Standard library only (runs on the device machine's python3 as well).
"""

import argparse
import csv
import os
import sys

# bench_results.py: beside this script in the folder pack.sh makes, one folder up in the checkout.
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [HERE, os.path.dirname(HERE)]
from bench_results import Column, Table  # noqa: E402

# Table 1 of the hybrid voxelization paper (JCGT 2013), GTX 480, 6-separating (thin) binary:
# (triangle-parallel, fragment-parallel, hybrid, cutoff (voxels^2, None = na), pass 1 share).
PAPER = {
    "large triangle (1 tri)": {
        128: (10.62, 0.03, 0.04, None, 36.1),
        256: (42.4, 0.06, 0.07, None, 22.1),
        512: (169.7, 0.22, 0.19, None, 12.0),
    },
    "XYZ RGB Asian Dragon (7,219,045 tris)": {
        128: (6.37, 165.2, 8.51, 2.0, 99.9),
        256: (7.70, 165.0, 8.57, 1.7, 99.7),
        512: (9.80, 164.6, 10.3, 1.4, 99.8),
    },
    "Crytek Sponza (262,267 tris)": {
        128: (13.4, 10.65, 1.11, 2.8, 87.7),
        256: (53.2, 11.13, 1.80, 3.9, 71.6),
        512: (208.7, 11.87, 3.68, 3.1, 52.8),
    },
    "Stanford Bunny (69,666 tris)": {
        128: (0.28, 1.58, 0.19, 1.8, 88.1),
        256: (0.82, 1.55, 0.34, 4.5, 91.6),
        512: (3.12, 1.82, 1.08, 12.7, 93.0),
    },
    "Stanford Dragon (100,000 tris)": {
        128: (0.25, 2.13, 0.26, 13.3, 97.8),
        256: (0.51, 2.09, 0.52, 5.9, 93.4),
        512: (1.61, 2.25, 1.25, 13.7, 88.6),
    },
}
# Our scene -> the paper's row it stands for (None: no Table 1 row).
MATCH = {
    "bunny_stanford_69k": "Stanford Bunny (69,666 tris)",
    "dragon_stanford_res2_203k": "Stanford Dragon (100,000 tris)",
    "sponza_crytek_262k_vcolor": "Crytek Sponza (262,267 tris)",
    "triangle": "large triangle (1 tri)",
    "dragon_stanford_871k": None,
    "dragon_stanford_871k x4": "XYZ RGB Asian Dragon (7,219,045 tris)",
    "dragon_stanford_871k x16": "XYZ RGB Asian Dragon (7,219,045 tris)",
}
SCENE_ORDER = list(MATCH)


def fmt(value, digits=2):
    if value is None or value == "":
        return ""
    value = float(value)
    if value >= 100:
        return f"{value:.0f}"
    if value >= 10:
        return f"{value:.1f}"
    return f"{value:.{digits}f}"


def shlex_join(argv):
    import shlex

    return shlex.join(["python3", "bench/device/table.py"] + argv[1:])


def device_machine(device_txt, renderer, version):
    """The results' machine and date from run.sh's device.txt (the GPU machine's, wherever the
    table is made), else this machine's; the GPU from gl_info.txt."""
    gpu = f"GPU: {renderer} ({version})"
    if not device_txt:
        return {"extra_machine": {"gpu": gpu}}
    try:
        with open(device_txt) as f:
            d = dict(line.rstrip("\n").split("=", 1) for line in f if "=" in line)
    except OSError:
        return {"extra_machine": {"gpu": gpu}}
    memory = d.get("mem_kib", "")
    machine = {
        "cpu": d.get("cpu", "unknown"),
        "cores": int(d["cpus"]) if d.get("cpus", "").isdigit() else None,
        "memory_gib": round(int(memory) / 2**20, 1) if memory.isdigit() else None,
        "os": d.get("os", ""),
        "kernel": d.get("host", ""),
        "gpu": gpu,
        "load_start": None,
    }
    date = d.get("date", "").replace("T", " ")
    date = date[:16] + " UTC" if len(date) >= 16 else None
    return {"extra_machine": machine, "date": date}


def check_text(row):
    check = row["check"]
    if check == "touches":
        return f"touches {row['touches']}"
    if check == "DIFF":
        return f"**DIFF** -{row['missed']} +{row['false_voxels']} ({row['unexplained']} unexplained)"
    return check


def verify(path, rows):
    """Every row whole; every exact row equal (or touches) to cpu; tessellation with no false
    voxel and a bias in (0, 25%); the thread rows equal to the all-cores voxels; each
    (step, scene) of an exact step with all four methods, of a live step with cpu and hybrid."""
    problems = []
    with open(path, newline="") as f:
        header = next(csv.reader(f))
        widths = {len(line) for line in csv.reader(f)}
    if widths - {len(header)}:
        problems.append(f"rows of {sorted(widths)} fields, header has {len(header)}")
    groups = {}
    for r in rows:
        where = f"{r['scene']} {r['mode']}@{r['res']} {r['method']} t{r['threads']}"
        check = r["check"]
        if check.startswith("ERROR") or check == "DIFF":
            problems.append(f"{where}: {check}")
        if r["method"] in ("hybrid", "triangle", "fragment") and check not in ("equal", "touches"):
            problems.append(f"{where}: check {check}")
        if r["method"] in ("hybrid", "triangle", "fragment", "tessellation") and float(r["gpu_ms"]) <= 0:
            problems.append(f"{where}: no GPU time")
        if r["method"] == "tessellation" and check == "bias":
            if int(r["false_voxels"]):
                problems.append(f"{where}: {r['false_voxels']} false voxels")
            if not 0 < float(r["bias"]) < 0.25:
                problems.append(f"{where}: bias {r['bias']}")
        if r["method"] == "cpu" and r["threads"] != "0" and check != "equal":
            problems.append(f"{where}: thread row {check}")
        if r["threads"] == "0" and r["method"] != "tessellation":
            groups.setdefault((r["step"], r["scene"], r["mode"].startswith("live-")), set()).add(r["method"])
    for (step, scene, live), methods in groups.items():
        if live and methods != {"cpu", "hybrid"}:
            problems.append(f"step {step} {scene}: live methods {sorted(methods)}")
        if not live and methods != {"cpu"} and methods != {"cpu", "hybrid", "triangle", "fragment"}:
            problems.append(f"step {step} {scene}: methods {sorted(methods)}")
    print(f"# verify: {len(rows)} rows, {len(problems)} problem(s)")
    for p in problems:
        print(f"#   {p}")
    return 1 if problems else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("csv")
    ap.add_argument("--info", help="gl_info.txt of the same run (GL_RENDERER, ...)")
    ap.add_argument("--device", help="device.txt of the same run (date, CPU, OS, nvidia-smi): the results' machine")
    ap.add_argument("--out", help="also write the tables as results (.json, .md) into this folder")
    ap.add_argument("--res", default="128,256,512,1024")
    ap.add_argument("--mode", default="thin", choices=["thin", "conservative"])
    ap.add_argument(
        "--verify",
        action="store_true",
        help="check the CSV instead (shape, every check passed, biases plausible); exit 1 on a problem",
    )
    args = ap.parse_args()
    wanted = {int(r) for r in args.res.split(",")}

    with open(args.csv, newline="") as f:
        rows = list(csv.DictReader(f))
    if args.verify:
        return verify(args.csv, rows)
    info = {}
    if args.info:
        try:
            with open(args.info) as f:
                info = dict(line.rstrip("\n").split("=", 1) for line in f if "=" in line)
        except OSError:
            pass

    # (scene, res) -> method -> row, for the exact steps of the chosen mode (tessellation
    # rows sit in the first step of their resolution, whatever its mode).
    cells = {}
    triangles = {}
    for r in rows:
        if r["threads"] != "0":
            continue
        res = int(r["res"])
        if res not in wanted:
            continue
        triangles[r["scene"]] = int(r["triangles"])
        if r["method"] == "tessellation" or r["mode"] == args.mode:
            cells.setdefault((r["scene"], res), {}).setdefault(r["method"], r)

    renderer = info.get("GL_RENDERER", "?")
    machine = device_machine(args.device, renderer, info.get("GL_VERSION", "?"))
    tables = []
    table1 = Table(
        "device_table1" + ("" if args.mode == "thin" else "_" + args.mode),
        f"The GL methods on a GPU beside the paper's Table 1 ({args.mode})",
        [
            Column(c)
            for c in (
                "scene",
                "tris",
                "res",
                "triangle",
                "fragment",
                "hybrid @cutoff",
                "pass 1/2",
                "tessellation (bias)",
                "cpu",
                "checks",
                "paper scene",
                "paper tri / frag / hybrid @cutoff",
                "x paper hybrid",
            )
        ],
        command=shlex_join(sys.argv),
        **machine,
    )
    table1.note(
        f"Mode {args.mode}; ms, medians of the timed runs; GPU = GL timer queries (pass 1 + pass 2); cpu = "
        "its voxelize stage (wall). Paper: JCGT 2013 Table 1, GTX 480, thin binary into a dense 3D texture."
    )
    tables.append(table1)

    def order(key):
        scene, res = key
        return (SCENE_ORDER.index(scene) if scene in SCENE_ORDER else 99, scene, res)

    for scene, res in sorted(cells, key=order):
        m = cells[(scene, res)]

        def gpu(method):
            row = m.get(method)
            if row is None:
                return ""
            if row["check"].startswith("ERROR"):
                return "error"
            return fmt(row["gpu_ms"])

        hyb = m.get("hybrid")
        hybrid = ""
        split = ""
        if hyb and not hyb["check"].startswith("ERROR"):
            cutoff = float(hyb["cutoff"])
            hybrid = f"{fmt(hyb['gpu_ms'])} @{'na' if cutoff > 1e6 else fmt(cutoff, 1)}"
            total = float(hyb["pass1_ms"]) + float(hyb["pass2_ms"])
            if total > 0:
                split = f"{100 * float(hyb['pass1_ms']) / total:.0f}%/{100 * float(hyb['pass2_ms']) / total:.0f}%"
        tess = m.get("tessellation")
        tess_text = ""
        if tess:
            tess_text = (
                "error"
                if tess["check"].startswith("ERROR")
                else f"{fmt(tess['gpu_ms'])} ({100 * float(tess['bias']):.1f}%)"
            )
        cpu = m.get("cpu")
        checks = "; ".join(
            f"{meth[0]}: {check_text(m[meth])}"
            for meth in ("hybrid", "triangle", "fragment")
            if meth in m and m[meth]["check"] != "equal"
        )
        if not checks and any(meth in m for meth in ("hybrid", "triangle", "fragment")):
            checks = "equal"
        if tess and tess["check"] == "bias" and int(tess["false_voxels"]):
            checks += f"; **tessellation: {tess['false_voxels']} false voxels**"
        paper_scene = MATCH.get(scene)
        paper = PAPER.get(paper_scene, {}).get(res) if paper_scene else None
        paper_text = ratio = ""
        if paper:
            p_tri, p_frag, p_hyb, p_cut, _ = paper
            paper_text = f"{p_tri} / {p_frag} / {p_hyb} @{'na' if p_cut is None else p_cut}"
            if hyb and not hyb["check"].startswith("ERROR") and float(hyb["gpu_ms"]) > 0:
                r = p_hyb / float(hyb["gpu_ms"])
                ratio = f"{r:.1f}x" if r >= 1 else f"{r:.3f}x"
        table1.add(
            [
                scene,
                str(triangles.get(scene, "")),
                str(res),
                gpu("triangle"),
                gpu("fragment"),
                hybrid,
                split,
                tess_text,
                fmt(cpu["stage_ms"]) if cpu else "",
                checks,
                paper_scene or "",
                paper_text,
                ratio,
            ]
        )

    attribute_rows = [r for r in rows if r["mode"] == "attributes" and not r["check"].startswith("ERROR")]
    if attribute_rows:
        colour = Table(
            "device_attributes",
            "The price of colour and normal voxels on a GPU",
            [
                Column(c)
                for c in (
                    "scene",
                    "res",
                    "method",
                    "binary",
                    "with attributes",
                    "ratio",
                    "max colour diff vs cpu",
                    "check",
                )
            ],
            command=shlex_join(sys.argv),
            **machine,
        )
        colour.note(
            "Conservative; wall ms of the whole call, medians: each method's binary run, then with "
            "attributes; colour checked against cpu's."
        )
        tables.append(colour)
        for r in sorted(attribute_rows, key=lambda r: (order((r["scene"], int(r["res"]))), r["method"])):
            binary, attributed = float(r["binary_wall_ms"]), float(r["wall_ms"])
            ratio = f"{attributed / binary:.1f}x" if binary > 0 else ""
            diff = "" if float(r["attr_max_diff"]) < 0 else f"{float(r['attr_max_diff']):.1e}"
            colour.add([r["scene"], r["res"], r["method"], fmt(binary), fmt(attributed), ratio, diff, check_text(r)])

    live_rows = [r for r in rows if r["mode"].startswith("live-") and not r["check"].startswith("ERROR")]
    if live_rows:
        live = Table(
            "device_live",
            "Live's updates on a GPU, without Blender",
            [
                Column(c)
                for c in (
                    "scene",
                    "mode",
                    "res",
                    "method",
                    "update",
                    "voxelize",
                    "write",
                    "updates a second",
                    "check",
                    "target",
                )
            ],
            command=shlex_join(sys.argv),
            **machine,
        )
        live.note(
            "Per edit a vertex moved, the fixed lattice, voxelize, write the .vdb (ms, medians); hybrid "
            "checked against cpu on the last state. Target: the bunny at 256 at 30 updates a second with "
            "hybrid."
        )
        tables.append(live)
        for r in sorted(live_rows, key=lambda r: (order((r["scene"], int(r["res"]))), r["mode"], r["method"])):
            rate = 1000.0 / float(r["wall_ms"]) if float(r["wall_ms"]) > 0 else 0.0
            target = ""
            if r["scene"] == "bunny_stanford_69k" and r["res"] == "256" and r["method"] == "hybrid":
                target = "met" if rate >= 30 else "not met"
            live.add(
                [
                    r["scene"],
                    r["mode"][5:],
                    r["res"],
                    r["method"],
                    fmt(r["wall_ms"]),
                    fmt(r["stage_ms"]),
                    fmt(r["pass2_ms"]),
                    f"{rate:.1f}",
                    check_text(r),
                    target,
                ]
            )

    threads = [r for r in rows if r["method"] == "cpu" and r["step"] and r["threads"] != "0"]
    if threads:
        by_scene = {}
        for r in threads:
            by_scene.setdefault((r["scene"], int(r["res"])), {})[int(r["threads"])] = float(r["stage_ms"])
        counts = sorted({t for v in by_scene.values() for t in v})
        scaling = Table(
            "device_threads",
            "The cpu method's thread scaling on the GPU machine",
            [Column("scene"), Column("res")] + [Column(f"{t} thr") for t in counts],
            command=shlex_join(sys.argv),
            **machine,
        )
        scaling.note("cpu method, conservative, its voxelize stage (ms) by threads (speed-up vs 1 thread).")
        tables.append(scaling)
        for (scene, res), v in sorted(by_scene.items(), key=lambda kv: order(kv[0])):
            one = v.get(1)
            scaling.add(
                [scene, str(res)]
                + [f"{fmt(v[t])} ({one / v[t]:.1f}x)" if t in v and one and v[t] > 0 else "" for t in counts]
            )

    for table in tables:
        print(f"\n{table.title}. " + " ".join(table.notes) + "\n")
        print("| " + " | ".join(c.name for c in table.columns) + " |")
        print("|" + "---|" * len(table.columns))
        for row in table.rows:
            print("| " + " | ".join(str(v) for v in row) + " |")
        if args.out:
            table.write(args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
