# SPDX-License-Identifier: GPL-3.0-or-later
"""The damage run: every shared mesh written in every format hyvox reads
(tests/python/mesh_writers.py), each file damaged many ways (mesh_damage.py), and each
damaged file given to the CLI, the module and gamma-sweep. Prints a table per format and
writes it as OUT/damage.json and OUT/damage.md; a damaged file with a problem is kept in
OUT/problems/ with its note. Exits 1 when any file has a problem.

    PYTHONPATH=BUILD/python /usr/bin/python3 tests/damage/damage_meshes.py --cli BUILD/hyvox \\
        [--meshes ../shared/data/meshes] [--out BUILD/damage] [--variants 48] [--formats ply,stl_binary,...]

--variants: damaged files per mesh and format (a quarter of each kind); the largest meshes
get fewer (at least a quarter as many), so that the run stays within hours on two cores."""

import argparse
import collections
import json
import os
import random
import shutil
import sys
import time


HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import mesh_damage  # noqa: E402
from mesh_damage import mesh_writers  # noqa: E402

import hyvox  # noqa: E402


def shared_meshes(folder):
    return sorted(f for f in os.listdir(folder) if f.endswith((".ply", ".ply.gz")))


def variants_for(triangles, variants):
    """Fewer damaged files for the meshes whose every read takes long."""
    if triangles > 500_000:
        return max(4, variants // 4)
    if triangles > 150_000:
        return max(4, variants // 2)
    return variants


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--cli", required=True)
    parser.add_argument("--meshes", default=os.path.join(HERE, "..", "..", "..", "shared", "data", "meshes"))
    parser.add_argument("--out", default="damage")
    parser.add_argument("--variants", type=int, default=48)
    parser.add_argument("--formats", default=",".join(mesh_writers.FORMATS))
    parser.add_argument("--only", default="", help="comma list of shared mesh files (default: all)")
    parser.add_argument("--seed", type=int, default=27)
    args = parser.parse_args()

    work = os.path.join(args.out, "work")
    problems_dir = os.path.join(args.out, "problems")
    shutil.rmtree(args.out, ignore_errors=True)
    os.makedirs(work)
    os.makedirs(problems_dir)
    module = mesh_damage.ModuleDoor(os.environ.get("PYTHONPATH", ""))
    formats = args.formats.split(",")
    meshes = args.only.split(",") if args.only else shared_meshes(args.meshes)
    table = collections.defaultdict(lambda: collections.Counter())
    problems = []
    pieces = collections.defaultdict(list)  # format -> the starts of earlier meshes' files, to splice from
    start = time.time()
    for mesh in meshes:
        vertices, triangles = hyvox.read_mesh(os.path.join(args.meshes, mesh))
        reference = mesh_damage.digest(mesh_damage.corner_rows(vertices, triangles))
        stem = mesh.split(".")[0]
        count = variants_for(len(triangles), args.variants)
        files = {}
        for name in formats:
            suffix, writer = mesh_writers.FORMATS[name]
            path = os.path.join(work, f"{stem}_{name}{suffix}")
            with open(path, "wb") as f:
                f.write(writer(vertices, triangles))
            files[name] = path
        for name in formats:
            suffix, _ = mesh_writers.FORMATS[name]
            original = files[name]
            data = open(original, "rb").read()
            whole = module(original)
            if whole["outcome"] != "ok" or whole["digest"] != reference:
                problems.append(
                    {
                        "mesh": mesh,
                        "format": name,
                        "kind": "undamaged",
                        "problems": [f"the undamaged file does not read back as the mesh: {whole}"],
                    }
                )
                table[name]["problems"] += 1
                continue
            # Splice pieces from the earlier meshes' files of this format: the same format's
            # structures in the wrong place.
            others = pieces[name][-3:]
            pieces[name].append(data[: 1 << 16])
            rng = random.Random(f"{args.seed} {mesh} {name}")
            for k in range(count):
                kind = mesh_damage.KINDS[k % len(mesh_damage.KINDS)]
                bytes_, note = mesh_damage.damaged(name, data, vertices, triangles, kind, rng, others)
                if bytes_ is None:
                    table[name][f"{kind} (none to change)"] += 1
                    continue
                path = os.path.join(work, f"damaged{suffix}")
                with open(path, "wb") as f:
                    f.write(bytes_)
                cli = mesh_damage.cli_door(args.cli, path, work)
                read = module(path, original if kind == "truncate" and name == "obj" else None)
                sweep = mesh_damage.gamma_sweep_door(args.cli, path, work)
                found = mesh_damage.judge(name, kind, note, whole, cli, read, sweep)
                table[name]["files"] += 1
                table[name][cli["outcome"] if cli["outcome"] in ("ok", "error") else "failure"] += 1
                table[name][f"{kind} read"] += cli["outcome"] == "ok"
                if found:
                    table[name]["problems"] += 1
                    kept = os.path.join(problems_dir, f"{stem}_{name}_{k}{suffix}")
                    shutil.copy(path, kept)
                    problems.append(
                        {
                            "mesh": mesh,
                            "format": name,
                            "kind": kind,
                            "note": note,
                            "file": kept,
                            "problems": found,
                            "cli": cli,
                            "module": read,
                            "gamma-sweep": sweep,
                        }
                    )
        for f in files.values():
            os.remove(f)
        print(f"{mesh}: {count} damaged files per format, {time.time() - start:.0f} s so far", flush=True)
    module.close()
    shutil.rmtree(work, ignore_errors=True)

    columns = ["files", "error", "ok", "failure", "problems", "truncate read", "flip read", "count read", "splice read"]
    lines = ["| format | " + " | ".join(columns) + " |", "|---|" + "---:|" * len(columns)]
    for name in formats:
        lines.append(f"| {name} | " + " | ".join(str(table[name][c]) for c in columns) + " |")
    total = collections.Counter()
    for name in formats:
        total.update(table[name])
    lines.append("| all | " + " | ".join(str(total[c]) for c in columns) + " |")
    header = (
        f"Damaged files of the shared meshes in every format, through the CLI, the module and "
        f"gamma-sweep (tests/damage/damage_meshes.py --variants {args.variants} --seed {args.seed}): "
        f"{total['files']} files, {total['problems']} with a problem, {time.time() - start:.0f} s."
    )
    text = header + "\n\n" + "\n".join(lines) + "\n"
    print(text)
    for p in problems:
        print(json.dumps(p)[:1500])
    with open(os.path.join(args.out, "damage.md"), "w") as f:
        f.write(text)
    with open(os.path.join(args.out, "damage.json"), "w") as f:
        json.dump(
            {
                "variants": args.variants,
                "seed": args.seed,
                "meshes": meshes,
                "formats": {name: dict(table[name]) for name in formats},
                "problems": problems,
            },
            f,
            indent=1,
        )
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
