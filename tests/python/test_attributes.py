# SPDX-License-Identifier: GPL-3.0-or-later
# Attribute voxels (colour, alpha, normal) of the exact methods against the numpy oracle of
# the definition (attribute_oracle.py): same voxels as the density, same values.
import numpy as np
import pytest

import hyvox
from attribute_oracle import CANCELLED_NORMAL_LENGTH, load_texture, srgb_to_linear, voxel_attributes

EXACT = ("cpu", "reference")


def by_voxel(ijk, dims):
    ijk = np.asarray(ijk, dtype=np.int64)
    return (ijk[:, 0] * dims[1] + ijk[:, 1]) * dims[2] + ijk[:, 2]


def compare(grid, oracle_ijk, oracle, *, atol, names=("color", "normal")):
    """The grid's attribute voxels are exactly its density voxels and the oracle's, with values within atol."""
    ijk = grid.coords()
    got = grid.attributes()
    keys, oracle_keys = by_voxel(ijk, grid.dims), by_voxel(oracle_ijk, grid.dims)
    order = np.argsort(keys)
    assert np.array_equal(keys[order], oracle_keys), "voxels differ from the oracle's"
    assert grid.stats["attribute_voxels_unreached"] == 0
    for name in names:
        assert got[name].shape[0] == len(ijk) == grid.voxel_count
        value, expected = got[name][order], oracle[name]
        if name == "normal" and "normal_length" in oracle:
            # Means rounding puts within a factor 2 of the cancelled-normal line (zero below
            # it) may fall on either side; a cancelled normal (opposite faces of a thin wall)
            # is zero in both, compared below like any other.
            near_line = np.abs(np.log2(np.maximum(oracle["normal_length"], 1e-300) / CANCELLED_NORMAL_LENGTH)) < 1
            assert near_line.sum() <= max(3, 1e-3 * len(ijk)), near_line.sum()
            value, expected = value[~near_line], expected[~near_line]
        np.testing.assert_allclose(value, expected, rtol=0, atol=atol, err_msg=name)


@pytest.fixture(scope="module")
def spot_vcolor(mesh_dir):
    return hyvox.read_mesh(mesh_dir / "spot_vcolor.ply", attributes=True)


@pytest.mark.parametrize("method", EXACT)
@pytest.mark.parametrize("resolution", [32, 96])
def test_vertex_colours_and_normals_match_the_oracle(spot_vcolor, method, resolution):
    v, t, attrs = spot_vcolor
    encoded = (attrs["colors"][:, :3] * 255).round().astype(np.uint8)  # the file's bytes
    grid = hyvox.voxelize(v, t, resolution=resolution, method=method, colors=encoded, attributes=("color", "normal"))
    ijk, oracle = voxel_attributes(
        v, t, grid.origin, grid.voxel_size, grid.dims, colors=srgb_to_linear(encoded / 255.0)
    )
    compare(grid, ijk, oracle, atol=1e-5)
    assert "alpha" not in grid.attributes()
    # The colour is not flat: the test could tell a wrong weighting.
    assert grid.attributes()["color"].std(axis=0).min() > 0.05


def test_thin_mode_values_are_the_same_definition_on_fewer_voxels(spot_vcolor):
    # Thin voxels are a subset of the conservative ones; each keeps the value over the whole
    # surface in its box.
    v, t, attrs = spot_vcolor
    encoded = (attrs["colors"][:, :3] * 255).round().astype(np.uint8)
    grid = hyvox.voxelize(v, t, resolution=48, mode="thin", colors=encoded, attributes="color,normal")
    ijk, oracle = voxel_attributes(v, t, grid.origin, grid.voxel_size, grid.dims, colors=srgb_to_linear(encoded / 255))
    oracle_keys, keys = by_voxel(ijk, grid.dims), by_voxel(grid.coords(), grid.dims)
    assert len(keys) < 0.8 * len(oracle_keys)
    rows = np.searchsorted(oracle_keys, keys)
    assert np.array_equal(oracle_keys[rows], keys)
    for name in ("color", "normal"):
        np.testing.assert_allclose(grid.attributes()[name], oracle[name][rows], atol=1e-5)


