# SPDX-License-Identifier: GPL-3.0-or-later
"""Writes docs/benchmarks.md from the latest results in bench/results/ (each benchmark's NAME.json
and NAME.md, bench_results.py / bench_results.h), in the order and with the words below.

    python3 bench/make_benchmarks_page.py            # after bash bench/run_all.sh
    python3 bench/make_benchmarks_page.py --check    # exit 1 when the page or a result is stale

--check also requires every NAME.md to be what bench_results.render_markdown() makes of its
NAME.json, so the C++ and Python writers cannot drift apart. Standard library only."""

import argparse
import json
import pathlib
import sys

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path[:0] = [str(HERE), str(HERE / "device")]
from bench_results import GENERATED, render_markdown  # noqa: E402
from table import PAPER  # noqa: E402  (the paper's Table 1, written once in bench/device/table.py)

# (heading, what the section measures, the results it shows in this order)
SECTIONS = [
    (
        "The surface against OpenVDB",
        "hyvox's exact `cpu` method (conservative surface) against OpenVDB's `meshToUnsignedDistanceField` with a "
        "one-voxel band, the band Blender's Mesh to Volume builds: same voxel size and placement, same process, "
        "all cores. The voxel counts differ on purpose: hyvox marks every voxel the surface touches, OpenVDB's band "
        "keeps voxels whose centre lies within one voxel of it.",
        ["mesh_to_volume"],
    ),
    (
        "Solid against OpenVDB and libigl",
        "`mode=\"solid\"` (inside rule `auto`) against OpenVDB's `meshToVolume` + `sdfToFogVolume` (Blender's Mesh "
        "to Volume with Fill Volume) on the same grid, and against libigl's fast winding numbers at every voxel "
        "centre. On open meshes OpenVDB's sign flood has no closed surface to follow; the brute-force winding "
        "number says who is right (the checks table).",
        ["solid", "solid_three_way", "solid_three_way_checks", "solid_winding", "solid_disagreements", "open_sampling"],
    ),
    (
        "The signed distance grid against OpenVDB",
        "The `sdf` attribute (a narrow-band signed distance grid, [sdf.md](sdf.md)) against OpenVDB's "
        "`meshToLevelSet`, what Blender's Mesh to SDF Grid node runs: same voxel size, placement and band (3 voxels), "
        "same process, all cores. Where both sides hold a voxel, how far their distances differ; where their signs "
        "differ, the exact winding number says which is right.",
        ["sdf"],
    ),
    (
        "Large grids",
        "The CLI end to end, one process per row, from 1024 to 8192 voxels a side: the stages, the output's "
        "leaves and tiles, the process's peak memory beside the OpenVDB grid's own. Memory follows the surface, "
        "not the box.",
        ["sparse_scale", "sparse_scale_hybrid"],
    ),
    (
        "The memory estimate",
        "What a run is estimated to hold before any work (the memory budget refuses a run on it, "
        "[mesh-formats.md](mesh-formats.md#the-memory-budget)) against the peak resident memory it then takes, "
        "over shared meshes from 1024 to 8192 voxels, surface and solid, with and without colour.",
        ["memory_estimate"],
    ),
    (
        "The price of colour",
        '`hyvox.voxelize` binary, with `attributes="color"` and with `"color,normal"`, interleaved in one run: '
        "Sponza (vertex colours) and Spot (a texture), surface and solid.",
        ["attributes_conservative", "attributes_solid", "attributes_conservative_triangle_fragment_hybrid"],
    ),
    (
        "The tessellation method",
        "The point-tessellated method against the exact methods: its time, points, bias against the exact "
        "conservative and thin voxels, and the flood test of watertightness per γ; then random closed shapes.",
        ["tessellation", "tessellation_seal_sweep", "tessellation_bias_references", "tessellation_cancel"],
    ),
    (
        "The GL methods in software (llvmpipe)",
        "The JCGT 2013 paper's Table 1 columns on Mesa's software rasterizer: the naive one-thread-per-triangle "
        "baseline, `triangle`, `fragment` and `hybrid` with its pass split, and `cpu` beside them. Software GL "
        "runs on the CPU, so these figures say what works, not how fast a GPU is.",
        ["gl_hybrid"],
    ),
    (
        "On a GPU, beside the paper's Table 1",
        "`bench/device/` measures the GL methods on a lent GPU in one run (`bench/device/README.md`): every Table 1 "
        "scene, checked against `cpu`, beside the paper's GTX 480 figures; then the price of colour, the cpu "
        "method's thread scaling and Live's updates without Blender.",
        ["device_table1", "device_table1_conservative", "device_attributes", "device_threads", "device_live"],
    ),
    (
        "In Blender",
        "The add-on's operator end to end (export, voxelize, write, import) against Blender's own Mesh to Volume "
        "modifier on subdivided Suzannes, both making a surface.",
        ["blender_addon"],
    ),
    (
        "Live in Blender",
        "Live's edit-to-new-voxels latency ([live.md](live.md)) in Blender 5.0's `bpy` module: from a vertex moved "
        "until the new grid is loaded in the evaluated volume, against Geometry Nodes' Mesh to Density Grid and the "
        "Mesh to Volume modifier at the same voxel size; then where an update's time goes.",
        ["live", "live_breakdown"],
    ),
    (
        "Regions of one grid",
        "One grid voxelized as a job of regions ([regions.md](regions.md)) against the one-machine run: each task's "
        "peak memory and wall time, and the merge's, every task the CLI in its own process.",
        ["regions"],
    ),
    (
        "Farm jobs",
        "The farm job ([farm.md](farm.md)) three ways: a shell loop of `blender -b` per frame, the Open Job "
        "Description job with a Blender per task, and with one Blender per worker session, run by the real `openjd`.",
        ["farm"],
    ),
    ("Reading meshes", "hyvox's strict PLY/OBJ readers against the assimp path they replaced.", ["mesh_read"]),
    (
        "Against cuda_voxelizer's CPU path",
        "Whole processes of hyvox's CLI and of [cuda_voxelizer](https://github.com/Forceflow/cuda_voxelizer)'s OpenMP "
        "CPU path on the same plain PLY files, and hyvox's Python call beside the CLI's stages. The peer is not part "
        "of hyvox: `PEER=/path/to/cuda_voxelizer bash bench/run_all.sh` adds it.",
        ["vs_cuda_voxelizer"],
    ),
    (
        "The release build",
        "The release's `hyvox` (`scripts/build_release.sh`: zig, glibc 2.28, libc++ and every library linked "
        "statically) against the build tree's (Debian's GCC and shared libraries), whole processes alternating; and "
        "the size of each file of the release. `/usr/bin/python3 bench/bench_release.py build/hyvox dist`.",
        ["release_vs_build", "release_sizes"],
    ),
]
OTHER = (
    "Other results",
    "Comparisons of two builds and single-purpose tools (`bench/README.md`), kept while their files are in "
    "`bench/results/`.",
)
PAGE_HEAD = """<!-- SPDX-License-Identifier: GPL-3.0-or-later -->
<!-- Generated by `python3 bench/make_benchmarks_page.py` from bench/results/: do not edit. -->
# Benchmarks

Each table below is the latest result of one benchmark in `bench/` (what each measures and how to
run it: [bench/README.md](../bench/README.md)). Its header names the command, the machine and the
date it comes from: figures from different machines or loads are not comparable, ratios within
one table are. `bash bench/run_all.sh` runs the benchmarks this page shows and
`python3 bench/make_benchmarks_page.py` rebuilds it from `bench/results/`. Why the code is built
the way these figures reward is in [docs/why/](why/README.md).
"""


