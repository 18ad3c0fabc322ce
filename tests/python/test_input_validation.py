# SPDX-License-Identifier: GPL-3.0-or-later
# numpy input is checked at the boundary: clear ValueErrors, never a crash.
import numpy as np
import pytest

import hyvox


def test_package_surface():
    for name in hyvox.__all__:
        assert hasattr(hyvox, name), name
    assert hyvox.METHODS[:2] == ("cpu", "reference")
    assert hyvox.MODES == ("conservative", "thin", "solid")
    assert issubclass(hyvox.ResourceError, RuntimeError)
    assert issubclass(hyvox.BackendError, RuntimeError)
    assert issubclass(hyvox.Cancelled, Exception) and not issubclass(hyvox.Cancelled, RuntimeError)


@pytest.mark.parametrize(
    "vertices, message",
    [
        (np.zeros((4, 3), dtype=np.int32), "float32 or float64"),
        (np.zeros((4, 3), dtype=np.float16), "float32 or float64"),
        (np.zeros((4, 2), dtype=np.float32), r"shape \(N, 3\)"),
        (np.zeros(12, dtype=np.float32), r"shape \(N, 3\)"),
        (np.zeros((4, 3, 1), dtype=np.float32), r"shape \(N, 3\)"),
    ],
)
def test_bad_vertices(tetrahedron, vertices, message):
    _, triangles = tetrahedron
    with pytest.raises(ValueError, match=message):
        hyvox.voxelize(vertices, triangles, resolution=8)


@pytest.mark.parametrize(
    "triangles, message",
    [
        (np.zeros((4, 3), dtype=np.float32), "integer dtype"),
        (np.zeros((4, 3), dtype=bool), "integer dtype"),
        (np.zeros((4, 4), dtype=np.int32), r"shape \(M, 3\)"),
        (np.array([[0, 1, -2]]), "negative"),
        (np.array([[0, 1, 2**33]]), "too large"),
        (np.array([[0, 1, 7]], dtype=np.uint32), "refers to vertex 7"),
    ],
)
def test_bad_triangles(tetrahedron, triangles, message):
    vertices, _ = tetrahedron
    with pytest.raises(ValueError, match=message):
        hyvox.voxelize(np.asarray(vertices, dtype=np.float32), triangles, resolution=8)


# Blender stores an infinite coordinate as the largest float; every front door refuses it as
# it refuses Inf: the module, and the CLI on a mesh file that holds it.
@pytest.mark.parametrize("value", [3.4028235e38, -3.4028235e38, 3.4e38, float("inf")])
def test_float_max_is_refused_like_inf(tetrahedron, cli, tmp_path, value):
    import subprocess

    vertices, triangles = tetrahedron
    bad = np.array(vertices, dtype=np.float32)
    bad[2, 2] = value
    with pytest.raises(ValueError, match="vertex 2 has a non-finite coordinate"):
        hyvox.voxelize(bad, triangles, resolution=8)
    mesh = tmp_path / "bad.obj"
    mesh.write_text(
        "".join(f"v {x!r} {y!r} {z!r}\n" for x, y, z in bad.tolist())
        + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in np.asarray(triangles).tolist())
    )
    out = tmp_path / "out.vdb"
    done = subprocess.run([str(cli), "voxelize", str(mesh), "-o", str(out)], capture_output=True, text=True, timeout=60)
    # (the reader numbers the vertices in the order the faces use them)
    assert done.returncode == 1 and "has a non-finite coordinate" in done.stderr, done.stderr
    assert not out.exists()
    below = np.array(vertices, dtype=np.float32)
    below[2, 2] = np.nextafter(np.float32(3.4e38), np.float32(0))  # still a number: accepted
    hyvox.voxelize(below, triangles, resolution=8)


def test_bad_values_and_options(tetrahedron):
    vertices, triangles = tetrahedron
    nan = np.array(vertices, dtype=np.float32)
    nan[2, 1] = np.nan
    with pytest.raises(ValueError, match="non-finite"):
        hyvox.voxelize(nan, triangles)
    huge = np.array(vertices, dtype=np.float64) * 1e300  # inf once in float32
    with pytest.raises(ValueError, match="non-finite"):
        hyvox.voxelize(huge, triangles)
    with pytest.raises(ValueError, match="empty"):
        hyvox.voxelize(np.zeros((0, 3), np.float32), np.zeros((0, 3), np.uint32))
    with pytest.raises(ValueError, match="degenerate"):
        hyvox.voxelize(vertices, [[0, 0, 1]])
    with pytest.raises(ValueError, match="unknown mode"):
        hyvox.voxelize(vertices, triangles, mode="thick")
    with pytest.raises(ValueError, match="unknown method"):
        hyvox.voxelize(vertices, triangles, method="magic")
    with pytest.raises(ValueError, match="resolution"):
        hyvox.voxelize(vertices, triangles, resolution=0)
    with pytest.raises(ValueError, match="origin"):
        hyvox.voxelize(vertices, triangles, origin=(0, 0))
    with pytest.raises(hyvox.ResourceError, match="memory budget"):
        hyvox.voxelize(vertices, triangles, resolution=4096, memory_budget_mib=1)
    with pytest.raises(TypeError):
        hyvox.voxelize(vertices, triangles, cancel=object())