def test_file_colours_are_taken_as_srgb(spot_vcolor):
    # Mesh colours read from a file (bytes / 255) go through the same sRGB decoding.
    v, t, attrs = spot_vcolor
    from_bytes = hyvox.voxelize(
        v, t, resolution=32, colors=(attrs["colors"][:, :3] * 255).round().astype(np.uint8), attributes="color"
    )
    linear = hyvox.voxelize(
        v, t, resolution=32, colors=srgb_to_linear(attrs["colors"][:, :3]).astype(np.float32), attributes="color"
    )
    np.testing.assert_allclose(from_bytes.attributes()["color"], linear.attributes()["color"], atol=1e-6)


@pytest.mark.parametrize("method", EXACT)
def test_texture_matches_the_oracle(mesh_dir, method):
    v, t, attrs = hyvox.read_mesh(mesh_dir / "spot_uv.ply", attributes=True)
    png = mesh_dir / "spot_texture.png"
    grid = hyvox.voxelize(v, t, resolution=64, method=method, uvs=attrs["uvs"], texture=png, attributes="color")
    ijk, oracle = voxel_attributes(
        v, t, grid.origin, grid.voxel_size, grid.dims, uvs=attrs["uvs"], texture=load_texture(png)
    )
    compare(grid, ijk, oracle, atol=2 / 255, names=("color",))
    assert grid.attributes()["color"].std(axis=0).min() > 0.05


def test_sponza_crop_matches_the_oracle(mesh_dir):
    v, t, attrs = hyvox.read_mesh(mesh_dir / "sponza_crytek_262k_vcolor.ply.gz", attributes=True)
    # A piece of the atrium (columns, arches, floor): the triangles with every corner in a box.
    lo, hi = np.array([-20.0, 5.0, -10.0]), np.array([-14.0, 11.0, -4.0])
    inside = np.all((v[t] >= lo) & (v[t] <= hi), axis=(1, 2))
    crop = t[inside]
    assert 500 < len(crop) < 20000, len(crop)
    encoded = (attrs["colors"][:, :3] * 255).round().astype(np.uint8)
    grid = hyvox.voxelize(v, crop, resolution=64, colors=encoded, attributes=("color", "normal"))
    ijk, oracle = voxel_attributes(
        v, crop, grid.origin, grid.voxel_size, grid.dims, colors=srgb_to_linear(encoded / 255.0)
    )
    compare(grid, ijk, oracle, atol=1e-5)


def hand_made(method, **sources):
    return hyvox.voxelize(
        sources.pop("v"),
        sources.pop("t"),
        voxel_size=1.0,
        origin=(0, 0, 0),
        bounds=((0, 0, 0), (2, 2, 2)),
        method=method,
        **sources,
    )


@pytest.mark.parametrize("method", EXACT)
def test_two_triangles_meeting_inside_one_voxel(method):
    v = np.array([[0.1, 0.1, 0.5], [0.7, 0.1, 0.5], [0.1, 0.7, 0.5], [0.7, 0.1, 0.5], [0.9, 0.9, 0.5], [0.1, 0.7, 0.5]])
    t = np.array([[0, 1, 2], [3, 4, 5]])
    palette = np.array([[1.0, 0, 0, 1.0], [0, 0, 1.0, 0.5]])
    grid = hand_made(method, v=v, t=t, material_ids=[0, 1], palette=palette, attributes="color,normal")
    red, blue = 0.18 + 1e-6, 0.3 + 1e-6
    assert grid.coords().tolist() == [[0, 0, 0]]
    got = grid.attributes()
    np.testing.assert_allclose(got["color"][0], [red / (red + blue), 0, blue / (red + blue)], atol=1e-6)
    np.testing.assert_allclose(got["alpha"][0], (red + 0.5 * blue) / (red + blue), atol=1e-6)
    np.testing.assert_allclose(np.abs(got["normal"][0]), [0, 0, 1], atol=1e-6)
    # The oracle agrees, per vertex colours standing in for the palette.
    ijk, oracle = voxel_attributes(v, t, (0, 0, 0), 1.0, grid.dims, colors=palette[[0, 0, 0, 1, 1, 1]])
    np.testing.assert_allclose(got["alpha"], oracle["alpha"], atol=1e-6)