def paper_table():
    """The paper's Table 1 (GTX 480), the figures bench/device/table.py sets our GPU's beside."""
    lines = [
        "The paper's own figures (Rauwendaal & Bailey, JCGT 2013, Table 1: GTX 480, thin binary "
        "voxelization into a dense 3D texture; ms; cutoff in voxels², na: none):",
        "",
        "| scene | res | triangle-parallel | fragment-parallel | hybrid | cutoff | pass 1 share % |",
        "|---|---:|---:|---:|---:|---:|---:|",
    ]
    for scene, by_res in PAPER.items():
        for res, (tri, frag, hybrid, cutoff, pass1) in sorted(by_res.items()):
            lines.append(
                f"| {scene} | {res} | {tri} | {frag} | {hybrid} | {'na' if cutoff is None else cutoff} | {pass1} |"
            )
    return "\n".join(lines) + "\n"


def result_text(md_text):
    """A result's .md without its generated-by comment, its heading a level under the section's."""
    lines = md_text.splitlines()
    if lines and lines[0] == GENERATED:
        lines = lines[1:]
    while lines and not lines[0].strip():
        lines = lines[1:]
    return "\n".join(lines) + "\n"


def build_page(results):
    """The page's text from {name: (record, md text)}."""
    parts = [PAGE_HEAD]
    shown = set()
    for heading, about, names in SECTIONS:
        parts.append(f"\n## {heading}\n\n{about}\n")
        if heading.startswith("On a GPU"):
            parts.append("\n" + paper_table())
        present = [n for n in names if n in results]
        if not present:
            parts.append("\n*Not run yet.*\n")
        for name in present:
            parts.append("\n" + result_text(results[name][1]))
            shown.add(name)
    others = sorted(set(results) - shown)
    if others:
        parts.append(f"\n## {OTHER[0]}\n\n{OTHER[1]}\n")
        for name in others:
            parts.append("\n" + result_text(results[name][1]))
    return "".join(parts)


def read_results(folder):
    results = {}
    for path in sorted(pathlib.Path(folder).glob("*.json")):
        record = json.loads(path.read_text(encoding="utf-8"))
        md = path.with_suffix(".md")
        results[record["benchmark"]] = (record, md.read_text(encoding="utf-8") if md.exists() else None, path)
    return results


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--results", default=str(HERE / "results"))
    parser.add_argument("--page", default=str(ROOT / "docs" / "benchmarks.md"))
    parser.add_argument("--check", action="store_true", help="compare instead of writing; exit 1 on a difference")
    args = parser.parse_args()
    results = read_results(args.results)
    problems = []
    for name, (record, md, path) in results.items():
        if path.stem != name:
            problems.append(f"{path}: holds benchmark '{name}' (the file must be named {name}.json)")
        if md != render_markdown(record):
            problems.append(
                f"{path.with_suffix('.md')}: not what its .json renders to (written by another "
                "writer version? rerun the benchmark)"
            )
    page = build_page({name: (record, render_markdown(record)) for name, (record, _, _) in results.items()})
    if args.check:
        current = pathlib.Path(args.page).read_text(encoding="utf-8") if pathlib.Path(args.page).exists() else ""
        if current != page:
            problems.append(
                f"{args.page} is not what bench/results/ makes: regenerate it with "
                "`python3 bench/make_benchmarks_page.py`"
            )
        for p in problems:
            print(p)
        return 1 if problems else 0
    for p in problems:
        print("warning:", p)
    pathlib.Path(args.page).parent.mkdir(parents=True, exist_ok=True)
    pathlib.Path(args.page).write_text(page, encoding="utf-8")
    print(f"wrote {args.page} from {len(results)} results")
    return 0


if __name__ == "__main__":
    sys.exit(main())
