# SPDX-License-Identifier: GPL-3.0-or-later
# Colour and normal voxels of the GL methods (triangle, fragment, hybrid; llvmpipe here and in
# CI) against the cpu method's: the GPU clips each (voxel, triangle) pair the passes find in
# double and the host sums the pieces with the cpu's code, so the grids must agree voxel for
# voxel. The cpu itself is checked against the numpy oracle in test_attributes.py.
#
# Tolerance: the GPU reads each vertex as an integer cell plus a float fraction (the binary
# passes' input), the cpu in double, so the corners differ by up to 2^-25 voxel; the pieces'
# areas and centroids come back as floats (relative error 2^-24). Both move a piece's weight
# and its barycentrics by ~1e-7 relative; with colours and normals in [-1, 1] a voxel's mean
# moves by a few 1e-7, and float output rounding adds 6e-8. 2e-5 leaves a wide margin over
# that and is still 50x below one 8-bit colour step (the differences the test must catch:
# a piece lost, counted twice or given another triangle's weight, move means by > 1e-3).
import numpy as np
import pytest

import hyvox

GL_METHODS = ("triangle", "fragment", "hybrid")
ATOL = 2e-5


def by_voxel(ijk, dims):
    ijk = np.asarray(ijk, dtype=np.int64)
    return (ijk[:, 0] * dims[1] + ijk[:, 1]) * dims[2] + ijk[:, 2]


def assert_same_attributes(gl, cpu, names):
    assert gl.dims == cpu.dims
    assert np.array_equal(gl.coords(), cpu.coords()), "the GL method set other voxels than the cpu"
    assert gl.stats["attribute_voxels_unreached"] == 0
    got, expected = gl.attributes(), cpu.attributes()
    assert sorted(got) == sorted(expected)
    for name in names:
        assert got[name].shape[0] == gl.voxel_count
        np.testing.assert_allclose(got[name], expected[name], rtol=0, atol=ATOL, err_msg=name)


def assert_deterministic(run):
    first, second = run(), run()
    for name, values in first.attributes().items():
        assert np.array_equal(values, second.attributes()[name]), f"{name} differs between two runs"


@pytest.fixture(scope="module")
def spot_vcolor(mesh_dir):
    return hyvox.read_mesh(mesh_dir / "spot_vcolor.ply", attributes=True)


@pytest.mark.parametrize("method", GL_METHODS)
def test_vertex_colours_and_normals_equal_the_cpu(spot_vcolor, method):
    v, t, attrs = spot_vcolor
    colors = (attrs["colors"][:, :3] * 255).round().astype(np.uint8)

    def run(m=method):
        return hyvox.voxelize(v, t, resolution=48, method=m, colors=colors, attributes="color,normal")

    gl = run()
    assert_same_attributes(gl, run("cpu"), ("color", "normal"))
    assert gl.attributes()["color"].std(axis=0).min() > 0.05  # not flat: a wrong weighting would show
    assert_deterministic(run)


@pytest.mark.parametrize("method", GL_METHODS)
def test_texture_equals_the_cpu(mesh_dir, method):
    v, t, attrs = hyvox.read_mesh(mesh_dir / "spot_uv.ply", attributes=True)
    png = mesh_dir / "spot_texture.png"

    def run(m=method):
        return hyvox.voxelize(v, t, resolution=40, method=m, uvs=attrs["uvs"], texture=png, attributes="color")

    gl = run()
    assert_same_attributes(gl, run("cpu"), ("color",))
    assert gl.attributes()["color"].std(axis=0).min() > 0.05
    assert_deterministic(run)


@pytest.mark.parametrize("method", GL_METHODS)
def test_bunny_part_with_smooth_normals_equals_the_cpu(bunny, method):
    # The bunny's ears: long thin triangles across many voxels; per-vertex normals given.
    v, t = bunny
    v = np.asarray(v, dtype=np.float64)
    t = np.asarray(t)
    top = v[:, 1].max() - 0.3 * np.ptp(v[:, 1])
    part = t[np.all(v[t][:, :, 1] > top, axis=1)]
    assert 1000 < len(part) < 30000, len(part)
    normals = np.zeros_like(v)
    faces = np.cross(v[part[:, 1]] - v[part[:, 0]], v[part[:, 2]] - v[part[:, 0]])
    for corner in range(3):
        np.add.at(normals, part[:, corner], faces)

    def run(m=method, mode="conservative"):
        return hyvox.voxelize(
            v, part, resolution=64, method=m, mode=mode, normals=normals.astype(np.float32), attributes="normal"
        )

    assert_same_attributes(run(), run("cpu"), ("normal",))
    assert_same_attributes(run(mode="thin"), run("cpu", mode="thin"), ("normal",))