def test_float64_and_int64_are_converted(bunny):
    vertices, triangles = bunny
    expected = hyvox.voxelize(vertices, triangles, resolution=64)
    converted = hyvox.voxelize(vertices.astype(np.float64), triangles.astype(np.int64), resolution=64)
    assert converted.dims == expected.dims and converted.origin == expected.origin
    assert np.array_equal(converted.coords(), expected.coords())
    big_endian = hyvox.voxelize(vertices.astype(">f4"), triangles.astype(">u4"), resolution=64)
    assert np.array_equal(big_endian.coords(), expected.coords())
    # Non-contiguous views and plain lists are accepted too.
    strided = np.zeros((len(vertices), 6), np.float32)
    strided[:, ::2] = vertices
    from_views = hyvox.voxelize(strided[:, ::2], np.asfortranarray(triangles), resolution=64)
    assert np.array_equal(from_views.coords(), expected.coords())


def test_list_input_and_grid_properties(tetrahedron):
    vertices, triangles = tetrahedron
    grid = hyvox.voxelize(vertices, triangles, resolution=8, padding=1)
    assert grid.dims == (10, 10, 10)
    assert grid.voxel_size == pytest.approx(1 / 8)
    assert grid.origin == pytest.approx((-1 / 8,) * 3)
    coords = grid.coords()
    assert coords.dtype == np.int32 and coords.shape == (grid.voxel_count, 3) == (len(grid), 3)
    assert coords.min() >= 0 and (coords.max(axis=0) < grid.dims).all()
    centres = grid.world_centres()
    assert centres.dtype == np.float64
    np.testing.assert_allclose(centres, np.asarray(grid.origin) + (coords + 0.5) * grid.voxel_size)
    dense = grid.to_dense()
    assert dense.shape == grid.dims and dense.sum() == grid.voxel_count
    assert dense[tuple(coords.T)].all()
    ijk, values = grid.counts()
    assert ijk.shape == (0, 3) and values.shape == (0,)
    stats = grid.stats
    assert stats["voxel_count"] == grid.voxel_count
    assert stats["triangles"] == {"input": 4, "used": 4, "degenerate": 0}
    assert stats["dims"] == list(grid.dims) and stats["method"] == "cpu" and stats["mode"] == "conservative"
    assert "voxelize" in stats["timings_ms"]
    assert "VoxelGrid" in repr(grid)


def test_degenerate_triangles_are_counted(tetrahedron):
    vertices, triangles = tetrahedron
    grid = hyvox.voxelize(vertices, triangles + [[1, 1, 2], [0, 1, 3]], resolution=8)
    assert grid.stats["triangles"] == {"input": 6, "used": 5, "degenerate": 1}


def test_read_mesh(mesh_dir, tmp_path):
    vertices, triangles = hyvox.read_mesh(mesh_dir / "spider_messy.ply")
    assert vertices.dtype == np.float32 and vertices.shape == (762, 3)
    assert triangles.dtype == np.uint32 and triangles.shape == (1368, 3)
    _, _, attrs = hyvox.read_mesh(str(mesh_dir / "spot_uv.ply"), attributes=True)
    assert set(attrs) == {"uvs"} and attrs["uvs"].shape == (3225, 2)
    _, _, attrs = hyvox.read_mesh(mesh_dir / "spot_vcolor.ply", attributes=True)
    assert set(attrs) == {"colors"} and attrs["colors"].shape == (2930, 4)
    assert 0 <= attrs["colors"].min() and attrs["colors"].max() <= 1
    with pytest.raises(ValueError, match="No such file"):
        hyvox.read_mesh(tmp_path / "missing.ply")
    (tmp_path / "bad.obj").write_text("this is not a mesh\n")
    with pytest.raises(ValueError, match="bad.obj"):
        hyvox.read_mesh(tmp_path / "bad.obj")


def test_vertex_attribute_checks(tetrahedron):
    vertices, triangles = tetrahedron
    with pytest.raises(ValueError, match=r"uvs must have shape \(N, 2\)"):
        hyvox.voxelize(vertices, triangles, uvs=np.zeros((4, 3)))
    with pytest.raises(ValueError, match="uvs must have one row per vertex"):
        hyvox.voxelize(vertices, triangles, uvs=np.zeros((3, 2)))
    with pytest.raises(ValueError, match="normals must be float32 or float64"):
        hyvox.voxelize(vertices, triangles, normals=np.zeros((4, 3), dtype=np.int8))
    bad = np.zeros((4, 3))
    bad[1, 1] = np.inf
    with pytest.raises(ValueError, match="non-finite normal"):
        hyvox.voxelize(vertices, triangles, normals=bad)
    # Valid attributes change nothing for the exact methods.
    plain = hyvox.voxelize(vertices, triangles, resolution=8)
    with_attrs = hyvox.voxelize(vertices, triangles, resolution=8, uvs=np.zeros((4, 2)), normals=np.ones((4, 3)))
    assert np.array_equal(plain.coords(), with_attrs.coords())


