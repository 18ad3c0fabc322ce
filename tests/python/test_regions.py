# SPDX-License-Identifier: GPL-3.0-or-later
"""Regions of one grid (docs/regions.md): a job of N parts, each voxelizing its box of the grid
(the CLI's --region K/N, voxelize(region="K/N")), merged (hyvox merge, hyvox.merge_vdb), gives
the one-machine file. The oracles: pyopenvdb reading both files (every grid's values and active
voxels, tiles included, the transform and the metadata), the files' own bytes (equal but for the
random UUID), and the box each part must keep to, computed here from the grid's dims."""

import json
import math
import os
import re
import subprocess

import numpy as np
import pyopenvdb as vdb  # the test interpreter has it (tests/python/CMakeLists.txt): no skip
import pytest

import hyvox

UUID = slice(21, 57)  # Archive::writeHeader: magic, version, library version, offsets flag, then the UUID


@pytest.fixture(scope="module")
def sponza(mesh_dir):
    return hyvox.read_mesh(mesh_dir / "sponza_crytek_262k_vcolor.ply.gz", attributes=True)


def expected_box(dims, index, count):
    """The box of region index/count: the longest axis's 8-voxel leaves split evenly."""
    axis = int(np.argmax(dims))
    leaves = math.ceil(dims[axis] / 8)
    lo, hi = [0, 0, 0], list(dims)
    lo[axis] = index * leaves // count * 8
    hi[axis] = min((index + 1) * leaves // count * 8, dims[axis])
    return "xyz"[axis], lo, hi


def bytes_but_uuid(path):
    data = bytearray(path.read_bytes())
    data[UUID] = b"\0" * (UUID.stop - UUID.start)
    return bytes(data)


def dense(grid, dims):
    """A pyopenvdb grid's values over the whole box (tiles expanded, background elsewhere)."""
    shape = tuple(dims) + (() if grid.valueTypeName == "float" else (3,))
    array = np.zeros(shape, dtype=np.float32)
    grid.copyToArray(array, ijk=(0, 0, 0))
    return array


def assert_same_vdb(whole_path, merged_path, dims):
    """The merged file is the one-machine file: the same grids, each with the same values on
    every voxel, active voxels (density: 1 on exactly those), tree (leaves, internal nodes,
    tiles), class, transform and metadata; and the same bytes."""
    whole, whole_meta = vdb.readAll(str(whole_path))
    merged, merged_meta = vdb.readAll(str(merged_path))
    assert [g.name for g in merged] == [g.name for g in whole]
    assert merged_meta == whole_meta
    for a, b in zip(whole, merged):
        assert b.gridClass == a.gridClass and b.valueTypeName == a.valueTypeName and b.background == a.background, (
            a.name
        )
        for count in ("activeVoxelCount", "activeLeafVoxelCount", "leafCount", "nonLeafCount", "memUsage"):
            assert getattr(b, count)() == getattr(a, count)(), (a.name, count)
        assert b.evalActiveVoxelBoundingBox() == a.evalActiveVoxelBoundingBox(), a.name
        assert b.transform.voxelSize() == a.transform.voxelSize(), a.name
        for ijk in [(0, 0, 0), (-0.5, -0.5, -0.5), (97, 13, 41)]:
            assert b.transform.indexToWorld(ijk) == a.transform.indexToWorld(ijk), a.name
        assert dict(b.metadata) == dict(a.metadata), a.name
        values = dense(a, dims)
        assert np.array_equal(dense(b, dims), values), a.name
        if a.name == "density":
            assert np.count_nonzero(values) == a.activeVoxelCount() and set(np.unique(values)) <= {0.0, 1.0}
    assert bytes_but_uuid(merged_path) == bytes_but_uuid(whole_path)


def check_part(path, stats, dims, index, count):
    """A part's stats name its region and box, and its voxels keep to that box."""
    axis, lo, hi = expected_box(dims, index, count)
    assert stats["region"] == {"index": index, "count": count, "axis": axis, "lo": lo, "hi": hi}
    assert stats["options"]["region"] == f"{index}/{count}"
    assert tuple(stats["dims"]) == tuple(dims)
    for grid in vdb.readAll(str(path))[0]:
        assert grid.metadata["hyvox_region"] == f"{index}/{count}"
        assert tuple(grid.metadata["hyvox_dims"]) == tuple(dims)
        if grid.activeVoxelCount():
            first, last = grid.evalActiveVoxelBoundingBox()
            assert all(first[a] >= lo[a] and last[a] < hi[a] for a in range(3)), (grid.name, first, last, lo, hi)


def run_cli(cli, *args):
    done = subprocess.run([str(cli), *map(str, args)], capture_output=True, text=True, timeout=300)
    return done


def cli_job(cli, mesh, count, tmp_path, *options):
    """The one-machine run and the job's parts by the CLI, merged by the CLI."""
    whole, stats = tmp_path / "whole.vdb", tmp_path / "whole.json"
    done = run_cli(cli, "voxelize", mesh, "-o", whole, "-q", "--stats-json", stats, *options)
    assert done.returncode == 0, done.stderr
    dims = json.loads(stats.read_text())["dims"]
    parts = []
    for k in range(count):
        part, part_stats = tmp_path / f"part{k}.vdb", tmp_path / f"part{k}.json"
        done = run_cli(
            cli, "voxelize", mesh, "-o", part, "-q", "--stats-json", part_stats, "--region", f"{k}/{count}", *options
        )
        assert done.returncode == 0, done.stderr
        check_part(part, json.loads(part_stats.read_text()), dims, k, count)
        parts.append(part)
    merged = tmp_path / "merged.vdb"
    done = run_cli(cli, "merge", *parts[::-1], "-o", merged)  # any order
    assert done.returncode == 0, done.stderr
    assert f"merged {count} files (the {count} regions of a job)" in done.stdout
    return whole, parts, merged, dims


def test_dragon_surface_in_four_regions_is_the_whole_run(cli, mesh_dir, tmp_path):
    # 300 voxels along x: 38 leaves, the last cut by the grid's end; 9 or 10 leaves a region.
    whole, parts, merged, dims = cli_job(
        cli, mesh_dir / "dragon_stanford_871k.ply.gz", 4, tmp_path, "--resolution", "300"
    )
    counts = [vdb.read(str(p), "density").activeVoxelCount() for p in parts]
    assert all(counts) and sum(counts) == vdb.read(str(whole), "density").activeVoxelCount()
    assert_same_vdb(whole, merged, dims)


def module_job(mesh, count, tmp_path, **options):
    """The one-machine run and the job's parts by the module, merged by hyvox.merge_vdb."""
    vertices, triangles, attrs = mesh
    whole = tmp_path / "whole.vdb"
    grid = hyvox.voxelize(vertices, triangles, **options)
    grid.write_vdb(whole)
    parts = []
    for k in range(count):
        part = hyvox.voxelize(vertices, triangles, region=f"{k}/{count}", **options)
        assert part.dims == grid.dims and part.origin == grid.origin and part.voxel_size == grid.voxel_size
        parts.append(tmp_path / f"part{k}.vdb")
        part.write_vdb(parts[-1])
        check_part(parts[-1], part.stats, grid.dims, k, count)
    merged = tmp_path / "merged.vdb"
    report = hyvox.merge_vdb(parts, merged)
    assert report["parts"] == count and report["regions"] == count and report["voxels"] == grid.voxel_count
    return whole, parts, merged, grid.dims


def test_sponza_solid_in_four_regions_is_the_whole_run(sponza, tmp_path):
    # Sponza is open: the inside is decided by fast winding numbers, region by region.
    whole, _, merged, dims = module_job(sponza, 4, tmp_path, resolution=200, mode="solid")
    density = vdb.read(str(merged), "density")
    assert density.activeVoxelCount() > density.activeLeafVoxelCount(), "the solid's inside is held as tiles"
    assert_same_vdb(whole, merged, dims)


def test_colour_and_normal_grids_in_regions(mesh_dir, tmp_path, cli):
    # Spot's texture through the CLI; Sponza's vertex colours through the module.
    spot = mesh_dir / "spot_uv.ply"
    whole, _, merged, dims = cli_job(
        cli,
        spot,
        3,
        tmp_path,
        "--resolution",
        "96",
        "--attributes",
        "color,normal",
        "--texture",
        mesh_dir / "spot_texture.png",
    )
    assert sorted(g.name for g in vdb.readAll(str(merged))[0]) == ["color", "density", "normal"]
    assert_same_vdb(whole, merged, dims)


def test_vertex_colours_in_regions(sponza, tmp_path):
    vertices, triangles, attrs = sponza
    whole, _, merged, dims = module_job(
        (vertices, triangles, attrs), 5, tmp_path, resolution=160, colors=attrs["colors"], attributes="color,normal"
    )
    assert sorted(g.name for g in vdb.readAll(str(merged))[0]) == ["alpha", "color", "density", "normal"]
    assert_same_vdb(whole, merged, dims)


def test_one_region_is_the_whole_grid(bunny, tmp_path):
    vertices, triangles = bunny
    whole = hyvox.voxelize(vertices, triangles, resolution=64)
    one = hyvox.voxelize(vertices, triangles, resolution=64, region="0/1")
    assert "region" not in one.stats and one.stats["options"]["region"] == ""
    assert np.array_equal(one.coords(), whole.coords())
    whole.write_vdb(tmp_path / "whole.vdb")
    one.write_vdb(tmp_path / "one.vdb")
    assert "hyvox_region" not in vdb.read(str(tmp_path / "one.vdb"), "density").metadata
    # A file of no job merges on its own into itself.
    report = hyvox.merge_vdb([tmp_path / "one.vdb"], tmp_path / "merged.vdb")
    assert report["regions"] is None
    assert_same_vdb(tmp_path / "whole.vdb", tmp_path / "merged.vdb", whole.dims)


def test_a_region_with_no_voxels_writes_its_grids(mesh_dir, tmp_path, cli):
    # Bounds twice the mesh's size along x: the last of four regions holds nothing.
    vertices, triangles = hyvox.read_mesh(mesh_dir / "spot_uv.ply")
    low, high = vertices.min(axis=0).astype(float), vertices.max(axis=0).astype(float)
    far = high.copy()
    far[0] += high[0] - low[0] + 1.0
    bounds = f"{low[0]},{low[1]},{low[2]},{far[0]},{far[1]},{far[2]}"
    whole, parts, merged, dims = cli_job(
        cli, mesh_dir / "spot_uv.ply", 4, tmp_path, "--resolution", "64", "--bounds", bounds, "--attributes", "normal"
    )
    empty, _ = vdb.readAll(str(parts[3]))
    assert sorted(g.name for g in empty) == ["density", "normal"] and all(g.activeVoxelCount() == 0 for g in empty)
    corner = vdb.read(str(whole), "density").transform.indexToWorld((-0.5, -0.5, -0.5))
    assert all(g.transform.indexToWorld((-0.5, -0.5, -0.5)) == corner for g in empty)
    assert_same_vdb(whole, merged, dims)


def test_more_regions_than_leaves_along_the_axis_are_refused(tetrahedron, tetra_obj, cli, tmp_path):
    vertices, triangles = tetrahedron
    # 20 voxels a side: 3 leaves along x (the first of the equal sides), so at most 3 regions.
    assert hyvox.voxelize(vertices, triangles, resolution=20, region="2/3").stats["region"]["lo"] == [16, 0, 0]
    with pytest.raises(
        ValueError,
        match=r"region 3/4: the 20x20x20 grid has 3 leaves .* along its longest side \(x\), "
        r"so it can be cut into at most 3 regions",
    ):
        hyvox.voxelize(vertices, triangles, resolution=20, region="3/4")
    out = tmp_path / "part.vdb"
    done = run_cli(cli, "voxelize", tetra_obj, "-o", out, "--resolution", "20", "--region", "0/4")
    assert done.returncode == 1 and "can be cut into at most 3 regions" in done.stderr
    assert not out.exists()


@pytest.mark.parametrize("text", ["4/4", "5/4", "-1/4", "1/0", "1/2049", "1", "a/b", "1/2/3", " 1/2"])
def test_a_region_out_of_range_is_refused(text, tetrahedron, tetra_obj, cli, tmp_path):
    vertices, triangles = tetrahedron
    message = f"region must be K/N with whole numbers 0 <= K < N <= 2048, or '' for the whole grid, got '{text}'"
    with pytest.raises(ValueError) as error:
        hyvox.voxelize(vertices, triangles, region=text)
    assert str(error.value) == message
    out = tmp_path / "part.vdb"
    done = run_cli(cli, "voxelize", tetra_obj, "-o", out, f"--region={text}")
    assert done.returncode == 2 and f"--region: {message}" in done.stderr
    assert not out.exists()


def test_solid_with_attributes_needs_the_whole_grid(bunny):
    vertices, triangles = bunny
    with pytest.raises(ValueError, match="solid mode with attributes .* needs the whole grid"):
        hyvox.voxelize(vertices, triangles, resolution=32, mode="solid", attributes="normal", region="1/2")


@pytest.fixture(scope="module")
def bunny_parts(bunny, tmp_path_factory):
    """Bunny parts of several jobs and runs at 48 voxels, by name."""
    vertices, triangles = bunny
    folder = tmp_path_factory.mktemp("parts")
    made = {}

    def part(name, **options):
        made[name] = folder / f"{name}.vdb"
        hyvox.voxelize(vertices, triangles, **{"resolution": 48, **options}).write_vdb(made[name])

    for k in range(3):
        part(f"{k}of3", region=f"{k}/3")
    part("0of2", region="0/2")
    part("1of3_at_49", region="1/3", resolution=49)
    part("1of3_solid", region="1/3", mode="solid")
    part("1of3_thin", region="1/3", mode="thin")
    part("1of3_normal", region="1/3", attributes="normal")
    part("1of3_padded", region="1/3", padding=1)
    part("whole")
    return made


@pytest.mark.parametrize(
    "names, message",
    [
        (["0of3", "2of3"], "cannot merge a job of 3 regions without region 1/3"),
        (["0of3"], "cannot merge a job of 3 regions without regions 1/3, 2/3"),
        (["0of3", "1of3", "1of3", "2of3"], "region 1/3 is also"),
        (["0of3", "1of3", "2of3", "0of2"], "it is region 0/2, of a job of 2 regions"),
        (["0of3", "1of3_at_49", "2of3"], "its voxel size is"),
        (["0of3", "1of3_padded", "2of3"], "its grid origin is"),
        (["0of3", "1of3_solid", "2of3"], "its mode is solid"),
        (["0of3", "1of3_thin", "2of3"], "its mode is thin"),
        (["0of3", "1of3_normal", "2of3"], "its grids are density, normal"),
        (["whole", "1of3"], "it is region 1/3 of a job, and"),
        (["whole", "whole"], "both hold voxels of the leaf at"),
    ],
)
def test_merge_refuses_parts_that_do_not_fit(bunny_parts, names, message, tmp_path, cli):
    out = tmp_path / "merged.vdb"
    paths = [bunny_parts[n] for n in names]
    with pytest.raises(ValueError, match=message):
        hyvox.merge_vdb(paths, out)
    done = run_cli(cli, "merge", *paths, "-o", out)
    assert done.returncode == 1 and message.split(" .*")[0] in done.stderr, done.stderr
    assert not out.exists() and os.listdir(tmp_path) == []  # nothing written, no temporary left


def test_merge_refuses_other_files_and_keeps_the_output(bunny_parts, tmp_path, cli):
    parts = [bunny_parts[f"{k}of3"] for k in range(3)]
    out = tmp_path / "merged.vdb"
    out.write_bytes(b"an earlier file")
    with pytest.raises(ValueError, match="is one of the parts"):
        hyvox.merge_vdb(parts, parts[1])
    not_vdb = tmp_path / "mesh.ply"
    not_vdb.write_bytes(b"ply\nformat ascii 1.0\n")
    with pytest.raises(ValueError, match="is not a .vdb file hyvox can read: it ends early|OpenVDB's magic number"):
        hyvox.merge_vdb(parts + [not_vdb], out)
    truncated = tmp_path / "truncated.vdb"
    truncated.write_bytes(parts[0].read_bytes()[:-100])
    with pytest.raises(ValueError, match="is not a .vdb file hyvox can read"):
        hyvox.merge_vdb([truncated] + parts[1:], out)
    with pytest.raises(ValueError, match="cannot open"):
        hyvox.merge_vdb([tmp_path / "missing.vdb"], out)
    assert out.read_bytes() == b"an earlier file"
    done = run_cli(cli, "merge", "-o", out)
    assert done.returncode == 2 and "no .vdb file given to merge" in done.stderr
    done = run_cli(cli, "merge", *parts)
    assert done.returncode == 2 and "no output file given" in done.stderr


def test_a_part_holds_only_its_box(dragon):
    # Each part is estimated, and held to the budget, for its box alone: a budget just below
    # the least the one-machine run can need (its estimate under a 1 MiB budget, with the
    # smallest tiles: what it holds for its whole result) fits every part.
    vertices, triangles = dragon
    with pytest.raises(hyvox.ResourceError) as refused:
        hyvox.voxelize(vertices, triangles, resolution=1200, memory_budget_mib=1)
    least_mib = int(re.search(r"needs about (\d+) MiB", str(refused.value)).group(1))
    budget_mib = least_mib - 1
    with pytest.raises(hyvox.ResourceError, match=f"memory budget of {budget_mib} MiB"):
        hyvox.voxelize(vertices, triangles, resolution=1200, memory_budget_mib=budget_mib)
    parts = [
        hyvox.voxelize(vertices, triangles, resolution=1200, region=f"{k}/4", memory_budget_mib=budget_mib).stats
        for k in range(4)
    ]
    assert max(p["memory_estimate"]["peak"] for p in parts) <= budget_mib << 20
    assert min(p["leaves"] for p in parts) > 0


def test_merge_help_lists_its_options(cli):
    general = run_cli(cli, "--help")
    assert "hyvox merge PART.vdb... -o OUT.vdb" in general.stdout
    merge = run_cli(cli, "merge", "--help")
    assert merge.returncode == 0 and merge.stdout.startswith("usage: hyvox merge PART.vdb... -o OUT.vdb")
    for flag in ("--output", "--progress", "--quiet", "--threads", "--durable-write"):
        assert re.search(rf"^  (-\w, )?{flag}\b", merge.stdout, re.M), flag
    assert hyvox.option("durable_write").help in merge.stdout  # the schema's help, not a copy
    assert "--resolution" not in merge.stdout
    done = run_cli(cli, "merge", "a.vdb", "-o", "b.vdb", "--resolution", "8")
    assert (
        done.returncode == 2
        and "--resolution is not a merge option" in done.stderr
        and "hyvox merge --help" in done.stderr
    )
    done = run_cli(cli, "merge", "a.vdb", "-o", "b.vdb", "--bogus")
    assert done.returncode == 2 and "unknown option '--bogus'" in done.stderr
    sweep = run_cli(cli, "gamma-sweep", "--help")
    assert "--region" not in sweep.stdout


def test_a_cancelled_merge_writes_nothing(bunny_parts, tmp_path):
    parts = [bunny_parts[f"{k}of3"] for k in range(3)]
    out = tmp_path / "merged.vdb"
    seen = []

    def stop(percent):
        seen.append(percent)
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        hyvox.merge_vdb(parts, out, progress=stop)
    token = hyvox.CancelToken()
    token.cancel()
    with pytest.raises(hyvox.Cancelled):
        hyvox.merge_vdb(parts, out, cancel=token)
    assert seen == [0] and os.listdir(tmp_path) == []
    assert hyvox.merge_vdb(parts, out, durable_write=True, threads=1)["voxels"] > 0