@pytest.mark.parametrize("method", EXACT)
def test_triangles_through_voxel_corners(method):
    # Planes through lattice points (z = (x + 2y) / 6 at 4 voxels per unit): the methods' exact
    # tests mark boxes the triangle meets in one corner, which a clip can lose to rounding;
    # the margin fallback finds them, in the methods and the oracle alike.
    v = np.array([[0, 0, 0], [3, 0, 0.5], [0, 3, 1], [3, 3, 3]], dtype=np.float32)
    t = np.array([[0, 1, 2], [1, 3, 2]])
    palette = np.array([[1.0, 0.5, 0.0, 0.25], [0.0, 0.5, 1.0, 1.0]])
    grid = hyvox.voxelize(
        v, t, resolution=12, method=method, attributes="color,normal", material_ids=[0, 1], palette=palette
    )
    assert grid.stats["attribute_leaves_rounded"] > 0 and grid.stats["attribute_voxels_unreached"] == 0
    # The oracle takes per-vertex colours: the triangles get corners of their own.
    v2 = v[[0, 1, 2, 1, 3, 2]]
    t2 = np.array([[0, 1, 2], [3, 4, 5]])
    colors = palette[[0, 0, 0, 1, 1, 1]]
    ijk, oracle = voxel_attributes(v2, t2, grid.origin, grid.voxel_size, grid.dims, colors=colors, voxels=grid.coords())
    compare(
        grid,
        ijk,
        {"color": oracle["color"], "alpha": oracle["alpha"][:, None], "normal": oracle["normal"]},
        atol=1e-5,
        names=("color", "normal"),
    )
    keys = np.argsort(by_voxel(grid.coords(), grid.dims))
    np.testing.assert_allclose(grid.attributes()["alpha"][keys], oracle["alpha"], atol=1e-5)


@pytest.mark.parametrize("method", EXACT)
def test_triangle_on_a_voxel_face(method):
    v = np.array([[0.2, 0.2, 1.0], [0.8, 0.2, 1.0], [0.2, 0.8, 1.0], [1.9, 1.9, 1.9]])
    t = np.array([[0, 1, 2]])
    colors = np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1], [0, 0, 0]], dtype=np.float32)
    grid = hand_made(method, v=v, t=t, colors=colors, attributes="color,normal", face_normals=np.array([[0, 0, 2.0]]))
    assert sorted(grid.coords().tolist()) == [[0, 0, 0], [0, 0, 1]]
    got = grid.attributes()
    np.testing.assert_allclose(got["color"], np.full((2, 3), 1 / 3), atol=1e-6)
    np.testing.assert_allclose(got["normal"], [[0, 0, 1], [0, 0, 1]], atol=1e-6)


def test_cpu_slab_sweep_equals_the_reference_box_clipping(spot_vcolor):
    # cpu cuts each triangle slab by slab, reference clips it box by box: the same pieces, whose
    # corners round differently (a few ulp in double), so the means may differ in the last bit
    # of their float. A piece lost or counted twice moves a mean by far more than 1e-6.
    v, t, attrs = spot_vcolor
    cpu, reference = (
        hyvox.voxelize(v, t, resolution=64, method=m, colors=attrs["colors"][:, :3], attributes="color,normal")
        for m in EXACT
    )
    assert np.array_equal(cpu.coords(), reference.coords())
    assert cpu.stats["attribute_pieces"] == reference.stats["attribute_pieces"]
    for name in ("color", "normal"):
        np.testing.assert_allclose(cpu.attributes()[name], reference.attributes()[name], rtol=0, atol=1e-6)


