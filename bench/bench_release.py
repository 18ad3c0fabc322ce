# SPDX-License-Identifier: GPL-3.0-or-later
"""Benchmark (not a test): the release (scripts/build_release.sh's dist/) against the build
tree, side by side in one run.

    /usr/bin/python3 bench/bench_release.py build/hyvox dist [--runs 9] [--out bench/results]

- the size of each artefact in dist/;
- the manylinux build's `hyvox` (from hyvox-VERSION-linux-x64-cli.zip, unpacked) against the
  build tree's, whole processes alternating (bench_cli_ab.py), on the shared meshes, cpu method,
  surface and solid, 256 and 512: the median wall time of each and their ratio per row.
Writes DIR/release_sizes.{json,md} and DIR/release_vs_build.{json,md}.
"""

import argparse
import glob
import json
import os
import subprocess
import sys
import tempfile
import zipfile

from bench_results import Column, Table, add_out_argument

HERE = os.path.dirname(os.path.abspath(__file__))
MESH_DIR = os.path.join(HERE, "..", "..", "shared", "data", "meshes")
MESHES = ["bunny_stanford_69k.ply", "sponza_crytek_262k_vcolor.ply.gz", "dragon_stanford_871k.ply.gz"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("build_hyvox", help="the build tree's hyvox")
    parser.add_argument("dist", help="the release's dist/ folder")
    parser.add_argument("--runs", type=int, default=9)
    parser.add_argument("--idle-wait", default="60", help="bench_cli_ab.py's wait for an idle machine, per round")
    add_out_argument(parser)
    args = parser.parse_args()

    sizes = Table("release_sizes", "The release's artefacts", [Column("file"), Column("MB", 2)])
    for path in sorted(glob.glob(os.path.join(args.dist, "*"))):
        sizes.add([os.path.basename(path), os.path.getsize(path) / 1e6])
    sizes.write(args.out)

    (cli_zip,) = glob.glob(os.path.join(args.dist, "hyvox-*-linux-x64-cli.zip"))
    table = Table(
        "release_vs_build",
        "The release's hyvox (zig, glibc 2.28, static libc++) against the build tree's (Debian's GCC)",
        [
            Column("mesh"),
            Column("res"),
            Column("mode"),
            Column("build ms", 1),
            Column("release ms", 1),
            Column("release / build", 3),
        ],
    )
    table.note(
        f"Median wall time of whole `hyvox voxelize --method cpu` processes, {args.runs} alternating rounds each."
    )
    with tempfile.TemporaryDirectory(prefix="hyvox-release-bench-") as tmp:
        with zipfile.ZipFile(cli_zip) as z:
            z.extractall(tmp)
            (folder,) = {n.split("/")[0] for n in z.namelist()}
        release = os.path.join(tmp, folder, "hyvox")
        for program in (release, os.path.join(tmp, folder, "hyvox_assimp_reader")):
            os.chmod(program, 0o755)
        for mesh in MESHES:
            for res in ("256", "512"):
                for mode in ("conservative", "solid"):
                    out = os.path.join(tmp, "row")
                    subprocess.run(
                        [
                            sys.executable,
                            os.path.join(HERE, "bench_cli_ab.py"),
                            args.build_hyvox,
                            release,
                            "--mesh",
                            os.path.join(MESH_DIR, mesh),
                            "--res",
                            res,
                            "--runs",
                            str(args.runs),
                            "--extra",
                            f"--mode {mode}",
                            "--out",
                            out,
                        ],
                        check=True,
                        stdout=subprocess.DEVNULL,
                        cwd=HERE,
                    )
                    with open(os.path.join(out, "cli_ab.json")) as f:
                        rows = json.load(f)["rows"]
                    medians = {row[0]: row[3] for row in rows}
                    build_ms, release_ms = medians[args.build_hyvox], medians[release]
                    table.add([mesh, res, mode, build_ms, release_ms, release_ms / build_ms])
                    print(f"{mesh} {res} {mode}: {build_ms:.1f} ms / {release_ms:.1f} ms", flush=True)
    table.write(args.out)


if __name__ == "__main__":
    main()
