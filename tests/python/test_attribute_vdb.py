# SPDX-License-Identifier: GPL-3.0-or-later
# The attribute grids in the .vdb (CLI --attributes / --texture, VoxelGrid.write_vdb) read
# back with pyopenvdb: active exactly on the density's voxels, with the module's values.
import json

import numpy as np
import pyopenvdb as vdb

import hyvox


def active_values(grid):
    """{(i, j, k): value} of a grid's active voxels (leaf voxels; no tiles in these grids)."""
    out = {}
    for item in grid.iterOnValues():
        assert item["min"] == item["max"], "attribute grids hold voxels, not tiles"
        out[tuple(item["min"])] = item["value"]
    return out


def assert_grid_matches(path, name, grid, expected):
    density = active_values(vdb.read(str(path), "density"))
    values = active_values(vdb.read(str(path), name))
    assert values.keys() == density.keys()
    assert len(values) == grid.voxel_count
    got = np.array([values[tuple(int(c) for c in ijk)] for ijk in grid.coords()])
    np.testing.assert_array_equal(got.reshape(expected.shape), expected)


def test_cli_writes_colour_and_normal_grids_from_file_colours(cli_voxelize, mesh_dir, tmp_path):
    out, stats = tmp_path / "spot.vdb", tmp_path / "stats.json"
    done = cli_voxelize(
        mesh_dir / "spot_vcolor.ply",
        out,
        "-q",
        "--resolution",
        "40",
        "--attributes",
        "color,normal",
        "--stats-json",
        stats,
    )
    assert done.returncode == 0, done.stderr
    names = sorted(meta["name"] for meta in vdb.readAllGridMetadata(str(out)))
    assert names == ["color", "density", "normal"]  # no alpha: the file has none
    assert json.loads(stats.read_text())["attribute_voxels_unreached"] == 0
    v, t, attrs = hyvox.read_mesh(mesh_dir / "spot_vcolor.ply", attributes=True)
    grid = hyvox.voxelize(
        v, t, resolution=40, attributes="color,normal", colors=(attrs["colors"][:, :3] * 255).round().astype(np.uint8)
    )
    assert_grid_matches(out, "color", grid, grid.attributes()["color"])
    assert_grid_matches(out, "normal", grid, grid.attributes()["normal"])


def test_cli_texture_flag(cli_voxelize, mesh_dir, tmp_path):
    out = tmp_path / "spot.vdb"
    png = mesh_dir / "spot_texture.png"
    done = cli_voxelize(
        mesh_dir / "spot_uv.ply", out, "-q", "--resolution", "32", "--attributes", "color", "--texture", png
    )
    assert done.returncode == 0, done.stderr
    v, t, attrs = hyvox.read_mesh(mesh_dir / "spot_uv.ply", attributes=True)
    grid = hyvox.voxelize(v, t, resolution=32, attributes="color", uvs=attrs["uvs"], texture=png)
    assert_grid_matches(out, "color", grid, grid.attributes()["color"])

    # A mesh without UVs cannot take a texture: a clear error, no file.
    bad = cli_voxelize(
        mesh_dir / "spot_vcolor.ply", tmp_path / "no.vdb", "--attributes", "color", "--texture", png, timeout=60
    )
    assert bad.returncode != 0 and "needs the mesh's UVs" in bad.stderr
    assert not (tmp_path / "no.vdb").exists()


def test_alpha_grid_when_the_colours_have_alpha(tmp_path):
    v = np.array([[0, 0, 0], [3, 0, 0.5], [0, 3, 1], [3, 3, 3]], dtype=np.float32)
    t = np.array([[0, 1, 2], [1, 3, 2]])
    grid = hyvox.voxelize(
        v,
        t,
        resolution=12,
        attributes="color",
        material_ids=[0, 1],
        palette=[[1.0, 0.5, 0.0, 0.25], [0.0, 0.5, 1.0, 1.0]],
    )
    path = tmp_path / "alpha.vdb"
    grid.write_vdb(path)
    alpha = grid.attributes()["alpha"]
    assert alpha.min() == np.float32(0.25) and alpha.max() == 1.0 and ((alpha > 0.25) & (alpha < 1)).any()
    assert_grid_matches(path, "alpha", grid, alpha)
    assert_grid_matches(path, "color", grid, grid.attributes()["color"])


def test_cli_writes_the_gl_methods_attribute_grids(cli_voxelize, mesh_dir, tmp_path):
    # The GL methods' colour and normal voxels (clipped on the GPU) go into the .vdb as the
    # cpu's do, and read back as the module computed them.
    v, t, attrs = hyvox.read_mesh(mesh_dir / "spot_vcolor.ply", attributes=True)
    colors = (attrs["colors"][:, :3] * 255).round().astype(np.uint8)
    for method in ("triangle", "fragment", "hybrid"):
        out = tmp_path / f"spot_{method}.vdb"
        done = cli_voxelize(
            mesh_dir / "spot_vcolor.ply",
            out,
            "-q",
            "--resolution",
            "32",
            "--method",
            method,
            "--attributes",
            "color,normal",
        )
        assert done.returncode == 0, done.stderr
        grid = hyvox.voxelize(v, t, resolution=32, method=method, attributes="color,normal", colors=colors)
        assert_grid_matches(out, "color", grid, grid.attributes()["color"])
        assert_grid_matches(out, "normal", grid, grid.attributes()["normal"])
