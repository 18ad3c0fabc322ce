# SPDX-License-Identifier: GPL-3.0-or-later
# The hyvox command-line tool end to end.
import json
import subprocess

import numpy as np
import pytest

import hyvox


def run(cli, *args):
    return subprocess.run([str(cli), *map(str, args)], capture_output=True, text=True, timeout=300)


def test_voxelize_bunny(cli, mesh_dir, tmp_path, bunny):
    out = tmp_path / "bunny.vdb"
    stats_path = tmp_path / "stats.json"
    result = run(
        cli, "voxelize", mesh_dir / "bunny_stanford_69k.ply", "-o", out, "--resolution", 128, "--stats-json", stats_path
    )
    assert result.returncode == 0, result.stderr
    assert "voxels" in result.stdout and result.stderr == ""
    stats = json.loads(stats_path.read_text())
    for key in ("origin", "voxel_size", "dims", "voxel_count", "triangles", "timings_ms", "options", "cpu"):
        assert key in stats, key
    assert stats["triangles"] == {"input": 69451, "used": 69451, "degenerate": 0}
    assert max(stats["dims"]) == 128
    assert {"read_mesh", "voxelize", "write_vdb"} <= set(stats["timings_ms"])

    # The file holds exactly what the Python module computes for the same options.
    expected = hyvox.voxelize(*bunny, resolution=128)
    assert stats["voxel_count"] == expected.voxel_count
    assert stats["origin"] == list(expected.origin) and stats["voxel_size"] == expected.voxel_size
    import pyopenvdb as vdb  # the test interpreter has it (tests/python/CMakeLists.txt): no skip

    density = vdb.read(str(out), "density")
    dense = np.zeros(expected.dims, np.float32)
    density.copyToArray(dense, ijk=(0, 0, 0))
    assert np.array_equal(dense == 1.0, expected.to_dense())


# The CLI reads the mesh on a thread of its own while TBB's workers start, and takes blocks up
# to 32 MiB from malloc's heap (native/cli/main.cpp) where the module keeps glibc's defaults:
# over gzip and plain PLY, one and all threads, surface and solid, with and without colour, its
# file holds what the module computes (read back by OpenVDB).
@pytest.mark.parametrize(
    "mesh, resolution, extra",
    [
        ("dragon_stanford_res2_203k.ply.gz", 256, []),
        ("dragon_stanford_res3_48k.ply", 96, ["--threads", "1", "--mode", "thin"]),
        ("spider_messy.ply", 64, ["--mode", "solid"]),
        ("sponza_crytek_262k_vcolor.ply.gz", 128, ["--attributes", "color"]),
    ],
)
def test_cli_file_equals_the_module(cli, mesh_dir, tmp_path, mesh, resolution, extra):
    import pyopenvdb as vdb

    out = tmp_path / "out.vdb"
    result = run(cli, "voxelize", mesh_dir / mesh, "-o", out, "-q", "--resolution", resolution, *extra)
    assert result.returncode == 0, result.stderr
    options = dict(zip([a.lstrip("-") for a in extra[::2]], extra[1::2]))
    keywords = {k: (int(v) if k == "threads" else v) for k, v in options.items() if k != "attributes"}
    if "attributes" in options:
        v, t, attrs = hyvox.read_mesh(mesh_dir / mesh, attributes=True)
        expected = hyvox.voxelize(
            v,
            t,
            resolution=resolution,
            attributes="color",
            colors=(attrs["colors"][:, :3] * 255).round().astype(np.uint8),
            **keywords,
        )
    else:
        expected = hyvox.voxelize(*hyvox.read_mesh(mesh_dir / mesh), resolution=resolution, **keywords)
    dense = np.zeros(expected.dims, np.float32)
    vdb.read(str(out), "density").copyToArray(dense, ijk=(0, 0, 0))
    assert np.array_equal(dense == 1.0, expected.to_dense())
    if "attributes" in options:
        colour = np.zeros((*expected.dims, 3), np.float32)
        vdb.read(str(out), "color").copyToArray(colour, ijk=(0, 0, 0))
        i, j, k = np.asarray(expected.coords()).T
        np.testing.assert_array_equal(colour[i, j, k], expected.attributes()["color"].reshape(-1, 3))