@pytest.mark.filterwarnings("ignore::hyvox.IgnoredOptionWarning")  # other methods' options on purpose
def test_every_option_reaches_the_native_options(tetrahedron):
    # The GL and tessellation options are ignored by cpu, but must be accepted and mapped.
    vertices, triangles = tetrahedron
    grid = hyvox.voxelize(
        vertices,
        triangles,
        resolution=8,
        voxel_size=None,
        mode="thin",
        method="cpu",
        padding=1,
        threads=1,
        origin=(-0.5, -0.5, -0.5),
        bounds=((-0.5, -0.5, -0.5), (1.5, 1.5, 1.5)),
        memory_budget_mib=1024,
        gl_device="software",
        shader_dir="",
        hybrid_cutoff=2.0,
        tess_gamma=1.5,
        pn_triangles=True,
        displacement_image="",
        displacement_strength=0.1,
        displacement_midlevel=0.5,
        displacement_pixels=np.zeros((4, 4)),
        tess_counts=False,
    )
    assert grid.mode == "thin" and grid.method == "cpu"
    assert grid.voxel_size == pytest.approx(0.25) and grid.dims == (10, 10, 10)  # 2 / 8, plus padding
    assert grid.origin == pytest.approx((-0.75, -0.75, -0.75))
    with pytest.raises(ValueError, match="displacement_pixels"):
        hyvox.voxelize(vertices, triangles, displacement_pixels=np.zeros(4))


def test_tessellation_options_take_effect():
    # Each option must change what the tessellation method does, so a binding that dropped
    # or swapped one fails here (the cpu call above ignores them all).
    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], np.float32)
    t = np.array([[0, 1, 2], [0, 2, 3]], np.uint32)
    uvs = v[:, :2].copy()
    normals = np.tile(np.float32([0, 0, 1]), (4, 1))
    bounds = ((0, 0, -0.5), (1, 1, 0.5))

    def run(normals=normals, **kw):
        return hyvox.voxelize(
            v,
            t,
            resolution=16,
            method="tessellation",
            gl_device="software",
            bounds=bounds,
            uvs=uvs,
            normals=normals,
            **kw,
        )

    flat = run()
    assert flat.voxel_count == 16 * 16 and len(flat.counts()[0]) == flat.voxel_count  # counts on by default
    assert len(run(tess_counts=False).counts()[0]) == 0
    assert run(tess_gamma=3.0).stats["tessellation"]["points"] > flat.stats["tessellation"]["points"]
    # A ramp height image lifts the square by up to `strength` (0.25 = 4 voxels) at u = 1.
    ramp = np.tile(np.linspace(0.0, 1.0, 8, dtype=np.float32), (8, 1))
    lifted = run(displacement_pixels=ramp, displacement_strength=0.25, displacement_midlevel=0.0)
    assert lifted.coords()[:, 2].max() >= flat.coords()[:, 2].max() + 3
    # Normals leaning outwards make the PN-triangles bulge upwards; flat ones do not.
    dome = np.hstack([v[:, :2] - 0.5, np.ones((4, 1), np.float32)])
    assert run(dome, pn_triangles=True).coords()[:, 2].max() > flat.coords()[:, 2].max()
    assert np.array_equal(run(dome).to_dense(), flat.to_dense())
    # A midlevel equal to every height leaves the square where it was.
    still = run(
        displacement_pixels=np.full((8, 8), 0.5, np.float32), displacement_strength=0.25, displacement_midlevel=0.5
    )
    assert np.array_equal(still.to_dense(), flat.to_dense())


def test_gl_devices_lists_the_software_device():
    # Mesa's llvmpipe is always there on the test machines (libegl-mesa0); a GPU adds more.
    devices = hyvox.gl_devices()
    assert any(d["software"] for d in devices), devices
    for d in devices:
        assert set(d) == {"index", "name", "software"}
    # Each listed index is a valid device choice for the GL methods.
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=np.float32)
    t = np.array([[0, 1, 2]], dtype=np.uint32)
    software = next(d for d in devices if d["software"])
    grid = hyvox.voxelize(v, t, resolution=4, method="hybrid", gl_device=str(software["index"]))
    # The same voxels as the cpu method, not just as many (a count alone could hide a shift).
    cpu = hyvox.voxelize(v, t, resolution=4, method="cpu")
    assert grid.voxel_count == cpu.voxel_count > 0
    assert np.array_equal(grid.to_dense(), cpu.to_dense())