@pytest.mark.parametrize("method", GL_METHODS)
def test_palette_and_alpha_on_a_made_mesh_equal_the_cpu(method):
    # Two triangles meeting inside voxels, one lying on voxel planes (x = 2), one crossing
    # them at a slant, each with its own palette colour and alpha; tiny voxels around the
    # shared edge get pieces of both.
    v = np.array([[2.0, 0.2, 0.3], [2.0, 3.7, 0.6], [2.0, 1.9, 3.8], [0.3, 0.4, 0.1], [3.9, 3.1, 3.3]])
    t = np.array([[0, 1, 2], [3, 4, 2]])
    palette = np.array([[1.0, 0.25, 0.0, 0.5], [0.0, 0.5, 1.0, 1.0]])

    def run(m=method):
        return hyvox.voxelize(
            v,
            t,
            voxel_size=0.25,
            origin=(0, 0, 0),
            bounds=((0, 0, 0), (4, 4, 4)),
            method=m,
            material_ids=[0, 1],
            palette=palette,
            attributes="color,normal",
        )

    gl = run()
    assert_same_attributes(gl, run("cpu"), ("color", "alpha", "normal"))
    mixed = np.all(np.abs(gl.attributes()["color"] - palette[:, :3][:, None]).max(axis=2) > 1e-3, axis=0)
    assert mixed.sum() > 10  # voxels where the two colours are averaged
    assert_deterministic(run)


def test_tiles_and_gl_slabs_do_not_change_the_values(spot_vcolor):
    v, t, attrs = spot_vcolor
    colors = attrs["colors"][:, :3]
    whole = hyvox.voxelize(v, t, resolution=48, method="hybrid", colors=colors, attributes="color")
    tiled = hyvox.voxelize(
        v, t, resolution=48, method="hybrid", colors=colors, attributes="color", tile_size=16, gl_tile_bytes=2 * 2 * 64
    )  # one 8-voxel slab of a 16³ tile
    assert tiled.stats["tiles"] > 1 and tiled.stats["hybrid"]["tiles"] > tiled.stats["tiles"]
    assert np.array_equal(whole.coords(), tiled.coords())
    assert np.array_equal(whole.attributes()["color"], tiled.attributes()["color"])


def test_the_pair_list_grows_until_every_piece_fits():
    # The pair list's first guess is 8 pairs per triangle, at least 2^16: four large triangles
    # over a fine grid overflow it many times over, and the tile is run again with room for
    # all. A dropped pair would leave voxels unreached or off the cpu's values.
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float32)
    t = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    normals = v - 0.25
    gl = hyvox.voxelize(v, t, resolution=160, method="triangle", normals=normals, attributes="normal")
    cpu = hyvox.voxelize(v, t, resolution=160, method="cpu", normals=normals, attributes="normal")
    assert gl.stats["attribute_pieces"] > 1 << 16
    # The same pieces but for touches the two clips round differently (the diagonal face
    # passes through lattice points).
    assert abs(gl.stats["attribute_pieces"] - cpu.stats["attribute_pieces"]) < 1e-3 * cpu.stats["attribute_pieces"]
    assert_same_attributes(gl, cpu, ("normal",))


@pytest.mark.parametrize("method", GL_METHODS)
def test_progress_and_cancel_during_a_gl_attribute_run(spot_vcolor, method):
    v, t, attrs = spot_vcolor
    extra = dict(resolution=48, method=method, tile_size=16, colors=attrs["colors"][:, :3], attributes="color,normal")
    seen = []
    hyvox.voxelize(v, t, progress=seen.append, **extra)
    assert seen == sorted(seen) and seen[-1] == 100 and len(set(seen)) > 3
    # Cancelled as soon as the first tile reports: the run stops with Cancelled, not a result.
    token = hyvox.CancelToken()

    def cancel_after_first_tile(percent):
        if percent > 0:
            token.cancel()

    with pytest.raises(hyvox.Cancelled):
        hyvox.voxelize(v, t, cancel=token, progress=cancel_after_first_tile, **extra)
    assert token.cancelled and not token.running


def test_a_tile_whose_pairs_exceed_the_list_is_run_as_halves(spot_vcolor):
    # A pair list (20 bytes a piece) with room for half the pieces cannot hold the one bit
    # tile's pairs, so the tile is halved until each part's pairs fit; the values stay the same.
    v, t, attrs = spot_vcolor
    extra = dict(resolution=48, method="triangle", colors=attrs["colors"][:, :3], attributes="color,normal")
    whole = hyvox.voxelize(v, t, **extra)
    assert whole.stats["hybrid"]["tiles"] == 1
    halved = hyvox.voxelize(v, t, gl_pair_list_bytes=20 * whole.stats["attribute_pieces"] // 2, **extra)
    assert halved.stats["hybrid"]["tiles"] >= 2
    assert np.array_equal(whole.coords(), halved.coords())
    for name in ("color", "normal"):
        assert np.array_equal(whole.attributes()[name], halved.attributes()[name])
    # A list too small for one 8-voxel slab's pairs cannot be halved further: a clear error.
    with pytest.raises(hyvox.ResourceError, match="pairs in one 8-voxel slab, more than the 3 that fit"):
        hyvox.voxelize(v, t, gl_pair_list_bytes=64, **extra)