def test_options(cli, mesh_dir, tmp_path):
    out = tmp_path / "t.vdb"
    result = run(
        cli,
        "voxelize",
        mesh_dir / "teapot_utah.ply",
        f"--output={out}",
        "--voxel-size",
        "0.25",
        "--mode",
        "thin",
        "--method",
        "cpu",
        "--padding",
        "1",
        "--threads",
        "1",
        "-q",
        "--stats-json",
        tmp_path / "s.json",
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout == ""
    stats = json.loads((tmp_path / "s.json").read_text())
    assert stats["mode"] == "thin" and stats["voxel_size"] == 0.25
    assert out.exists()


def test_help_and_version(cli):
    result = run(cli, "--help")
    assert result.returncode == 0 and "usage: hyvox voxelize" in result.stdout
    result = run(cli, "--version")
    assert result.returncode == 0 and result.stdout.strip() == f"hyvox {hyvox.__version__}"


@pytest.mark.parametrize(
    "args, status, message",
    [
        (["voxelize", "{dir}/missing.ply", "-o", "{out}"], 1, "No such file"),
        (["voxelize", "{dir}/garbage.ply", "-o", "{out}"], 1, "garbage.ply"),
        (["voxelize", "{mesh}", "-o", "{out}", "--resolution", "0"], 2, "--resolution"),
        (["voxelize", "{mesh}", "-o", "{out}", "--resolution", "abc"], 2, "whole number"),
        (["voxelize", "{mesh}", "-o", "{out}", "--mode", "thick"], 2, "unknown mode"),
        (["voxelize", "{mesh}", "-o", "{out}", "--bogus"], 2, "unknown option"),
        (["voxelize", "{mesh}"], 2, "no output file"),
        (["voxelize", "{mesh}", "-o", "{out}", "--memory-budget-mib", "1", "--resolution", "8192"], 1, "memory budget"),
        (["voxelize", "{mesh}", "-o", "{out}", "--gammas", "1,2"], 2, "belongs to gamma-sweep"),
        (["gamma-sweep", "{mesh}", "-o", "{out}"], 2, "writes no .vdb"),
        (["gamma-sweep", "{mesh}", "--method", "cpu"], 2, "not a gamma-sweep option"),
        (["gamma-sweep", "{mesh}", "--gammas", "2"], 2, "at least two"),
        (["gamma-sweep", "{mesh}", "--gammas", "2,1"], 2, "ascending"),
        (["gamma-sweep", "{mesh}", "--gammas", "0,1"], 2, "> 0"),
        (["gamma-sweep", "{mesh}", "--gammas", "1,x"], 2, "finite number"),
        (["frobnicate"], 2, "unknown command"),
        ([], 2, "no command"),
    ],
)
def test_bad_input_fails_cleanly(cli, mesh_dir, tmp_path, args, status, message):
    (tmp_path / "garbage.ply").write_text("ply\nthis is not a mesh\n")
    out = tmp_path / "out.vdb"
    values = {"dir": tmp_path, "out": out, "mesh": mesh_dir / "teapot_utah.ply"}
    result = run(cli, *[a.format(**values) for a in args])
    assert result.returncode == status, result.stderr
    assert message in result.stderr
    assert "hyvox: error:" in result.stderr
    assert not out.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["garbage.ply"]  # no temporaries either


def test_unwritable_output_keeps_nothing(cli, mesh_dir, tmp_path):
    result = run(cli, "voxelize", mesh_dir / "teapot_utah.ply", "-o", tmp_path / "no" / "such" / "dir.vdb")
    assert result.returncode == 1 and "cannot write" in result.stderr
    existing = tmp_path / "keep.vdb"
    existing.write_bytes(b"previous")
    result = run(cli, "voxelize", mesh_dir / "teapot_utah.ply", "-o", existing, "--resolution", "0")
    assert result.returncode == 2 and existing.read_bytes() == b"previous"


def test_bad_stats_path_fails_before_writing(cli, mesh_dir, tmp_path):
    out = tmp_path / "out.vdb"
    result = run(cli, "voxelize", mesh_dir / "teapot_utah.ply", "-o", out, "--stats-json", tmp_path / "no" / "s.json")
    assert result.returncode == 1 and "does not exist" in result.stderr
    assert not out.exists()


def test_gamma_sweep_matches_the_module_and_a_least_squares_fit(cli, mesh_dir, tmp_path):
    # Each row's biases are recounted here from the module's own voxels (exact conservative
    # and thin cpu sets minus the tessellation set at that gamma), and the fit of Eq. 3 is redone with
    # numpy: gamma = c0 + c1 ln(bias), B = -c1, A = exp(c0 / c1).
    mesh = mesh_dir / "happy_buddha_100k.ply"
    stats_path = tmp_path / "sweep.json"
    result = run(cli, "gamma-sweep", mesh, "--resolution", 96, "--gammas", "1,2,4", "--stats-json", stats_path)
    assert result.returncode == 0, result.stderr
    assert "Eq. 3 fit" in result.stdout and "needs gamma" in result.stdout
    sweep = json.loads(stats_path.read_text())
    assert [row["gamma"] for row in sweep["rows"]] == [1, 2, 4]

    vertices, triangles = hyvox.read_mesh(mesh)
    exact = hyvox.voxelize(vertices, triangles, resolution=96)
    assert sweep["reference_voxels"] == exact.voxel_count and sweep["dims"] == list(exact.dims)
    reference = {tuple(c) for c in exact.coords()}
    thin = {tuple(c) for c in hyvox.voxelize(vertices, triangles, resolution=96, mode="thin").coords()}
    assert sweep["thin_reference_voxels"] == len(thin)
    biases = []
    for row in sweep["rows"]:
        points = hyvox.voxelize(vertices, triangles, resolution=96, method="tessellation", tess_gamma=row["gamma"])
        got = {tuple(c) for c in points.coords()}
        missed = len(reference - got)
        assert row["missed_voxels"] == missed and row["voxels"] == points.voxel_count
        assert row["bias"] == pytest.approx(missed / len(reference), rel=1e-12)
        assert row["missed_thin_voxels"] == len(thin - got)
        assert row["bias_thin"] == pytest.approx(len(thin - got) / len(thin), rel=1e-12)
        # The Buddha is closed: its thin voxels enclose its inside, which the points seal
        # from gamma 2 on (the flood test itself is tested in test_tessellation_cpu).
        assert row["enclosed_voxels"] > 1000 and row["sealed"] == (row["leaked_voxels"] == 0)
        if row["gamma"] >= 2:
            assert row["sealed"] is True
        biases.append(row["bias"])
    assert biases[0] > biases[1] > biases[2] > 0

    c1, c0 = np.polyfit(np.log(biases), [1.0, 2.0, 4.0], 1)
    assert sweep["fit"]["B"] == pytest.approx(-c1, rel=1e-9)
    assert sweep["fit"]["A"] == pytest.approx(np.exp(c0 / c1), rel=1e-9)
