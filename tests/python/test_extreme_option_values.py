# SPDX-License-Identifier: GPL-3.0-or-later
# Option values inside the schema's limits whose combination with the mesh used to give
# nonsense with no error (0 voxels, a failure only at the write, 300-digit messages): each
# is now a clear error naming the option, or a meaningful result, from every front door.
import subprocess

import numpy as np
import pytest

import hyvox

TETRA_VERTICES = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], np.float32)
TETRA_TRIANGLES = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], np.uint32)
TETRA_UVS = np.array([[0, 0], [1, 0], [0, 1], [1, 1]], np.float32)
HEIGHTS = np.array([[0.0, 1.0], [0.3, 0.7]], np.float32)  # midlevel 0.5: offsets up to 0.5 × strength


def voxelize_tetra(**options):
    extra = {"uvs": TETRA_UVS, "displacement_pixels": HEIGHTS} if "displacement_strength" in options else {}
    return hyvox.voxelize(TETRA_VERTICES, TETRA_TRIANGLES, **extra, **options)


@pytest.mark.parametrize("method", hyvox.METHODS)
def test_a_voxel_larger_than_the_mesh_holds_it_in_voxel_zero_on_every_method(method):
    # Geometry is the oracle: origin = the mesh's min corner and a voxel at least as large as
    # the mesh put the whole closed mesh in voxel (0,0,0). The largest size allowed (a million
    # times the mesh) still gives exactly that on every method; the GL methods used to give
    # 0 voxels from ~1e19 on (single precision underflow), the CPU ones 1.
    for voxel_size in (2.0, 1e6):
        extra = {"tess_counts": False} if method == "tessellation" else {}
        grid = voxelize_tetra(method=method, voxel_size=voxel_size, **extra)
        assert grid.dims == (1, 1, 1)
        assert grid.coords().tolist() == [[0, 0, 0]], (method, voxel_size)


@pytest.mark.parametrize("method", ["cpu", "hybrid"])
@pytest.mark.parametrize("voxel_size", [1.01e6, 1e20, 1e300])
def test_a_voxel_size_that_makes_the_mesh_a_speck_is_refused(method, voxel_size):
    with pytest.raises(ValueError, match=r"voxel_size .* more than 1e\+06 times the mesh's longest side \(1\)"):
        voxelize_tetra(method=method, voxel_size=voxel_size)


def test_a_tiny_mesh_in_huge_bounds_is_refused_naming_bounds():
    # resolution 256 over a 1e9 box: voxels of ~3.9e6 around a mesh of side 1.
    with pytest.raises(ValueError, match=r"^bounds \(a voxel size of 3\.9\d+e\+06"):
        voxelize_tetra(bounds=((0, 0, 0), (1e9, 1e9, 1e9)))
    assert voxelize_tetra(bounds=((0, 0, 0), (1e5, 1e5, 1e5))).coords().tolist() == [[0, 0, 0]]


def test_bounds_wider_than_a_double_are_refused():
    # Each corner is finite, their difference is not: it used to give a 1x1x1 grid, 0 voxels.
    with pytest.raises(ValueError, match=r"bounds span more than a double can hold"):
        voxelize_tetra(bounds=((-1e308, -1e308, -1e308), (1e308, 1e308, 1e308)))


def test_a_grid_too_large_is_reported_with_a_short_number():
    with pytest.raises(ValueError) as caught:
        voxelize_tetra(origin=(-1e300, 0, 0))
    message = str(caught.value)
    assert "2.56e+302 voxels along an axis" in message and len(message) < 200, message


def test_a_displacement_beyond_single_precision_is_refused_up_front():
    for options, named in [
        ({"displacement_strength": 1e30}, "displacement_strength 1e+30"),
        ({"displacement_strength": 1.0, "displacement_midlevel": 1e30}, "displacement_midlevel 1e+30"),
    ]:
        with pytest.raises(ValueError, match=r"at most 16777216 voxels can be computed") as caught:
            voxelize_tetra(method="tessellation", resolution=32, **options)
        assert named in str(caught.value)


def test_a_displacement_that_carries_every_point_away_is_an_error_not_zero_voxels():
    # Strength 1000 on a unit mesh: every point moves 300 to 500 units, far out of the grid.
    with pytest.raises(ValueError, match=r"every one of the \d+ displaced points left the grid"):
        voxelize_tetra(method="tessellation", resolution=32, displacement_strength=1000.0)
    # The same strength with bounds that hold the displaced surface is a meaningful result:
    # voxels far outside the undisplaced mesh's box (which lies in the grid's voxels 15..16).
    reach = 0.5 * 1000.0 + 1
    grid = voxelize_tetra(
        method="tessellation",
        resolution=32,
        displacement_strength=1000.0,
        bounds=((-reach, -reach, -reach), (reach, reach, reach)),
    )
    coords = grid.coords()
    assert len(coords) > 0
    assert (np.abs(coords.astype(np.int64) - 16) > 2).any()
    # Some points clipped, some landed: not an error either.
    grid = voxelize_tetra(method="tessellation", resolution=32, displacement_strength=0.5)
    assert (
        grid.voxel_count > 0 and 0 < grid.stats["tessellation"]["points_clipped"] < grid.stats["tessellation"]["points"]
    )


def test_a_voxel_size_a_vdb_cannot_hold_is_a_clear_error_at_the_write(tmp_path):
    import pyopenvdb as vdb  # the test interpreter has it (tests/python/CMakeLists.txt)

    small = TETRA_VERTICES * np.float32(1e-3)
    too_small = hyvox.voxelize(small, TETRA_TRIANGLES, voxel_size=1.4e-5)
    path = tmp_path / "small.vdb"
    with pytest.raises(ValueError, match=r"voxel size 1\.4e-05 is below the smallest a \.vdb file can hold"):
        too_small.write_vdb(str(path))
    assert not path.exists()
    # Just above OpenVDB's limit the file is written and holds that voxel size.
    fine = hyvox.voxelize(small, TETRA_TRIANGLES, voxel_size=1.45e-5)
    fine.write_vdb(str(path))
    assert vdb.read(str(path), "density").transform.voxelSize()[0] == pytest.approx(1.45e-5)


def test_the_cli_refuses_a_voxel_size_the_vdb_cannot_hold_before_the_work(cli, tmp_path):
    mesh = tmp_path / "tiny.obj"
    mesh.write_text("v 0 0 0\nv 0.001 0 0\nv 0 0.001 0\nv 0 0 0.001\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    out = tmp_path / "o.vdb"
    done = subprocess.run(
        [str(cli), "voxelize", str(mesh), "-o", str(out), "--resolution", "100"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode != 0
    assert "voxel size 1e-05 is below the smallest a .vdb file can hold" in done.stderr
    assert "voxelize" not in done.stdout and not out.exists()  # refused before voxelizing


def test_the_cli_gives_the_same_refusals(cli, tmp_path, tetra_obj):
    done = subprocess.run(
        [str(cli), "voxelize", str(tetra_obj), "-o", str(tmp_path / "o.vdb"), "--voxel-size", "1e20"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode != 0 and "more than 1e+06 times the mesh's longest side" in done.stderr
    assert not (tmp_path / "o.vdb").exists()