def test_threads_do_not_change_the_values(spot_vcolor):
    v, t, attrs = spot_vcolor
    results = [
        hyvox.voxelize(v, t, resolution=48, threads=n, colors=attrs["colors"][:, :3], attributes="color,normal")
        for n in (1, 3)
    ]
    for name in ("color", "normal"):
        assert np.array_equal(results[0].attributes()[name], results[1].attributes()[name])


def test_tiles_do_not_change_the_values(spot_vcolor):
    v, t, attrs = spot_vcolor
    whole, tiled = (
        hyvox.voxelize(v, t, resolution=48, tile_size=size, colors=attrs["colors"][:, :3], attributes="color")
        for size in (0, 16)
    )
    assert whole.stats["tiles"] == 1 and tiled.stats["tiles"] > 1
    assert np.array_equal(whole.coords(), tiled.coords())
    assert np.array_equal(whole.attributes()["color"], tiled.attributes()["color"])


@pytest.mark.parametrize(
    "sources, message",
    [
        ({}, "needs a colour source"),
        ({"texture": np.zeros((4, 4, 3), np.uint8)}, "needs the mesh's UVs"),
        ({"material_ids": [0, 3, 0, 0], "palette": [[1.0, 0, 0]]}, "material id 3"),
        ({"colors": np.zeros((3, 3), np.float32)}, "one row per vertex"),
        ({"colors": np.full((4, 3), np.nan, np.float32)}, "NaN"),
        ({"texture": "/nonexistent/texture.png", "uvs": np.zeros((4, 2))}, "cannot open texture"),
    ],
)
def test_bad_attribute_input_is_a_clear_error(tetrahedron, sources, message):
    v, t = tetrahedron
    with pytest.raises(ValueError, match=message):
        hyvox.voxelize(v, t, resolution=8, attributes="color", **sources)


@pytest.mark.parametrize("value", ["colour", "color,colour", ("color", "colour")])
def test_unknown_attribute_is_refused(tetrahedron, value):
    v, t = tetrahedron
    with pytest.raises(
        ValueError, match="unknown attributes 'colour' in 'color,colour'|unknown attributes 'colour' in 'colour'"
    ):
        hyvox.voxelize(v, t, resolution=8, attributes=value)


@pytest.mark.parametrize("method", hyvox.METHODS)
def test_every_method_computes_attributes(tetrahedron, method):
    v, t = tetrahedron
    grid = hyvox.voxelize(v, t, resolution=8, attributes="normal", method=method)
    assert len(grid.attributes()["normal"]) == grid.voxel_count > 0


def test_attributes_in_either_spelling(tetrahedron):
    # The comma list and a sequence of names are one set: the same run, the schema's text back.
    v, t = tetrahedron
    as_text = hyvox.voxelize(v, t, resolution=8, attributes="normal,color", colors=np.ones((4, 3)))
    as_names = hyvox.voxelize(v, t, resolution=8, attributes=["color", "normal"], colors=np.ones((4, 3)))
    assert as_text.stats["options"]["attributes"] == as_names.stats["options"]["attributes"] == "color,normal"
    for name in ("color", "normal"):
        np.testing.assert_array_equal(as_text.attributes()[name], as_names.attributes()[name])
    with pytest.raises(TypeError, match="attributes must be a comma list of color, normal, sdf"):
        hyvox.voxelize(v, t, resolution=8, attributes=("color", 3))


def test_a_texture_too_large_is_refused(tmp_path, tetrahedron):
    from PIL import Image

    path = tmp_path / "wide.png"
    Image.new("RGB", (8193 * 8, 1024)).save(path)
    v, t = tetrahedron
    with pytest.raises(ValueError, match="more than the limit"):
        hyvox.voxelize(v, t, resolution=8, attributes="color", uvs=np.zeros((4, 2)), texture=path)


