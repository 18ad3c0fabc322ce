# SPDX-License-Identifier: GPL-3.0-or-later
"""`openjd run` of the region job (hyvox job-template openjd-regions): one mesh's grid as 4
region tasks of the hyvox CLI and a merge gives the one-machine run's voxels, grid
transform included: the 871k dragon's surface and Sponza solid."""

import os

import pytest

from conftest import CLI, assert_same_voxels, check, openjd_run, run, template

MESHES = os.environ.get(
    "HYVOX_MESH_DIR", os.path.join(os.path.dirname(__file__), "..", "..", "..", "shared", "data", "meshes")
)


@pytest.mark.parametrize(
    "mesh, mode, resolution",
    [("dragon_stanford_871k.ply.gz", "conservative", 192), ("sponza_crytek_262k_vcolor.ply.gz", "solid", 96)],
)
def test_regions_merged_equal_the_one_machine_run(tmp_path, mesh, mode, resolution):
    import pyopenvdb as vdb

    path = os.path.join(MESHES, mesh)
    whole = str(tmp_path / "whole.vdb")
    options = ["--resolution", str(resolution), "--mode", mode, "--method", "cpu"]
    check(run([CLI, "voxelize", path, "-o", whole, *options]))
    merged = str(tmp_path / "merged.vdb")
    params = {
        "MeshFile": path,
        "OutputFile": merged,
        "Regions": 4,
        "HyvoxExecutable": CLI,
        "Resolution": resolution,
        "Mode": mode,
        "Method": "cpu",
    }
    done = check(
        openjd_run(
            template("openjd-regions", tmp_path), params, dict(os.environ), step="Merge", extra=["--run-dependencies"]
        )
    )
    assert sorted(os.listdir(tmp_path / "merged.vdb.regions")) == [f"region_{k}_of_4.vdb" for k in range(4)], (
        done.stdout
    )
    assert sorted(g["name"] for g in vdb.readAllGridMetadata(merged)) == sorted(
        g["name"] for g in vdb.readAllGridMetadata(whole)
    )
    assert_same_voxels(merged, whole)
