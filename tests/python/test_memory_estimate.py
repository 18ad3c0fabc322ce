# SPDX-License-Identifier: GPL-3.0-or-later
# The memory estimate (native/src/voxelize/memory_estimate.h) against the memory a real run
# holds: the peak resident memory the kernel reports for the CLI (getrusage of the child)
# lies between the base (the same mesh at resolution 8: process and mesh) plus the estimate
# and two thirds of it; and a run estimated past the budget is refused before its first
# progress step, naming the pass and the setting. bench/bench_memory_estimate.py runs the
# same comparison over more meshes and resolutions.
import json
import subprocess

import pytest

import hyvox


def peak_of(command):
    """The peak resident bytes of `command` (a fresh child: ru_maxrss of the children is the
    largest of them, so one child per call)."""
    code = (
        "import resource, subprocess, sys; subprocess.run(sys.argv[1:], check=True); "
        "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)"
    )
    done = subprocess.run(["/usr/bin/python3", "-c", code, *command], capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-2000:]
    return int(done.stdout.split()[-1]) * 1024


@pytest.mark.parametrize(
    "mesh,resolution,extra",
    [
        ("bunny_stanford_69k.ply", 1024, []),
        ("spot_vcolor.ply", 512, ["--mode=solid", "--attributes=color"]),
        ("dragon_stanford_res2_203k.ply.gz", 768, ["--mode=solid"]),
    ],
)
def test_the_estimate_follows_the_memory_held(mesh, resolution, extra, mesh_dir, cli, tmp_path):
    def run(res, more):
        stats = tmp_path / "s.json"
        command = [
            str(cli),
            "voxelize",
            str(mesh_dir / mesh),
            "-o",
            str(tmp_path / "o.vdb"),
            "-q",
            "--method=cpu",
            f"--resolution={res}",
            "--stats-json",
            str(stats),
            *more,
        ]
        return peak_of(command), json.loads(stats.read_text())

    base, _ = run(8, [])
    peak, stats = run(resolution, extra)
    estimate = stats["memory_estimate"]["peak"]
    assert peak <= base + estimate <= 1.5 * peak, (peak, base, stats["memory_estimate"])


def test_a_run_past_the_budget_is_refused_before_it_starts(mesh_dir):
    vertices, triangles = hyvox.read_mesh(mesh_dir / "bunny_stanford_69k.ply")
    steps = []
    for options, part in (
        (dict(resolution=16384, mode="solid", memory_budget_mib=4096), "for the "),
        (dict(resolution=2048, attributes="normal", memory_budget_mib=256), "for the "),
    ):
        with pytest.raises(hyvox.ResourceError) as refused:
            hyvox.voxelize(vertices, triangles, method="cpu", progress=steps.append, **options)
        message = str(refused.value)
        assert "more than the memory budget of" in message and "memory_budget_mib" in message, message
        assert "Preferences > Add-ons > hyvox > Memory Budget" in message, message
        assert part in message
    assert all(p <= 0 for p in steps), steps  # no step of the work began


def test_every_pass_is_estimated(mesh_dir):
    vertices, triangles, attrs = hyvox.read_mesh(mesh_dir / "spot_vcolor.ply", attributes=True)
    grid = hyvox.voxelize(vertices, triangles, resolution=64, method="cpu", mode="solid", attributes="color", **attrs)
    e = grid.stats["memory_estimate"]
    assert all(e[k] > 0 for k in ("surface_pass", "solid_pass", "attribute_values", "vdb_write")), e
    assert e["peak"] == max(e["surface_pass"], e["solid_pass"], e["attribute_values"], e["vdb_write"])
    surface = hyvox.voxelize(vertices, triangles, resolution=64, method="cpu").stats["memory_estimate"]
    assert surface["solid_pass"] == 0 and surface["attribute_values"] == 0, surface


@pytest.mark.parametrize("mesh", ["sponza_crytek_262k_vcolor.ply.gz", "bunny_stanford_69k.ply"])
def test_the_surface_leaves_of_a_large_grid_are_counted(mesh, mesh_dir):
    # From 512³ the estimate counts the surface's leaves (the mesh voxelized on the grid of the
    # bricks) instead of modelling them from the area, which overcounts where surfaces crowd
    # within a brick (Sponza's ~40% at 1024): the count is the conservative surface's own.
    vertices, triangles = hyvox.read_mesh(mesh_dir / mesh)
    stats = hyvox.voxelize(vertices, triangles, resolution=1024, method="cpu").stats
    counted, leaves = stats["memory_estimate"]["surface_leaves"], stats["leaves"]
    assert abs(counted - leaves) <= 1e-3 * leaves, (counted, leaves)