@pytest.mark.parametrize(
    "mode, pixel, expected",
    [
        ("RGB", (200, 100, 50), [200 / 255, 100 / 255, 50 / 255, None]),
        ("RGBA", (200, 100, 50, 64), [200 / 255, 100 / 255, 50 / 255, 64 / 255]),
        ("L", 128, [128 / 255] * 3 + [None]),
        ("I;16", 40000, [40000 / 65535] * 3 + [None]),  # 16-bit: its own precision, sRGB like 8-bit
    ],
)
def test_png_texture_kinds_decode_srgb(tmp_path, tetrahedron, mode, pixel, expected):
    # A flat texture: every voxel takes its one colour, sRGB-decoded (alpha as stored).
    from PIL import Image

    path = tmp_path / "flat.png"
    Image.new(mode, (5, 3), pixel).save(path)
    v, t = tetrahedron
    uvs = np.array([[0, 0], [1, 0], [0.3, 0.9], [2.5, -1.5]])  # wrapping UVs too
    got = hyvox.voxelize(v, t, resolution=6, attributes="color", uvs=uvs, texture=path).attributes()
    np.testing.assert_allclose(
        got["color"], np.broadcast_to(srgb_to_linear(expected[:3]), got["color"].shape), atol=1e-6
    )
    if expected[3] is None:
        assert "alpha" not in got
    else:
        np.testing.assert_allclose(got["alpha"], expected[3], atol=1e-6)


# The exact methods: tessellation's points land unevenly on the two sides of a voxel, so its
# estimate of a cancelled normal is a short vector, not zero.
@pytest.mark.parametrize("method", [m for m in hyvox.METHODS if m != "tessellation"])
def test_a_two_sided_wall_has_no_normal(method):
    # Opposite faces inside one voxel cancel: by the definition the mean normal is zero, not a
    # direction rounding picks (which differed between methods on Sponza's two-sided walls).
    # A slanted sheet of jittered triangles, and the same sheet facing the other way with each
    # triangle's corners rotated, so that every piece's area rounds differently on each side.
    rng = np.random.default_rng(11)
    n = 8
    u, v = np.meshgrid(np.arange(n + 1), np.arange(n + 1), indexing="ij")
    uv = (np.stack([u.ravel(), v.ravel()], axis=1) + rng.uniform(-0.3, 0.3, ((n + 1) ** 2, 2))) / n
    frame = np.array([[0.83, 0.21, 0.37], [-0.29, 0.91, 0.17]])
    vertices = uv @ frame + np.array([0.1, 0.2, 0.3])
    corner = (np.arange(n)[:, None] * (n + 1) + np.arange(n)[None, :]).ravel()
    front = np.concatenate(
        [
            np.stack([corner, corner + n + 1, corner + n + 2], axis=1),
            np.stack([corner, corner + n + 2, corner + 1], axis=1),
        ]
    ).astype(np.uint32)
    back = front[:, [2, 1, 0]][:, [1, 2, 0]]  # reversed, then rotated
    colour = np.array([0.2, 0.5, 0.8], dtype=np.float32)
    colors = np.tile(colour, (len(vertices), 1))
    grid = hyvox.voxelize(
        vertices,
        np.concatenate([front, back]),
        resolution=24,
        method=method,
        colors=colors,
        attributes=("color", "normal"),
    )
    got = grid.attributes()
    assert grid.voxel_count > 200
    assert np.all(got["normal"] == 0), np.count_nonzero(np.any(got["normal"] != 0, axis=1))
    np.testing.assert_allclose(got["color"], np.broadcast_to(colour, got["color"].shape), atol=1e-5)
    # One side alone keeps its direction: the sheet's unit normal in every voxel.
    one_side = hyvox.voxelize(vertices, front, resolution=24, method=method, attributes=("normal",))
    normal = np.cross(frame[0], frame[1])
    normal /= np.linalg.norm(normal)
    np.testing.assert_allclose(np.abs(one_side.attributes()["normal"] @ normal), 1, atol=1e-5)
